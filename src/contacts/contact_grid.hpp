// The contact stage's host geometry: which object pairs are candidates (closed, allowed,
// world boxes overlapping), the grid of rays over where their boxes overlap, the fixed-
// point scale of the GPU sums, and the sums turned back into world-space contacts.
// Host only (no device); contact_stage.cpp uses it between its two submissions and after.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "broad/projection.hpp"
#include "contacts/contacts.h"

namespace vkcollide::passes {

// One candidate pair's sums, in world units.
struct StageContact {
    std::uint32_t a = 0, b = 0;      // run indices, a < b
    double volume = 0;
    std::array<double, 3> normal{};  // unit, from a into b; zero when undefined
    double depth = 0;
    std::array<double, 3> point{};   // centroid (volume > 0) or the middle of the boxes' overlap
};

struct ContactCandidates {
    std::vector<std::array<std::uint32_t, 2>> pairs;  // a < b, sorted
    std::vector<std::array<double, 3>> middles;       // middle of each pair's box overlap
    std::array<double, 6> region{};                   // union of the box overlaps (min, max)
};

// Pairs a < b of objects with `closed[i]` set whose world boxes (min x, y, z, max x, y, z;
// min > max: no box) overlap, touching included, and that `may_collide` allows (empty:
// all). A sweep along x: O(n log n + overlapping pairs).
ContactCandidates findContactCandidates(std::span<const std::array<float, 6>> boxes, std::span<const std::uint8_t> closed,
                                        const std::function<bool(std::uint32_t, std::uint32_t)>& may_collide);

// Square pixels over `region` seen along `direction`: `resolution` rays across the longer
// side, the grid centred on the region, depth measured from the region's middle.
struct ContactGrid {
    ProjectionBasis basis;
    double h = 1;                      // pixel side, world units
    std::array<double, 3> origin{};    // grid origin along u, v, d (world units)
    std::uint32_t width = 1, height = 1;
    double depth_pixels = 1;           // the region's extent along d, in pixels
};
ContactGrid fitContactGrid(const std::array<float, 3>& direction, const std::array<double, 6>& region, std::uint32_t resolution);
// Fills params.grid (world -> grid rows), width, height and fixed_scale, for rays with at
// most `layers` hits each.
void writeGridParams(const ContactGrid& grid, std::uint32_t layers, gpu::ContactsParams& io_params);
// The pair's sums in world units: volume, centroid, normal and depth; false when no ray
// sampled a volume.
// The float of an order-preserving uint (the shaders' orderedFromFloat).
float orderedToFloat(std::uint32_t u);

bool contactFromSums(const gpu::ContactsPair& sums, const ContactGrid& grid, float fixed_scale, StageContact& out);

}  // namespace vkcollide::passes
