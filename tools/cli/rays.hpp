// The collision rays of a detection, as world-space segments for --png --rays.
//
// The public API reports how many collision rays there were, not where: this file runs the
// broad phase (passes::Detection, vkcollide's internals) once more with the settings the
// detection resolved and the collision-ray image kept, and maps each collision ray's pixel
// centre back to world space through the projection that run sampled with. It is the only
// file of the tool that reaches below the public API; a public ray image (a DetectSettings
// switch) would replace it.
#pragma once

#include <array>
#include <vector>

#include "cli/scene.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"

namespace cli {

struct CollisionRays {
    // Each ray from where the sampled box begins along the direction to where it ends.
    std::vector<std::array<vkcollide::Float3, 2>> segments;
    float pixel_size = 0;  // world width of one ray's pixel (the first direction's)
    std::size_t per_axis[3] = {0, 0, 0};
};

// `resolved`: CollisionWorld::resolveSettings of the settings the detection used.
vkcollide::Result<CollisionRays> collisionRays(vkcollide::Context& context, const Scene& scene,
                                               const vkcollide::DetectSettings& resolved);

}  // namespace cli
