#include "common/lent_device.hpp"

#include <cstdio>

namespace samples {

int lendDevice(const CommonOptions& options, LentDevice& out) {
    out.engine = Engine::create({options.validation, options.device});
    auto context = vkcollide::Context::adopt(out.engine->adoptedDevice(), out.engine->messageCallback());
    if (!context) return fail(context.error());
    out.context = std::move(*context);
    auto world = vkcollide::CollisionWorld::create(*out.context, {.threads = options.threads});
    if (!world) return fail(world.error());
    out.world = std::move(*world);
    std::printf("device: %s\n", out.engine->deviceName().c_str());
    return 0;
}

}  // namespace samples
