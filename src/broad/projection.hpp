// The sampling projection, typed: world space -> the broad phase's sampling space
// (x, y in [0, 1] across the image, depth in [kDepthNear, kDepthNear + kDepthSpan]) as the
// gpu::Projection every shader reads. The one place that builds it on the host (the basis
// of a direction, the fit to bounds, a caller's region) and inverts it (kept boxes back to
// world space for the multi-axis union). fit.comp.glsl computes the same fit on the GPU
// from the bounds it measured; tests/gpu/projection_tests.cpp checks the two agree.
//
// Rows u, v, d of the basis are orthonormal, so the projection's rows are orthogonal with
// scales 1/size (image) and kDepthSpan/depth (depth): the inverse needs no matrix solve.
#pragma once

#include <array>

#include "common/broadphase.h"

namespace vkcollide::passes {

// Orthonormal image axes u, v and the unit direction d, with u x v = d (so outward faces
// seen along d are front-facing). Precondition: direction finite and non-zero.
struct ProjectionBasis {
    std::array<float, 3> u{}, v{}, d{};
};
ProjectionBasis projectionBasis(const std::array<float, 3>& direction);

// An axis-aligned box in basis coordinates (u, v, d): min then max.
struct BasisBounds {
    std::array<float, 3> lo{}, hi{};
};
// The extent of a world box (min x, y, z, max x, y, z) along the basis axes.
BasisBounds boundsInBasis(const ProjectionBasis& basis, const std::array<float, 6>& world_box);
// Bounds as the bounds pass stores them in gpu::Header::bounds (order-preserving uints).
BasisBounds boundsFromHeader(const gpu::Header& header);

// The fit of fit.comp.glsl: a square image over the bounds' u, v extent grown by `margin`
// (relative, each side), centred; depth range to [kDepthNear, kDepthNear + kDepthSpan].
// An empty extent counts as 1. Epsilons are in world units (stored in normalised depth).
gpu::Projection fitProjection(const ProjectionBasis& basis, const BasisBounds& bounds, float margin, float open_epsilon,
                              float closed_epsilon);
// A caller's world box, sampled without margin: the fit of its corners' extent.
gpu::Projection regionProjection(const ProjectionBasis& basis, const std::array<float, 6>& region, float open_epsilon,
                                 float closed_epsilon);

// Sampling-space point of a world point (the shaders' toSampling), in float.
std::array<float, 3> toSampling(const gpu::Projection& projection, const std::array<float, 3>& world);

// The world AABB of a sampling-space box (min x, y, depth then max): the box's points are
// sum over rows a of unit_a * (s_a - offset_a) / scale_a, so the AABB is the sum of the
// three segments' AABBs. In double; no padding.
std::array<double, 6> samplingBoxToWorld(const gpu::Projection& projection, const std::array<double, 3>& lo,
                                         const std::array<double, 3>& hi);
// World width of the image (1 / scale of the x row).
double imageWidth(const gpu::Projection& projection);

}  // namespace vkcollide::passes
