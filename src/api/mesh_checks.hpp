// Cheap host-side checks that a mesh declared closed (ObjectOptions::open false) is a
// closed surface facing outwards: boundary edges (the surface has holes) and the sign of
// its enclosed volume (inside out). Host code only, no Vulkan; the world keeps the results
// per host mesh and DetectStats::mesh_warnings reports them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "vkcollide/thread_pool.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide::mesh_checks {

// Edges (unordered vertex pairs) used by exactly one triangle: 0 for a closed surface.
// Topology only; edges of a triangle that repeats a vertex are not counted.
// O(T log T) time and 24 bytes per triangle of temporary memory. Precondition: every index
// in range (validated meshes).
std::uint64_t boundaryEdges(std::span<const std::uint32_t> indices);

// Six times the signed volume the triangles enclose (object units cubed; positive when
// their counter-clockwise sides face outwards), summed in double about the first vertex in
// fixed runs of kVolumeChunk triangles, added in order: the same on every executor and
// thread count. Meaningful for a closed surface only.
double signedVolume6(Executor& executor, std::span<const Float3> positions, std::span<const std::uint32_t> indices);
inline constexpr std::size_t kVolumeChunk = std::size_t{1} << 14;

// The determinant of a transform's 3x3 part: a mirroring transform (< 0) turns a surface
// inside out.
double determinant(const Transform3x4& t);

// The warning's text for an object with those findings ("" when none): what is wrong and
// what it does to a detection.
std::string describe(bool inside_out, std::uint64_t boundary_edges);

}  // namespace vkcollide::mesh_checks
