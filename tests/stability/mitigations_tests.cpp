// The mitigations beyond the paper (DetectSettings::peeling.axes, coverage, closed_epsilon): what
// each guarantees (they only add pairs; three axes test at least what three separate
// detections would, once each), their errors, the asynchronous path, and their recall on
// the recall guard's scenes at the coarse resolution where the paper misses pairs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>

#include "broad/broad_phase.hpp"
#include "broad/projection.hpp"
#include "support/gpu_fixture.hpp"
#include "support/stability_scenes.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

std::unique_ptr<CollisionWorld> worldWith(ValidatedContext& ctx, const TestScene& scene) {
    auto w = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(w);
    for (const SceneObject& o : scene.objects) REQUIRE((*w)->addMesh(o.mesh, o.options));
    return std::move(*w);
}

// The paper's method, which the mitigations extend.
DetectSettings coarse(std::array<float, 3> direction = {0.15f, -0.2f, 1.0f}) {
    DetectSettings s;
    s.method = DetectMethod::Peeling;
    s.resolution = 64;
    s.direction = direction;
    return s;
}

bool contains(const std::vector<TrianglePair>& all, const std::vector<TrianglePair>& part) {
    return std::includes(all.begin(), all.end(), part.begin(), part.end());
}

}  // namespace

TEST_CASE("three axes test at least what three one-axis detections would, each pair once", "[stability][gpu][axes]") {
    ValidatedContext ctx;
    auto scene = selfIntersectingTube();
    REQUIRE(scene);
    auto world = worldWith(ctx, *scene);
    const DetectSettings one = coarse();
    const auto basis = passes::projectionBasis(*one.direction);
    std::vector<TrianglePair> united;
    std::size_t tests_of_three = 0;
    for (const std::array<float, 3>& d : {*one.direction, basis.u, basis.v}) {
        DetectSettings s = one;
        s.direction = d;
        auto r = world->detect(s);
        REQUIRE(r);
        tests_of_three += r->stats.triangle_tests;
        united.insert(united.end(), r->pairs.begin(), r->pairs.end());
    }
    std::sort(united.begin(), united.end());
    united.erase(std::unique(united.begin(), united.end()), united.end());
    DetectSettings three = one;
    three.peeling.axes = 3;
    auto r = world->detect(three);
    REQUIRE(r);
    CHECK(r->stats.peeling.axes == 3);
    CHECK(contains(r->pairs, united));
    std::printf("axes: union of three detections %zu pairs in %zu tests; axes = 3: %zu pairs in %zu tests\n", united.size(),
                tests_of_three, r->pairs.size(), r->stats.triangle_tests);
    CHECK(r->stats.triangle_tests < tests_of_three);
    CHECK(r->stats.narrow.candidates <= r->stats.triangles_downloaded);  // one record per triangle after uniting

    // The asynchronous form gives the same pairs (layers predicted per axis).
    REQUIRE(world->submit(three));
    auto async = world->collect();
    REQUIRE(async);
    CHECK(async->pairs == r->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("every mitigation only adds pairs to the paper's", "[stability][gpu]") {
    ValidatedContext ctx;
    auto scenes = allTestScenes();
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto world = worldWith(ctx, scene);
        DetectSettings paper_settings = coarse();
        paper_settings.peeling.depth_aware = false;  // the paper's separation, as the variants use
        auto paper = world->detect(paper_settings);
        REQUIRE(paper);
        for (const Variant& v : mitigationVariants()) {
            StabilityCase c{scene.name, {}, coarse(), {}};
            c.pixel = 3.0f / 64;
            DetectSettings s = c.settings;
            v.apply(s, c);
            auto r = world->detect(s);
            REQUIRE(r);
            INFO(scene.name << " / " << v.name);
            CHECK(contains(r->pairs, paper->pairs));
            CHECK(r->stats.collision_rays >= paper->stats.collision_rays);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("depth-aware separation finds every pair the paper's separation finds, at 64 and 256 rays", "[stability][gpu][depth]") {
    ValidatedContext ctx;
    auto scenes = allTestScenes();
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto world = worldWith(ctx, scene);
        for (std::uint32_t resolution : {64u, 256u}) {
            DetectSettings s = coarse();
            s.resolution = resolution;
            s.peeling.depth_aware = false;
            auto paper = world->detect(s);
            s.peeling.depth_aware = true;
            auto depth = world->detect(s);
            REQUIRE(paper);
            REQUIRE(depth);
            std::printf("stability | %-24s %4u rays: paper %zu pairs, %zu downloaded; depth-aware %zu pairs, %zu downloaded\n",
                        scene.name.c_str(), resolution, paper->pairs.size(), paper->stats.triangles_downloaded, depth->pairs.size(),
                        depth->stats.triangles_downloaded);
            INFO(scene.name << " at " << resolution);
            CHECK(contains(depth->pairs, paper->pairs));
            CHECK(depth->stats.collision_rays == paper->stats.collision_rays);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("at 64 rays three axes or dilation find every pair of the recall guard's scenes", "[stability][gpu][recall]") {
    ValidatedContext ctx;
    auto scenes = allTestScenes();
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto objects = scene.reference();
        auto reference = computeReferencePairs(objects);
        REQUIRE(reference);
        StabilityCase c{scene.name + " 64", scene, coarse(), *reference};
        c.pixel = 3.0f / 64;
        for (const Variant& v : mitigationVariants()) {
            DetectSettings s = c.settings;
            v.apply(s, c);
            auto m = measureCase(ctx.context(), c, s);
            REQUIRE(m);
            std::printf("stability | %s\n", describe(c.name, v.name, *m).c_str());
            INFO(c.name << " / " << v.name);
            CHECK(m->cmp.false_positives == 0);
            if (v.name != "paper" && v.name != "eps=2px") CHECK(m->cmp.recall == 1.0);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("mitigation settings are checked and reported", "[stability][gpu]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox();
    REQUIRE(scene);
    auto world = worldWith(ctx, *scene);
    DetectSettings s = coarse();
    s.peeling.axes = 2;
    auto bad_axes = world->detect(s);
    REQUIRE_FALSE(bad_axes);
    CHECK(bad_axes.error().code() == ErrorCode::InvalidArgument);
    CHECK(bad_axes.error().message().find("peeling.axes must be 1 or 3") != std::string::npos);
    s = coarse();
    s.peeling.closed_epsilon = -1;
    auto bad_eps = world->detect(s);
    REQUIRE_FALSE(bad_eps);
    CHECK(bad_eps.error().message().find("peeling.closed_epsilon") != std::string::npos);

    const bool hardware = ctx.context().deviceInfo().conservative_rasterization;
    s = coarse();
    s.peeling.coverage = Coverage::Conservative;
    auto conservative = world->detect(s);
    if (hardware) {
        REQUIRE(conservative);
        CHECK(conservative->stats.peeling.coverage == Coverage::Conservative);
    } else {  // lavapipe: no VK_EXT_conservative_rasterization
        REQUIRE_FALSE(conservative);
        CHECK(conservative.error().code() == ErrorCode::UnsupportedFeature);
        CHECK(conservative.error().message().find("use dilation") != std::string::npos);
    }
    s.peeling.coverage = Coverage::Best;
    auto best = world->detect(s);
    REQUIRE(best);
    CHECK(best->stats.peeling.coverage == (hardware ? Coverage::Conservative : Coverage::Dilate));
    CHECK(best->stats.settings_note.find("coverage") != std::string::npos);
    // Thin-triangle coverage is drawn on the raster backend: Auto falls back to it, an
    // explicit Compute is refused.
    s = coarse();
    s.peeling.coverage = Coverage::Dilate;
    s.peeling.backend = SamplingBackend::Compute;
    auto compute_dilate = world->detect(s);
    REQUIRE_FALSE(compute_dilate);
    CHECK(compute_dilate.error().code() == ErrorCode::UnsupportedFeature);
    s.peeling.backend = SamplingBackend::Auto;
    auto auto_dilate = world->detect(s);
    REQUIRE(auto_dilate);
    CHECK(auto_dilate->stats.peeling.backend == SamplingBackend::Raster);
    // The world is still usable after the refused settings.
    auto plain = world->detect(coarse());
    REQUIRE(plain);
    CHECK(plain->stats.peeling.coverage == Coverage::Centre);
    CHECK(plain->stats.peeling.axes == 1);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
