// The reliable method through the public API (the default), validation on: every pair the
// exact reference finds, at any resolution and direction, with host and engine meshes,
// transforms, edits between detections, submit()/collect(), bad engine meshes, the pair
// filter and self-collision; its statistics and automatic settings.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "api/engine_copy.hpp"
#include "support/error_text.hpp"
#include "support/exact_reference.hpp"
#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "support/world_fixture.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

std::vector<TrianglePair> reference(const std::vector<ReferenceObject>& objects) {
    auto ref = computeReferencePairs(objects, {.threads = 2});
    REQUIRE(ref);
    return *ref;
}

using test::mentions;

// Exactly the reference: nothing missed, nothing extra (the narrow phase is exact).
void requireExact(const DetectResult& r, const std::vector<TrianglePair>& ref, const std::string& what) {
    const PairComparison cmp = comparePairs(r.pairs, ref);
    INFO(what << ": " << cmp.true_positives << " of " << ref.size() << " found, " << cmp.false_positives << " spurious");
    CHECK(cmp.false_negatives == 0);
    CHECK(cmp.false_positives == 0);
}

// The README example: a host ball pushed through a flat engine cloth (2 x 2, in the xy
// plane) whose size the world is not told.
struct BallCloth {
    HostMesh cloth, ball;
    EngineMesh engine;
    Transform3x4 ball_at = rotationY(0.0f, {0.1f, -0.05f, 0.2f});
    std::vector<ReferenceObject> refs() const {
        return {{&ball, transformFrom3x4(ball_at), false}, {&cloth, kIdentityTransform, true}};
    }
};

BallCloth ballCloth(vk::Device& device) {
    BallCloth s;
    auto cloth = clothGrid(2.0f, 2.0f, 24, 24);
    auto ball = uvSphere(0.5f, 24, 12);
    REQUIRE(cloth);
    REQUIRE(ball);
    s.cloth = std::move(*cloth);
    s.ball = std::move(*ball);
    s.engine = engineCopy(device, s.cloth);
    return s;
}

}  // namespace

