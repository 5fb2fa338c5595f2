// A world holding a test scene, on a validated context (GPU tests).
#pragma once

#include <memory>

#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {

// A world on ctx with the scene's objects added (REQUIREd), in order: ids 0, 1, ...
inline std::unique_ptr<CollisionWorld> sceneWorld(ValidatedContext& ctx, const TestScene& scene, unsigned threads = 2) {
    auto world = CollisionWorld::create(ctx.context(), {.threads = threads});
    REQUIRE(world);
    for (const SceneObject& o : scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    return std::move(*world);
}

}  // namespace vkcollide::test
