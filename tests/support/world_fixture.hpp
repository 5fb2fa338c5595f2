// A world on the validated test Context, and a TestScene's objects added to it as host
// meshes (every step REQUIREd), for the API tests.
#pragma once

#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {

inline std::unique_ptr<CollisionWorld> makeWorld(ValidatedContext& ctx, WorldOptions options = {.threads = 2}) {
    auto w = CollisionWorld::create(ctx.context(), options);
    REQUIRE(w);
    return std::move(*w);
}

// The ids of the scene's objects, in order.
inline std::vector<ObjectId> addScene(CollisionWorld& world, const TestScene& scene) {
    std::vector<ObjectId> ids;
    for (const SceneObject& o : scene.objects) {
        auto id = world.addMesh(o.mesh, o.options);
        REQUIRE(id);
        ids.push_back(*id);
    }
    return ids;
}

}  // namespace vkcollide::test
