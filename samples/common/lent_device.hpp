// What every sample sets up first: the engine, its device lent to vkcollide
// (Context::adopt) and the collision world on that device.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <memory>

#include "common/options.hpp"
#include "common/render.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"

namespace samples {

// In the order they are made; destroyed in reverse, the engine last.
struct LentDevice {
    std::unique_ptr<Engine> engine;
    std::unique_ptr<vkcollide::Context> context;
    std::unique_ptr<vkcollide::CollisionWorld> world;
};

// Creates the engine (options.validation, options.device), lends its device to a Context,
// creates the world (options.threads) and prints the device's name. Returns 0, or fail()'s
// status when vkcollide refuses; `out` keeps what was made, so that the engine outlives
// the message as it does in a sample's own scope.
int lendDevice(const CommonOptions& options, LentDevice& out);

}  // namespace samples
