// The candidates of several sampling directions (DetectSettings::peeling.axes = 3) as one list for
// the narrow phase: one record per triangle, its box the union over the directions that
// kept it of the kept region mapped back to world space (a box in one direction's image
// space would mean nothing next to another's). A pair that any one direction would test has
// overlapping boxes here too, so the narrow phase sees at least the union of the
// directions' tests, each once.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"

namespace vkcollide::passes {

// A record's kept region (image box and depth extent, in the sampling space of
// `projection`) as a world AABB, cut to the triangle's own AABB and padded by kKeptBoxPad
// of the image width against rounding.
std::array<double, 6> keptWorldBox(const CandidateTriangle& record, const gpu::Projection& projection);

// Every direction's records united per (object, triangle), sorted; boxes and depths are
// world x, y and z rounded outward to float (box[0..3] = x0, y0, x1, y1; zmin, zmax = z).
std::vector<CandidateTriangle> uniteAxes(std::span<const BroadPhaseResult> runs);

}  // namespace vkcollide::passes
