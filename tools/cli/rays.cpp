#include "cli/rays.hpp"

#include "broad/projection.hpp"
#include "detect/detection.hpp"
#include "mesh/mesh_upload.hpp"

namespace cli {

vkcollide::Result<CollisionRays> collisionRays(vkcollide::Context& context, const Scene& scene,
                                               const vkcollide::DetectSettings& s) {
    namespace passes = vkcollide::passes;
    std::vector<const vkcollide::HostMesh*> hosts;
    passes::MeshUploadOptions upload;
    for (const SceneObject& o : scene.objects) {
        hosts.push_back(&o.mesh);
        upload.open.push_back(o.options.open);
    }
    auto uploaded = passes::uploadMeshes(context.device(), hosts, upload);
    if (!uploaded) return uploaded.error();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) uploaded->meshes[i].transform = scene.objects[i].options.transform;

    // The settings as the API hands them to the broad phase (src/api/detect.cpp).
    passes::DetectionSettings d;
    d.broad.resolution = *s.resolution;
    d.broad.direction = *s.direction;
    d.broad.layer_cap = s.layer_cap;
    d.broad.dual = s.dual;
    d.broad.packing = s.packing;
    d.broad.backend = s.backend;
    d.broad.open_epsilon = s.open_epsilon.value_or(0.0f);
    d.broad.closed_epsilon = s.closed_epsilon;
    d.broad.coverage = s.coverage;
    d.broad.region = s.region;
    d.broad.keep_ray_image = true;
    d.axes = s.axes;
    d.bad_objects = s.bad_objects;
    auto detection = passes::Detection::create(context.device());
    if (!detection) return detection.error();
    if (auto ok = (*detection)->start(uploaded->meshes, d, true); !ok) return ok.error();
    auto result = (*detection)->collect();
    if (!result) return result.error();

    CollisionRays out;
    const std::uint32_t n = *s.resolution;
    for (std::size_t axis = 0; axis < result->axes.size() && axis < 3; ++axis) {
        const passes::BroadPhaseResult& b = result->axes[axis];
        if (axis == 0) out.pixel_size = static_cast<float>(passes::imageWidth(b.projection) / n);
        for (std::uint32_t p = 0; p < b.ray_image.size(); ++p) {
            if (!b.ray_image[p]) continue;
            // The ray through pixel (x, y)'s centre (finalize.comp.glsl: p = y * n + x), over
            // the sampled depth range.
            const double x = (p % n + 0.5) / n, y = (p / n + 0.5) / n;
            std::array<vkcollide::Float3, 2> seg;
            for (int end = 0; end < 2; ++end) {
                const std::array<double, 3> at{x, y, end == 0 ? vkcollide::gpu::kDepthNear : vkcollide::gpu::kDepthNear + vkcollide::gpu::kDepthSpan};
                const std::array<double, 6> w = passes::samplingBoxToWorld(b.projection, at, at);
                seg[end] = {static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2])};
            }
            out.segments.push_back(seg);
            ++out.per_axis[axis];
        }
    }
    return out;
}

}  // namespace cli
