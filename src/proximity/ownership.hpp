// Which vertices and edges each triangle owns, for the proximity pass (spirv/proximity.h,
// kProximityOwned*): a vertex's or an edge's owner is the lowest-numbered triangle of its
// mesh that has it, so each vertex-triangle and edge-edge pair is examined by exactly one
// candidate triangle pair. Host meshes only: computed once per mesh from its indices.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace vkcollide::proximity {

// One byte per triangle: bit k its vertex k, bit 3 + k its edge k (vertex k to k + 1 mod
// 3). A triangle that repeats an index owns the first occurrence only (and the first of
// two equal edges). `indices`: three per triangle, each below vertex_count.
std::vector<std::uint8_t> ownedPrimitives(std::span<const std::uint32_t> indices, std::uint32_t vertex_count);

}  // namespace vkcollide::proximity
