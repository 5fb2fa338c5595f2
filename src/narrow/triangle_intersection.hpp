// Exact intersection tests for closed triangles and segments in 3D.
//
// All decisions come from exact orientation predicates (exact_predicates.hpp); there are
// no tolerances. Sets are closed: touching at a single point counts as intersecting.
// Degenerate inputs are allowed: a triangle whose vertices are collinear is treated as
// the segment they span (or a point), a segment with equal ends as a point.
#pragma once

#include <span>

#include "vkcollide/mesh.hpp"

namespace vkcollide::narrow {

// True when the closed triangles a and b share at least one point.
// Thread safety: pure function.
bool trianglesIntersect(std::span<const Float3, 3> a, std::span<const Float3, 3> b) noexcept;

// True when the closed segment [s0, s1] and the closed triangle t share a point.
bool segmentTriangleIntersect(const Float3& s0, const Float3& s1, std::span<const Float3, 3> t) noexcept;

// True when the closed segments [a0, a1] and [b0, b1] share a point.
bool segmentsIntersect(const Float3& a0, const Float3& a1, const Float3& b0, const Float3& b1) noexcept;

// True when p, q, r lie on one line (including coincident points).
bool collinear(const Float3& p, const Float3& q, const Float3& r) noexcept;

}  // namespace vkcollide::narrow
