#include "broad/projection.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vkcollide::passes {
namespace {

float floatFromOrdered(std::uint32_t u) {
    const std::uint32_t bits = (u & 0x80000000u) ? (u & 0x7FFFFFFFu) : ~u;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

Eigen::Vector3d rowAxis(const gpu::vec4& row) { return {row.x, row.y, row.z}; }

std::array<float, 3> toFloat(const Eigen::Vector3d& x) {
    return {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2])};
}

}  // namespace

// In double, then rounded once: the helper axis is x unless d is close to it.
ProjectionBasis projectionBasis(const std::array<float, 3>& direction) {
    const Eigen::Vector3d d = Eigen::Vector3f(direction[0], direction[1], direction[2]).cast<double>().normalized();
    const Eigen::Vector3d a = std::fabs(d[0]) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d u = (a - d * a.dot(d)).normalized();
    const Eigen::Vector3d v = d.cross(u);
    return {toFloat(u), toFloat(v), toFloat(d)};
}

BasisBounds boundsInBasis(const ProjectionBasis& basis, const std::array<float, 6>& b) {
    const std::array<float, 3>* axes[3] = {&basis.u, &basis.v, &basis.d};
    BasisBounds out;
    for (int a = 0; a < 3; ++a) {
        const std::array<float, 3>& axis = *axes[a];
        for (int c = 0; c < 8; ++c) {
            const float p[3] = {(c & 1) ? b[3] : b[0], (c & 2) ? b[4] : b[1], (c & 4) ? b[5] : b[2]};
            const float dot = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
            out.lo[a] = c == 0 ? dot : std::min(out.lo[a], dot);
            out.hi[a] = c == 0 ? dot : std::max(out.hi[a], dot);
        }
    }
    return out;
}

BasisBounds boundsFromHeader(const gpu::Header& h) {
    BasisBounds out;
    for (int a = 0; a < 3; ++a) out.lo[a] = floatFromOrdered(h.bounds[a]), out.hi[a] = floatFromOrdered(h.bounds[a + 3]);
    return out;
}

// Float operations in fit.comp.glsl's order, so the host and the GPU round alike.
gpu::Projection fitProjection(const ProjectionBasis& basis, const BasisBounds& b, float margin, float open_epsilon,
                              float closed_epsilon) {
    float size = std::max(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]);
    if (!(size > 0)) size = 1;
    size *= 1.0f + 2.0f * margin;
    float depth = b.hi[2] - b.lo[2];
    if (!(depth > 0)) depth = 1;
    const std::array<float, 3>* image_axes[2] = {&basis.u, &basis.v};
    gpu::Projection p{};
    for (int a = 0; a < 2; ++a) {
        const float origin = 0.5f * (b.lo[a] + b.hi[a]) - 0.5f * size;
        const std::array<float, 3>& axis = *image_axes[a];
        p.row[a] = {axis[0] / size, axis[1] / size, axis[2] / size, -origin / size};
    }
    const float to_depth = gpu::kDepthSpan / depth;
    p.row[2] = {basis.d[0] * to_depth, basis.d[1] * to_depth, basis.d[2] * to_depth, gpu::kDepthNear - gpu::kDepthSpan * b.lo[2] / depth};
    p.world_to_depth = to_depth;
    p.open_epsilon = open_epsilon * to_depth;
    p.closed_epsilon = closed_epsilon * to_depth;
    return p;
}

gpu::Projection regionProjection(const ProjectionBasis& basis, const std::array<float, 6>& region, float open_epsilon,
                                 float closed_epsilon) {
    return fitProjection(basis, boundsInBasis(basis, region), 0.0f, open_epsilon, closed_epsilon);
}

std::array<float, 3> toSampling(const gpu::Projection& p, const std::array<float, 3>& w) {
    std::array<float, 3> s;
    for (int a = 0; a < 3; ++a) s[a] = p.row[a].x * w[0] + p.row[a].y * w[1] + p.row[a].z * w[2] + p.row[a].w;
    return s;
}

std::array<double, 6> samplingBoxToWorld(const gpu::Projection& p, const std::array<double, 3>& s_lo,
                                         const std::array<double, 3>& s_hi) {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3d r = rowAxis(p.row[a]);
        const double scale = r.norm();
        const double offset = p.row[a].w;
        for (int w = 0; w < 3; ++w) {
            const double unit = r[w] / scale;
            const double t0 = unit * (s_lo[a] - offset) / scale, t1 = unit * (s_hi[a] - offset) / scale;
            lo[w] += std::min(t0, t1);
            hi[w] += std::max(t0, t1);
        }
    }
    return {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
}

double imageWidth(const gpu::Projection& p) { return 1.0 / rowAxis(p.row[0]).norm(); }

}  // namespace vkcollide::passes
