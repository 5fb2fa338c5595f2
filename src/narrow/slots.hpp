// What the narrow phase knows about each candidate triangle once the input is ordered:
// "slots" 0..m-1 in canonical (object, triangle) order, each with its object, triangle,
// vertex indices and world vertices. The 80-byte record path reads them in place from
// the records (strided views); the lean record path and the pair path gather them from a
// TriangleSource into arrays (gatherSlots).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "narrow/parallel.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

using Index3 = std::uint32_t[3];
using Vertex3 = Float3[3];

// Element i of an array of T embedded in larger records: base + i * stride.
template <typename T>
struct Strided {
    const std::byte* base = nullptr;
    std::size_t stride = 0;

    Strided() = default;
    Strided(const T* first, std::size_t stride_bytes) : base(reinterpret_cast<const std::byte*>(first)), stride(stride_bytes) {}
    const T& operator[](std::size_t i) const noexcept { return *reinterpret_cast<const T*>(base + i * stride); }
};

// A record's box and depth extent: box[4], zmin, zmax as laid out in CandidateTriangle
// and CandidateRecord.
struct BoxZ {
    float x0, y0, x1, y1, z0, z1;
};

struct SlotData {
    Strided<std::uint32_t> object, triangle;
    Strided<Index3> vertex_index;
    Strided<Vertex3> v;
};

// The gathered form (lean and pair paths).
struct SlotTag {
    std::uint32_t object, triangle;
    std::uint32_t vertex_index[3];
};
struct SlotVertices {
    Float3 v[3];
};
SlotData slotView(const Buffer<SlotTag>& tags, const Buffer<SlotVertices>& vertices);

inline bool isFinite(const Float3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// World position of an object-space point: M * p in double, rounded once to float (the
// products of two floats are exact in double, so contracting them into FMAs changes
// nothing; the sums run in this order).
inline Float3 toWorld(const Transform3x4& m, const Float3& p) {
    const auto row = [&](int r) {
        return static_cast<float>(double(m[4 * r]) * p.x + double(m[4 * r + 1]) * p.y + double(m[4 * r + 2]) * p.z +
                                  double(m[4 * r + 3]));
    };
    return {row(0), row(1), row(2)};
}

// The object holding global id `id` (< source.totalTriangles()).
std::uint32_t objectOf(const TriangleSource& source, std::uint32_t id);

// Gathers slot s from the source: the triangle with global id ids[s] (ids ascending and
// below source.totalTriangles()). `table_keys` and `scratch` are scratch for the GPU
// table's (id, position) keys. Errors: the one of the lowest slot (an index out of range,
// a non-finite world vertex, a GPU-only triangle missing from the table) or a table id
// that repeats.
// `world` is scratch for whole meshes transformed at once: an object whose slots outnumber
// a third of its vertices gets every vertex transformed once instead of three per slot.
std::optional<Error> gatherSlots(const TriangleSource& source, const Buffer<std::uint32_t>& ids, Executor& executor,
                                 Buffer<SlotTag>& out_tags, Buffer<SlotVertices>& out_vertices,
                                 Buffer<std::uint64_t>& table_keys, Buffer<std::uint64_t>& scratch, Buffer<Float3>& world);

}  // namespace vkcollide::narrow
