// The public API (CollisionWorld) on the device, validation on: what detect() returns,
// the asynchronous form, object flags and filters, engine-owned GPU buffers (the errors
// bad input gets: validation_tests.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

#include "api/engine_copy.hpp"
#include "support/error_text.hpp"
#include "support/exact_reference.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scene_world.hpp"
#include "support/test_scenes.hpp"
#include "support/world_fixture.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

std::vector<TrianglePair> referencePairs(const TestScene& scene) {
    auto objects = scene.reference();
    auto ref = computeReferencePairs(objects);
    REQUIRE(ref);
    return *ref;
}

// The paper's method, whose statistics (rays, layers, records) these tests check; the
// reliable method has its own tests (reliable_tests.cpp).
DetectSettings fixedSettings(std::uint32_t resolution) {
    DetectSettings s;
    s.method = DetectMethod::Peeling;
    s.resolution = resolution;
    s.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    return s;
}

using test::mentions;

}  // namespace

TEST_CASE("detect() finds only exact pairs and reports the paper's statistics", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    auto result = world->detect(fixedSettings(256));
    REQUIRE(result);
    const auto cmp = comparePairs(result->pairs, referencePairs(*scene));
    CHECK(cmp.false_positives == 0);
    CHECK(cmp.recall > 0.95);
    const DetectStats& st = result->stats;
    CHECK(st.triangles == world->triangleCount());
    CHECK(st.objects == ids.size());
    CHECK(st.positive_tests == result->pairs.size());
    CHECK(st.triangle_tests >= st.positive_tests);
    CHECK(st.triangles_downloaded >= st.potentially_colliding_triangles);
    CHECK(st.triangles_downloaded < st.triangles);  // the far sphere and most surfaces are culled
    CHECK(st.collision_rays > 0);
    CHECK(st.peeling.layers == st.peeling.depth_complexity);
    CHECK_FALSE(st.peeling.layers_short);
    CHECK(st.resolution == 256);
    CHECK_FALSE(st.gpu_passes.empty());
    CHECK(st.sampling_ms > 0);
    CHECK(st.total_ms >= st.narrow_ms);
    // One response per colliding triangle, unit length or zero.
    std::size_t in_pairs = 0;
    for (const auto& r : result->responses) {
        in_pairs += r.partner_count;
        const double len = std::sqrt(double(r.direction.x) * r.direction.x + double(r.direction.y) * r.direction.y +
                                     double(r.direction.z) * r.direction.z);
        CHECK((len == 0.0 || std::abs(len - 1.0) < 1e-5));
    }
    CHECK(in_pairs == 2 * result->pairs.size());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("collision_rays returns the peeling detection's collision rays as world segments", "[api][gpu]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto world = sceneWorld(ctx, *scene);
    auto plain = world->detect(fixedSettings(128));
    REQUIRE(plain);
    CHECK_FALSE(plain->collision_rays);

    DetectSettings s = fixedSettings(128);
    s.peeling.collision_rays = true;
    auto result = world->detect(s);
    REQUIRE(result);
    CHECK(result->pairs == plain->pairs);  // the rays are read back, nothing else changes
    REQUIRE(result->collision_rays);
    const CollisionRays& rays = *result->collision_rays;
    REQUIRE(rays.segments.size() == result->stats.collision_rays);
    CHECK(rays.per_axis[0] == rays.segments.size());
    CHECK(rays.pixel_size > 0);
    // Every segment runs along the detection's direction.
    const auto d = *s.direction;
    const double dn = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
    for (const auto& [a, b] : rays.segments) {
        const double v[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        REQUIRE(len > 0);
        const double cosine = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / (len * dn);
        CHECK(std::abs(std::abs(cosine) - 1.0) < 1e-4);
    }

    // The reliable method samples no rays: refused by name.
    DetectSettings reliable;
    reliable.peeling.collision_rays = true;
    auto refused = world->detect(reliable);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(refused.error(), "collision_rays belongs to the peeling method"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("worlds on one Context share their pipelines", "[api][gpu]") {
    ValidatedContext ctx;
    const auto created = [&] {
        std::lock_guard lock(ctx.device().pipelines_mutex);
        return ctx.device().pipelines_created;
    };
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto a = sceneWorld(ctx, *scene);
    auto first = a->detect({});
    REQUIRE(first);
    const std::uint64_t after_a = created();
    CHECK(after_a > 0);

    // A second world on the Context, same method: no pipeline of its own.
    auto b = sceneWorld(ctx, *scene);
    auto second = b->detect({});
    REQUIRE(second);
    CHECK(second->pairs == first->pairs);
    CHECK(created() == after_a);
    // The other method's pipelines are made once, by whichever world needs them first.
    auto peeled = b->detect(fixedSettings(128));
    REQUIRE(peeled);
    const std::uint64_t after_peeling = created();
    CHECK(after_peeling > after_a);
    auto peeled_a = a->detect(fixedSettings(128));
    REQUIRE(peeled_a);
    CHECK(peeled_a->pairs == peeled->pairs);
    CHECK(created() == after_peeling);

    // A world that goes takes nothing from the other.
    b.reset();
    auto again = a->detect({});
    REQUIRE(again);
    CHECK(again->pairs == first->pairs);
    CHECK(created() == after_peeling);

    // With no world left the Context still holds them: a new world creates none.
    a.reset();
    auto c = sceneWorld(ctx, *scene);
    auto later = c->detect({});
    REQUIRE(later);
    CHECK(later->pairs == first->pairs);
    CHECK(created() == after_peeling);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a steady scene's later detections submit their command buffer again, with the same pairs", "[api][gpu]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto world = sceneWorld(ctx, *scene);
    std::vector<Result<DetectResult>> runs;
    for (int k = 0; k < 4; ++k) runs.push_back(world->detect());  // the reliable method, automatic settings
    for (const auto& r : runs) {
        REQUIRE(r);
        CHECK(r->pairs == runs[0]->pairs);
        CHECK(r->stats.host.reused_submissions <= r->stats.submissions);
    }
    CHECK(runs[0]->stats.host.reused_submissions == 0u);  // nothing recorded before
    CHECK(runs[3]->stats.host.reused_submissions == runs[3]->stats.submissions);
    CHECK(comparePairs(runs[3]->pairs, referencePairs(*scene)).recall == 1.0);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("submit()/collect() gives detect()'s pairs and guards the objects in flight", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = torusThroughBox();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    auto sync = world->detect(fixedSettings(128));
    REQUIRE(sync);
    REQUIRE(world->submit(fixedSettings(128)));
    CHECK(world->pending());
    // What the work in flight reads cannot change; a transform can (each detection keeps
    // the one it was submitted with: engine_sync_tests.cpp).
    auto blocked = world->setSelfCollision(ids[0], true);
    REQUIRE_FALSE(blocked);
    CHECK(mentions(blocked.error(), "setSelfCollision while a detection is in flight"));
    REQUIRE(world->setTransform(ids[0], scene->objects[0].options.transform));
    REQUIRE(world->submit(fixedSettings(128)));  // a second one in flight (pipelining)
    CHECK(world->inFlight() == 2);
    auto third = world->submit(fixedSettings(128));
    REQUIRE_FALSE(third);
    CHECK(mentions(third.error(), "kMaxInFlight"));
    for (int k = 0; k < 2; ++k) {
        auto async = world->collect();
        REQUIRE(async);
        CHECK(async->pairs == sync->pairs);
        CHECK(async->stats.peeling.layers == sync->stats.peeling.depth_complexity);  // the layers measured last time
    }
    CHECK_FALSE(world->pending());
    CHECK_FALSE(world->collect());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a deeper scene than predicted stays conservative and is reported", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto a = uvSphere(1.0f, 24, 12), b = uvSphere(0.6f, 24, 12);
    REQUIRE(a);
    REQUIRE(b);
    auto ia = world->addMesh(*a, {.name = "a"});
    REQUIRE(ia);
    REQUIRE(world->detect(fixedSettings(64)));  // depth complexity 2
    ObjectOptions inside;
    inside.name = "b";
    auto ib = world->addMesh(*b, inside);  // nested: 4 layers now
    REQUIRE(ib);
    REQUIRE(world->detect(fixedSettings(64)));  // measures again (objects changed): 4
    REQUIRE(world->setTransform(*ib, rotationY(0, {3, 0, 0})));
    REQUIRE(world->detect(fixedSettings(64)));  // 2 again
    REQUIRE(world->setTransform(*ib, rotationY(0, {0.5f, 0, 0})));
    REQUIRE(world->submit(fixedSettings(64)));  // predicts 2, the scene has 4
    auto r = world->collect();
    REQUIRE(r);
    CHECK(r->stats.peeling.layers == 2);
    CHECK(r->stats.peeling.depth_complexity == 4);
    CHECK(r->stats.peeling.layers_short);
    auto exact = world->detect(fixedSettings(64));
    REQUIRE(exact);
    CHECK_FALSE(exact->stats.peeling.layers_short);
    // Conservative: every pair the exact layers find is found with too few layers too.
    for (const auto& p : exact->pairs) CHECK(std::binary_search(r->pairs.begin(), r->pairs.end(), p));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("self-collision flag, pair filter, removal and vertex updates", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto tube = selfIntersectingTube();
    REQUIRE(tube);
    SceneObject t = tube->objects[0];
    t.options.self_collision = false;
    auto id = world->addMesh(t.mesh, t.options);
    REQUIRE(id);
    auto off = world->detect(fixedSettings(128));
    REQUIRE(off);
    CHECK(off->pairs.empty());
    REQUIRE(world->setSelfCollision(*id, true));
    auto on = world->detect(fixedSettings(128));
    REQUIRE(on);
    CHECK_FALSE(on->pairs.empty());
    for (const auto& p : on->pairs) CHECK((p.object_a == *id && p.object_b == *id));

    auto spheres = overlappingSpheres();
    REQUIRE(spheres);
    const auto ids = addScene(*world, *spheres);  // ids continue after the tube's
    REQUIRE(world->setPairFilter([&](ObjectId a, ObjectId b) { return !(a == ids[0] && b == ids[1]); }));
    auto filtered = world->detect(fixedSettings(128));
    REQUIRE(filtered);
    bool saw_a_c = false;
    for (const auto& p : filtered->pairs) {
        CHECK_FALSE((p.object_a == ids[0] && p.object_b == ids[1]));
        saw_a_c |= p.object_a == ids[0] && p.object_b == ids[2];
    }
    CHECK(saw_a_c);
    REQUIRE(world->setPairFilter({}));

    REQUIRE(world->removeObject(*id));
    CHECK_FALSE(world->removeObject(*id));
    auto removed = world->detect(fixedSettings(128));
    REQUIRE(removed);
    for (const auto& p : removed->pairs) CHECK(p.object_a != *id);

    // Move sphere-b far away by rewriting its vertices: its pairs disappear.
    std::vector<Float3> moved = spheres->objects[1].mesh.positions;
    for (Float3& p : moved) p.x += 10;
    REQUIRE(world->updateVertices(ids[1], moved));
    auto after = world->detect(fixedSettings(128));
    REQUIRE(after);
    for (const auto& p : after->pairs) CHECK((p.object_a != ids[1] && p.object_b != ids[1]));
    moved[3].y = std::numeric_limits<float>::quiet_NaN();
    auto nan = world->updateVertices(ids[1], moved);
    REQUIRE_FALSE(nan);
    CHECK(mentions(nan.error(), "sphere-b"));
    CHECK(mentions(nan.error(), "vertex 3"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("engine-owned GPU buffers give the host meshes' pairs", "[api][gpu]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto host_world = sceneWorld(ctx, *scene);
    auto expected = host_world->detect(fixedSettings(128));
    REQUIRE(expected);

    auto gpu_world = makeWorld(ctx);
    std::vector<EngineMesh> engine;
    for (std::size_t i = 0; i < scene->objects.size(); ++i) {
        // Mixed layouts: strided RGBA float positions with 16-bit indices, packed with 32-bit.
        const bool odd = i % 2 == 1;
        engine.push_back(engineCopy(ctx.device(), scene->objects[i].mesh, odd ? 32 : 12,
                                    odd ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32G32B32_SFLOAT, odd));
        REQUIRE(gpu_world->addGpuMesh(engine.back().desc, scene->objects[i].options));
    }
    auto got = gpu_world->detect(fixedSettings(128));
    REQUIRE(got);
    CHECK(got->pairs == expected->pairs);
    CHECK(got->stats.triangles_downloaded == expected->stats.triangles_downloaded);

    // The engine deforms a mesh on the GPU side: the next detection sees it.
    auto* v = static_cast<float*>(engine[1].vertices.mapped());
    for (std::uint32_t i = 0; i < engine[1].desc.vertex_count; ++i) v[i * 8] += 10.0f;
    engine[1].vertices.flush();
    auto deformed = gpu_world->detect(fixedSettings(128));
    REQUIRE(deformed);
    for (const auto& p : deformed->pairs) CHECK((p.object_a != 1 && p.object_b != 1));

    // Bad values only the GPU can see: with BadObjectPolicy::Fail the detection fails naming
    // the object and triangle (the default leaves the object out: tests/stability).
    DetectSettings strict = fixedSettings(128);
    strict.bad_objects = BadObjectPolicy::Fail;
    auto* idx = static_cast<std::uint32_t*>(engine[2].indices.mapped());
    const std::uint32_t saved = idx[7];
    idx[7] = engine[2].desc.vertex_count + 5;  // triangle 2
    engine[2].indices.flush();
    auto bad_index = gpu_world->detect(strict);
    REQUIRE_FALSE(bad_index);
    CHECK(bad_index.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(bad_index.error(), "sphere-c"));
    CHECK(mentions(bad_index.error(), "triangle 2 "));
    idx[7] = saved;
    engine[2].indices.flush();
    v = static_cast<float*>(engine[0].vertices.mapped());
    v[idx[0] * 3 + 1] = std::numeric_limits<float>::infinity();
    engine[0].vertices.flush();
    auto bad_vertex = gpu_world->detect(strict);
    REQUIRE_FALSE(bad_vertex);
    CHECK(mentions(bad_vertex.error(), "sphere-a"));
    CHECK(mentions(bad_vertex.error(), "NaN or infinite"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("automatic settings follow the scene", "[api][gpu]") {
    ValidatedContext ctx;
    auto cloth = clothThroughSphere();
    REQUIRE(cloth);
    auto world = sceneWorld(ctx, *cloth);
    const DetectSettings paper{.method = DetectMethod::Peeling};
    auto s = world->resolveSettings(paper);
    REQUIRE(s);
    // The cloth faces z; about four pixels per edge of the 40x40 cloth (3 / 40).
    CHECK(*s->direction == std::array<float, 3>{0, 0, 1});
    REQUIRE(s->resolution);
    CHECK(*s->resolution == 256);
    CHECK(*s->peeling.open_epsilon > 0);
    // Finer meshes ask for more rays.
    auto fine = clothThroughSphere(2.0f);
    REQUIRE(fine);
    auto fine_world = sceneWorld(ctx, *fine);
    auto fs = fine_world->resolveSettings(paper);
    REQUIRE(fs);
    CHECK(*fs->resolution == 2 * *s->resolution);
    auto r = world->detect(paper);
    REQUIRE(r);
    CHECK(r->stats.resolution == *s->resolution);
    CHECK(r->stats.settings_note.find("resolution 256") != std::string::npos);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// A world that held a raw Context pointer made every call that asked the
// Context for its device (detect's settings check, Coverage::Best, addGpuMesh's buffer
// check, resolveSettings) read freed memory once the Context was gone (ASan: heap
// use-after-free in detect.cpp and world.cpp). The world now holds the device itself.
TEST_CASE("a world used after its Context is destroyed: every call works as before", "[api][gpu][lifetime]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto world = sceneWorld(ctx, *scene);
    // An engine mesh made before the Context goes (its buffers keep the device alive too).
    EngineMesh engine = engineCopy(ctx.device(), scene->objects[0].mesh);
    DetectSettings peeling = fixedSettings(128);
    peeling.peeling.coverage = Coverage::Best;  // resolved from the device's features
    const auto reliable_before = world->detect({});
    REQUIRE(reliable_before);
    const auto peeling_before = world->detect(peeling);
    REQUIRE(peeling_before);
    CHECK(!reliable_before->pairs.empty());

    ctx.destroyContext();
    auto resolved = world->resolveSettings(peeling);
    REQUIRE(resolved);
    CHECK(resolved->peeling.coverage != Coverage::Best);
    auto reliable_after = world->detect({});
    REQUIRE(reliable_after);
    CHECK(reliable_after->pairs == reliable_before->pairs);
    auto peeling_after = world->detect(peeling);
    REQUIRE(peeling_after);
    CHECK(peeling_after->pairs == peeling_before->pairs);
    REQUIRE(world->submit({}));
    auto collected = world->collect();
    REQUIRE(collected);
    CHECK(collected->pairs == reliable_before->pairs);
    // Objects still come and go; an engine mesh's buffers are still checked on the device.
    auto shifted = scene->objects[1].options;
    shifted.transform[3] += 10.0f;
    auto added = world->addMesh(scene->objects[1].mesh, shifted);
    REQUIRE(added);
    auto gpu = world->addGpuMesh(engine.desc, {.name = "engine"});
    REQUIRE(gpu);
    GpuMeshDesc bad = engine.desc;
    bad.vertex_buffer_size *= 4;  // more than the buffer holds: found by asking the device
    auto refused = world->addGpuMesh(bad, {.name = "short"});
    REQUIRE(!refused);
    CHECK(refused.error().code() == ErrorCode::BufferTooSmall);
    REQUIRE(world->removeObject(*gpu));
    REQUIRE(world->removeObject(*added));
    auto again = world->detect({});
    REQUIRE(again);
    CHECK(again->pairs == reliable_before->pairs);
    world.reset();  // the last owner of the device but the engine buffers
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