TEST_CASE("reliable: every pair of the test scenes at any resolution and direction, with its statistics", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto scenes = allTestScenes(0.5f);
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto world = makeWorld(ctx);
        for (const SceneObject& o : scene.objects) REQUIRE(world->addMesh(o.mesh, o.options));
        const auto ref = reference(scene.reference());
        REQUIRE_FALSE(ref.empty());
        auto automatic = world->detect();
        REQUIRE(automatic);
        requireExact(*automatic, ref, scene.name + ", automatic");
        const DetectStats& st = automatic->stats;
        CHECK(st.method == DetectMethod::Reliable);
        CHECK(mentions(st.settings_note, "method reliable"));
        CHECK(st.cells.candidate_cells > 0);
        CHECK(st.collision_rays == st.cells.candidate_cells);
        CHECK(st.cells.survivors >= ref.size());
        CHECK(st.cells.candidates >= st.cells.survivors);
        CHECK(st.triangles_downloaded == st.narrow.candidates);
        CHECK(st.positive_tests == automatic->pairs.size());
        CHECK(st.cells.gpu_triangles == 0);  // host meshes only
        CHECK(st.reliable.footprints_ms > 0);
        CHECK(st.reliable.pairing_ms > 0);
        CHECK(st.reliable.filtering_ms > 0);
        CHECK(st.peeling.depth_complexity == 0);
        for (std::uint32_t n : {1u, 7u, 100u}) {
            DetectSettings s;
            s.resolution = n;
            s.direction = std::array<float, 3>{0.3f, -0.55f, 0.8f};
            auto r = world->detect(s);
            REQUIRE(r);
            requireExact(*r, ref, scene.name + " at " + std::to_string(n) + " cells");
            CHECK(r->stats.resolution == n);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: README's ball through an engine cloth is found whole, and seen face-on once measured", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    BallCloth s = ballCloth(ctx.device());
    auto world = makeWorld(ctx);
    REQUIRE(world->addMesh(s.ball, {.name = "ball", .transform = s.ball_at}));
    REQUIRE(world->addGpuMesh(s.engine.desc, {.name = "cloth", .self_collision = true, .open = true}));
    const auto ref = reference(s.refs());
    REQUIRE(ref.size() > 40);
    auto first = world->detect();
    REQUIRE(first);
    requireExact(*first, ref, "first detection");
    CHECK(mentions(first->stats.settings_note, "not measured yet"));
    CHECK(first->stats.cells.gpu_triangles > 0);  // the cloth's triangles in pairs, with their vertices
    CHECK(first->stats.cells.gpu_triangles <= s.cloth.triangleCount());
    // From the second detection the cloth's extent is known: it faces z.
    auto second = world->detect();
    REQUIRE(second);
    requireExact(*second, ref, "second detection");
    CHECK(second->stats.direction == std::array<float, 3>{0, 0, 1});
    CHECK(mentions(second->stats.settings_note, "measured"));
    // The paper's method sees the cloth face-on too now (it found 0 of the pairs edge-on).
    auto paper = world->detect({.method = DetectMethod::Peeling});
    REQUIRE(paper);
    CHECK(paper->stats.direction == std::array<float, 3>{0, 0, 1});
    CHECK(comparePairs(paper->pairs, ref).recall > 0.8);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: host and engine meshes mixed, strides, 16-bit indices, transforms and edits", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres(0.6f);
    REQUIRE(scene);
    auto world = makeWorld(ctx);
    std::vector<EngineMesh> engine;
    std::vector<ObjectId> ids;
    for (std::size_t i = 0; i < scene->objects.size(); ++i) {
        const SceneObject& o = scene->objects[i];
        if (i % 2 == 0) {
            auto id = world->addMesh(o.mesh, o.options);
            REQUIRE(id);
            ids.push_back(*id);
            continue;
        }
        // Engine meshes: RGBA positions in 32-byte vertices with 16-bit indices, one with
        // its typical edge given.
        engine.push_back(engineCopy(ctx.device(), o.mesh, 32, VK_FORMAT_R32G32B32A32_SFLOAT, true));
        ObjectOptions options = o.options;
        options.typical_edge_length = i == 1 ? 0.1f : 0.0f;
        auto id = world->addGpuMesh(engine.back().desc, options);
        REQUIRE(id);
        ids.push_back(*id);
    }
    auto r = world->detect();
    REQUIRE(r);
    requireExact(*r, reference(scene->reference()), "mixed");
    CHECK(r->stats.cells.gpu_triangles > 0);
    // Move a host sphere (setTransform) and an engine one (its buffer), detect again.
    scene->objects[0].options.transform = rotationY(1.1f, {-0.2f, 0.1f, 0.1f});
    REQUIRE(world->setTransform(ids[0], scene->objects[0].options.transform));
    auto* v = static_cast<float*>(engine[0].vertices.mapped());
    for (std::uint32_t k = 0; k < engine[0].desc.vertex_count; ++k) v[k * 8] += 0.3f;
    engine[0].vertices.flush();
    for (Float3& p : scene->objects[1].mesh.positions) p.x += 0.3f;
    r = world->detect();
    REQUIRE(r);
    requireExact(*r, reference(scene->reference()), "after setTransform and an engine write");
    // New vertices of a host mesh, then its removal.
    for (Float3& p : scene->objects[2].mesh.positions) p.y -= 0.25f;
    REQUIRE(world->updateVertices(ids[2], scene->objects[2].mesh.positions));
    r = world->detect();
    REQUIRE(r);
    requireExact(*r, reference(scene->reference()), "after updateVertices");
    REQUIRE(world->removeObject(ids[0]));
    r = world->detect();
    REQUIRE(r);
    std::vector<ReferenceObject> rest = scene->reference();
    rest.erase(rest.begin());
    std::vector<TrianglePair> expected = reference(rest);
    for (TrianglePair& p : expected) ++p.object_a, ++p.object_b;  // ids continue after the removed one
    requireExact(*r, expected, "after removeObject");
    // submit()/collect() gives detect()'s pairs.
    REQUIRE(world->submit());
    CHECK(world->pending());
    auto async = world->collect();
    REQUIRE(async);
    CHECK(async->pairs == r->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: bad engine meshes are left out or fail the detection, naming object and triangle", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres(0.5f);
    REQUIRE(scene);
    auto world = makeWorld(ctx);
    std::vector<EngineMesh> engine;
    for (const SceneObject& o : scene->objects) {
        engine.push_back(engineCopy(ctx.device(), o.mesh));
        REQUIRE(world->addGpuMesh(engine.back().desc, o.options));
    }
    std::vector<ReferenceObject> without_b = scene->reference();
    without_b.erase(without_b.begin() + 1);
    std::vector<TrianglePair> expected = reference(without_b);
    for (TrianglePair& p : expected) {
        if (p.object_a >= 1) ++p.object_a;
        if (p.object_b >= 1) ++p.object_b;
    }
    SECTION("an index out of range") {
        auto* idx = static_cast<std::uint32_t*>(engine[1].indices.mapped());
        idx[7] = engine[1].desc.vertex_count + 5;  // triangle 2
        engine[1].indices.flush();
    }
    SECTION("a finite coordinate beyond the reliable method's 2^62") {
        auto* v = static_cast<float*>(engine[1].vertices.mapped());
        const auto* idx = static_cast<const std::uint32_t*>(engine[1].indices.mapped());
        v[idx[6] * 3 + 2] = 1e30f;  // a vertex of triangle 2
        engine[1].vertices.flush();
    }
    auto left_out = world->detect();
    REQUIRE(left_out);
    REQUIRE(left_out->excluded.size() == 1);
    CHECK(left_out->excluded[0].object == 1);
    CHECK(mentions(left_out->excluded[0].error.message(), "sphere-b"));
    CHECK(mentions(left_out->excluded[0].error.message(), "triangle"));
    requireExact(*left_out, expected, "the others, as if it were absent");
    auto failed = world->detect({.bad_objects = BadObjectPolicy::Fail});
    REQUIRE_FALSE(failed);
    CHECK(failed.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(failed.error().message(), "sphere-b"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: host meshes beyond 2^62 are refused by name, and the pair filter is kept on the GPU", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres(0.5f);
    REQUIRE(scene);
    auto world = makeWorld(ctx);
    std::vector<ObjectId> ids;
    for (const SceneObject& o : scene->objects) {
        auto id = world->addMesh(o.mesh, o.options);
        REQUIRE(id);
        ids.push_back(*id);
    }
    auto all = world->detect();
    REQUIRE(all);
    int calls = 0;
    REQUIRE(world->setPairFilter([&](ObjectId a, ObjectId b) {
        ++calls;
        return !(a == ids[0] && b == ids[1]);
    }));
    auto filtered = world->detect();
    REQUIRE(filtered);
    const int calls_first = calls;
    CHECK(calls_first == 6);  // every pair of the four objects, once
    for (const TrianglePair& p : filtered->pairs) CHECK_FALSE((p.object_a == ids[0] && p.object_b == ids[1]));
    std::vector<TrianglePair> expected;
    for (const TrianglePair& p : all->pairs)
        if (!(p.object_a == ids[0] && p.object_b == ids[1])) expected.push_back(p);
    CHECK(filtered->pairs == expected);
    CHECK(filtered->stats.cells.candidates < all->stats.cells.candidates);  // no GPU work for the filtered pair
    REQUIRE(world->detect());
    CHECK(calls == calls_first);  // answers kept: not called again
    REQUIRE(world->setPairFilter({}));

    HostMesh far = scene->objects[3].mesh;
    far.positions[0].x = 1e30f;
    auto id = world->addMesh(far, {.name = "astronomic"});
    REQUIRE(id);
    auto refused = world->detect();
    REQUIRE_FALSE(refused);
    CHECK(mentions(refused.error().message(), "astronomic"));
    CHECK(mentions(refused.error().message(), "2^62"));
    REQUIRE(world->detect({.method = DetectMethod::Peeling}));  // the paper's method takes it
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: self-collision and automatic settings", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto tube = selfIntersectingTube(0.7f);
    REQUIRE(tube);
    auto world = makeWorld(ctx);
    SceneObject t = tube->objects[0];
    t.options.self_collision = false;
    auto id = world->addMesh(t.mesh, t.options);
    REQUIRE(id);
    auto off = world->detect();
    REQUIRE(off);
    CHECK(off->pairs.empty());
    CHECK(off->stats.cells.candidates == 0);  // one object without self-collision: nothing to pair
    REQUIRE(world->setSelfCollision(*id, true));
    auto on = world->detect();
    REQUIRE(on);
    requireExact(*on, reference(tube->reference()), "self-intersecting tube");

    // About kCellsPerEdge cells per typical edge: twice as fine a mesh, about twice the cells.
    auto cloth = clothThroughSphere(), fine = clothThroughSphere(2.0f);
    REQUIRE(cloth);
    REQUIRE(fine);
    auto coarse_world = makeWorld(ctx), fine_world = makeWorld(ctx);
    for (const SceneObject& o : cloth->objects) REQUIRE(coarse_world->addMesh(o.mesh, o.options));
    for (const SceneObject& o : fine->objects) REQUIRE(fine_world->addMesh(o.mesh, o.options));
    auto s = coarse_world->resolveSettings(), fs = fine_world->resolveSettings();
    REQUIRE(s);
    REQUIRE(fs);
    CHECK(*s->direction == std::array<float, 3>{0, 0, 1});  // the cloth faces z
    CHECK(s->peeling.axes == 1);
    const double ratio = double(*fs->resolution) / double(*s->resolution);
    CHECK(ratio > 1.8);
    CHECK(ratio < 2.2);
    auto three = coarse_world->resolveSettings({.peeling = {.axes = 3}});
    REQUIRE(three);
    CHECK(three->peeling.axes == 1);  // one grid finds everything
    auto r = coarse_world->detect({.peeling = {.axes = 3}});
    REQUIRE(r);
    CHECK(r->stats.peeling.axes == 1);
    CHECK(mentions(r->stats.settings_note, "axes 1"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The grid per scene (DetectSettings::reliable.grid_tuning): Auto is On on a GPU and Off on
// a CPU implementation such as lavapipe (the device type, faked below); On, a
// scene's first detections try the neighbouring grids, each giving the exact pairs, the
// settings note says which grid ran, and a given resolution is kept.
TEST_CASE("reliable: the grid tuned per scene tries neighbouring grids, every one exact", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto scene = clothThroughSphere();
    REQUIRE(scene);
    auto world = makeWorld(ctx);
    for (const SceneObject& o : scene->objects) REQUIRE(world->addMesh(o.mesh, o.options));
    const auto expected = reference(scene->reference());
    auto plain = world->resolveSettings();
    REQUIRE(plain);
    CHECK(plain->reliable.grid_tuning == GridTuning::Off);
    {
        // The same world on a device that says it is a GPU: Auto turns the tuner on.
        VkPhysicalDeviceType& type = ctx.device().properties.deviceType;
        const VkPhysicalDeviceType was = type;
        type = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
        auto on_gpu = world->resolveSettings();
        type = was;
        REQUIRE(on_gpu);
        CHECK(on_gpu->reliable.grid_tuning == GridTuning::On);
        auto fixed_on_gpu = world->resolveSettings({.reliable = {.grid_tuning = GridTuning::Off}});
        REQUIRE(fixed_on_gpu);
        CHECK(fixed_on_gpu->reliable.grid_tuning == GridTuning::Off);
    }
    const DetectSettings tuned{.reliable = {.grid_tuning = GridTuning::On}};
    std::set<std::uint32_t> resolutions;
    for (int k = 0; k < 8; ++k) {
        auto r = world->detect(tuned);
        REQUIRE(r);
        requireExact(*r, expected, "cloth through a sphere, tuned grid");
        resolutions.insert(r->stats.resolution);
        CHECK(mentions(r->stats.settings_note, "grid tuned per scene"));
        if (k == 1) CHECK(mentions(r->stats.settings_note, "trying x0.71"));
    }
    // x1, then x0.71 (x1.41 next where lavapipe's times hold steady within 5 % around it).
    CHECK(resolutions.size() >= 2);
    auto fixed = world->detect({.resolution = 40, .reliable = {.grid_tuning = GridTuning::On}});
    REQUIRE(fixed);
    CHECK(fixed->stats.resolution == 40);
    CHECK_FALSE(mentions(fixed->stats.settings_note, "grid tuned"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

namespace {

// A 2 x 2 x 2 stack of unit boxes face to face, every box turned by `turn` (row-major 3 x 3)
// about the stack's centre.
struct BoxStack {
    HostMesh box;
    std::vector<Transform3x4> at;
};
BoxStack boxStack(const std::array<float, 9>& turn) {
    auto b = box({0.5f, 0.5f, 0.5f}, 4);
    REQUIRE(b);
    BoxStack s{std::move(*b), {}};
    for (int i = 0; i < 8; ++i) {
        const float p[3] = {float(i & 1) - 0.5f, float((i >> 1) & 1) - 0.5f, float((i >> 2) & 1) - 0.5f};
        Transform3x4 t{};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) t[r * 4 + c] = turn[r * 3 + c];
            t[r * 4 + 3] = turn[r * 3] * p[0] + turn[r * 3 + 1] * p[1] + turn[r * 3 + 2] * p[2];
        }
        s.at.push_back(t);
    }
    return s;
}

}  // namespace

// Along an axis an axis-aligned box's four side faces are seen edge-on (lines of deep cells);
// the reliable method's automatic direction tilts the axis then, and only then
// (auto_settings.cpp, tiltedAxis). The pairs are the same along the axis and tilted.
TEST_CASE("reliable: a stack of boxes is seen along a tilted axis, a turned stack and the paper's method along the axis",
          "[api][gpu][reliable]") {
    ValidatedContext ctx;
    const std::array<float, 9> none{1, 0, 0, 0, 1, 0, 0, 0, 1}, quarter_z{0, -1, 0, 1, 0, 0, 0, 0, 1};
    // 40 degrees about (1, 2, 3): no face parallel to an axis (Rodrigues' formula).
    const double n = std::sqrt(14.0), x = 1 / n, y = 2 / n, z = 3 / n, co = std::cos(0.698), si = std::sin(0.698), t = 1 - co;
    const std::array<float, 9> oblique{float(co + t * x * x),     float(t * x * y - si * z), float(t * x * z + si * y),
                                       float(t * x * y + si * z), float(co + t * y * y),     float(t * y * z - si * x),
                                       float(t * x * z - si * y), float(t * y * z + si * x), float(co + t * z * z)};
    const auto isAxis = [](const std::array<float, 3>& d) {
        return std::count(d.begin(), d.end(), 1.0f) == 1 && std::count(d.begin(), d.end(), 0.0f) == 2;
    };
    struct Case {
        const char* what;
        std::array<float, 9> turn;
        bool tilted;
    };
    for (const Case& c : {Case{"axis-aligned", none, true}, Case{"a quarter turn about z", quarter_z, true},
                          Case{"turned about (1, 2, 3)", oblique, false}}) {
        INFO(c.what);
        const BoxStack stack = boxStack(c.turn);
        auto world = makeWorld(ctx);
        std::vector<ReferenceObject> refs;
        for (const Transform3x4& at : stack.at) {
            REQUIRE(world->addMesh(stack.box, {.transform = at}));
            std::array<float, 12> rows{};
            std::copy(at.begin(), at.end(), rows.begin());
            refs.push_back({&stack.box, transformFrom3x4(rows)});
        }
        auto s = world->resolveSettings();
        REQUIRE(s);
        CHECK(isAxis(*s->direction) != c.tilted);
        if (c.tilted) CHECK(*s->direction == std::array<float, 3>{0.21f, 0.27f, 0.94f});  // z first of tied axes, tilted
        auto paper = world->resolveSettings({.method = DetectMethod::Peeling});
        REQUIRE(paper);
        CHECK(isAxis(*paper->direction));
        const auto ref = reference(refs);
        REQUIRE(ref.size() > 100);
        auto automatic = world->detect();
        REQUIRE(automatic);
        requireExact(*automatic, ref, "the automatic direction");
        CHECK(mentions(automatic->stats.settings_note, "edge-on") == c.tilted);
        auto along_z = world->detect({.direction = std::array<float, 3>{0, 0, 1}});
        REQUIRE(along_z);
        requireExact(*along_z, ref, "along z");
        if (c.tilted) CHECK(automatic->stats.cells.max_cell < along_z->stats.cells.max_cell);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
