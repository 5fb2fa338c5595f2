// DetectSettings::peeling.collision_rays: the peeling method's collision-ray images, mapped back to
// world-space segments through the projection each direction sampled with.
#pragma once

#include <vector>

#include "broad/broad_phase_types.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

// `axes`: the detection's directions, each with its ray image kept; `resolution`: rays per side.
CollisionRays collisionRays(const std::vector<passes::BroadPhaseResult>& axes, std::uint32_t resolution);

}  // namespace vkcollide
