// The world's loops over a host mesh's positions, split over its Executor (host code only,
// no Vulkan): updateVertices' one loop (copy into the host copy and the upload buffer,
// finiteness, box) and the shape measurement behind the automatic settings (typical edge,
// area moment). Both give the same result on every executor and thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "vkcollide/thread_pool.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide::vertex_scans {

// What updateVertices learns of new positions in its one pass.
struct VertexScan {
    std::array<float, 6> box{};  // min x, y, z, max x, y, z (meaningful when finite)
    float max_abs = 0;           // largest |coordinate|
    bool finite = true;
    std::size_t first_bad = 0;   // !finite: the index of the first NaN or infinite vertex
};

// How the upload buffer is written (it may be write-combined device memory across the bus,
// written fastest in whole 64-byte lines: other cache misses in between compete for the
// buffers that combine the writes and may flush a line half-written):
//   Fused   each block of four vertices is stored to the host copy and the upload buffer
//           at once: one pass, the caller's array read once (the default);
//   Staged  per 12 KB step, the host copy first, then that step (still in L1) copied to the
//           upload buffer with no other miss in between.
// vkcollide_bench_frames times both on the device's upload memory.
enum class UploadWrites { Fused, Staged };

// Copies `in` to `out` (as many Float3s, host memory) and, when `upload` is not null, to
// `upload` (as many Float3s: the mapped upload buffer, only ever written, in whole 64-byte
// lines per thread when it is 64-byte aligned), and scans `in` (box, largest magnitude,
// first non-finite vertex) in the same pass. Chunks of at least kMinChunkVertices run on
// the executor's threads; the caller's thread alone below that. The result is exact (a
// min/max reduction) and names the same first bad vertex on every executor and thread
// count. Precondition: in.size() == out.size() >= 1; no overlap.
VertexScan copyAndScan(Executor& executor, std::span<const Float3> in, std::span<Float3> out, Float3* upload,
                       UploadWrites writes = UploadWrites::Fused);
inline constexpr std::size_t kMinChunkVertices = std::size_t{1} << 14;

// The shape of a host mesh for the automatic settings: the mean edge length and the sum over
// triangles of area * n n^T (xx, yy, zz, xy, xz, yz; object space), both from at most
// kShapeSampleTriangles triangles in evenly spaced blocks of kShapeBlock consecutive ones
// (the moment scaled to the whole mesh).
// Partial sums are formed over fixed runs of kShapeChunk sampled triangles and added in
// order, so the result does not depend on the executor. Precondition: every index is in
// range (validated meshes).
struct Shape {
    float edge_length = 0;
    std::array<double, 6> area_moment{};
    // The area of the triangles whose normal lies within about 1 degree of the object's
    // x, y or z axis (faces of an axis-aligned box; object space, scaled as the moment).
    std::array<double, 3> axis_area{};
};
// A triangle faces axis a (Shape::axis_area) where |n . a| >= this: within 1.15 degrees.
inline constexpr double kAxisFaceCos = 0.9998;
Shape measureShape(Executor& executor, std::span<const Float3> positions, std::span<const std::uint32_t> indices);
// Several meshes' shapes in one parallel loop (the executor's threads started once, not
// once per mesh: a detection of deforming meshes measures every one of them); out[i] is
// measureShape(meshes[i]) exactly. Precondition: out.size() == meshes.size().
struct ShapeMesh {
    std::span<const Float3> positions;
    std::span<const std::uint32_t> indices;
};
void measureShapes(Executor& executor, std::span<const ShapeMesh> meshes, std::span<Shape> out);
// copyAndScan and, in the same parallel loop (the executor's threads started once), the
// shape of the mesh with the new positions `in` and `indices`: when the scan finds every
// vertex finite, `shape` is measureShape(out, indices) bit for bit (same runs, same sums);
// otherwise it is left as it was.
VertexScan copyScanAndMeasure(Executor& executor, std::span<const Float3> in, std::span<Float3> out, Float3* upload,
                              std::span<const std::uint32_t> indices, Shape& shape, UploadWrites writes = UploadWrites::Fused);
inline constexpr std::size_t kShapeSampleTriangles = std::size_t{1} << 12;
inline constexpr std::size_t kShapeChunk = 512;
inline constexpr std::size_t kShapeBlock = 32;
static_assert(kShapeSampleTriangles % kShapeBlock == 0 && kShapeChunk % kShapeBlock == 0);

}  // namespace vkcollide::vertex_scans
