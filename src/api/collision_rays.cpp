#include "api/collision_rays.hpp"

#include "broad/projection.hpp"

namespace vkcollide {

CollisionRays collisionRays(const std::vector<passes::BroadPhaseResult>& axes, std::uint32_t resolution) {
    CollisionRays out;
    const std::uint32_t n = resolution;
    for (std::size_t axis = 0; axis < axes.size() && axis < out.per_axis.size(); ++axis) {
        const passes::BroadPhaseResult& b = axes[axis];
        if (axis == 0) out.pixel_size = static_cast<float>(passes::imageWidth(b.projection) / n);
        for (std::uint32_t p = 0; p < b.ray_image.size(); ++p) {
            if (!b.ray_image[p]) continue;
            // The ray through pixel (x, y)'s centre (finalize.comp.glsl: p = y * n + x), over
            // the sampled depth range.
            const double x = (p % n + 0.5) / n, y = (p / n + 0.5) / n;
            std::array<Float3, 2> segment;
            for (int end = 0; end < 2; ++end) {
                const double depth = end == 0 ? gpu::kDepthNear : gpu::kDepthNear + gpu::kDepthSpan;
                const std::array<double, 3> at{x, y, depth};
                const std::array<double, 6> w = passes::samplingBoxToWorld(b.projection, at, at);
                segment[end] = {static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2])};
            }
            out.segments.push_back(segment);
            ++out.per_axis[axis];
        }
    }
    return out;
}

}  // namespace vkcollide
