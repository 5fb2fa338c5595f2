// Pathological scenes under the peeling method: each ends in the exact pairs or
// a named error, on both sampling backends, with the validation layer quiet (no access
// outside a buffer that it could see) and in bounded time. The sizes are the smallest that
// reach each limit. The same scenes under the reliable method (the default):
// reliable_limits_tests.cpp; docs/stability.md, "Pathological scenes", says what each does.
#include <catch2/catch.hpp>

#include <cstring>

#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "common/broadphase.h"
#include "mesh/mesh_upload.hpp"
#include "stability_support.hpp"
#include "vkcollide/io.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

Result<DetectResult> detectWith(CollisionWorld& w, DetectSettings s, SamplingBackend backend) {
    s.peeling.backend = backend;
    return w.detect(s);
}

}  // namespace

TEST_CASE("one triangle repeated past the deepest peeled ray gives every pair, on both backends and from engine buffers",
          "[stability][gpu][limits]") {
    ValidatedContext ctx;
    // 1,100 copies: the rays through them have more than kMaxRayFragments (1,024) fragments.
    auto deep = repeatedTriangle(1100);
    REQUIRE(deep);
    for (bool engine : {false, true}) {
        std::vector<EngineMesh> keep;
        auto world = worldOf(ctx, *deep, engine ? &keep : nullptr);
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            INFO((engine ? "engine buffers, " : "host meshes, ") << toString(backend));
            auto r = detectWith(*world, deep->settings, backend);
            REQUIRE(r);
            checkExact(r->pairs, *deep->reference);
            CHECK(r->stats.peeling.deep_rays > 0);
            CHECK(r->stats.peeling.layers_short);
            CHECK(r->stats.peeling.depth_complexity <= gpu::kMaxRayFragments);
            CHECK(r->stats.peeling.peel_passes <= gpu::kMaxRayFragments);
        }
    }
    // Below the limit the same stack is peeled ray by ray: the same pairs, no deep ray.
    auto peeled = repeatedTriangle(300);
    REQUIRE(peeled);
    auto world = worldOf(ctx, *peeled);
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
        auto r = detectWith(*world, peeled->settings, backend);
        REQUIRE(r);
        checkExact(r->pairs, *peeled->reference);
        CHECK(r->stats.peeling.deep_rays == 0);
        CHECK(r->stats.peeling.depth_complexity >= 300);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("fragment counts do not wrap: 70,000 copies of one triangle count 70,000 fragments per ray, on both backends",
          "[stability][gpu][limits]") {
    ValidatedContext ctx;
    // 70,000 > 2^16: the 15- and 16-bit counts of before wrapped here (65,545 copies read as 10).
    auto one = repeatedTriangle(1);
    auto many = repeatedTriangle(70000);
    REQUIRE(one);
    REQUIRE(many);
    auto bp = passes::BroadPhase::create(ctx.device(), passes::PeelingMethod::create);
    REQUIRE(bp);
    passes::BroadPhaseSettings s;
    s.resolution = 16;
    s.direction = {0.2f, 0.3f, 1.0f};
    s.region = std::array<float, 6>{-1.5f, -1.5f, -1.5f, 1.5f, 1.5f, 1.5f};
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
        INFO(toString(backend));
        s.backend = backend;
        auto single = passes::uploadMeshes(ctx.device(), {&one->scene.objects[0].mesh});
        auto stack = passes::uploadMeshes(ctx.device(), {&many->scene.objects[0].mesh});
        REQUIRE(single);
        REQUIRE(stack);
        auto a = (*bp)->run(single->meshes, s);
        REQUIRE(a);
        auto b = (*bp)->run(stack->meshes, s);
        REQUIRE(b);
        REQUIRE(a->fragments > 0);
        CHECK(b->fragments == a->fragments * 70000);
        // Every ray the triangle covers is deep: a collision ray without peeling.
        CHECK(b->deep_rays == a->fragments);
        CHECK(b->depth_complexity == 0);
        CHECK(b->layers == 0);
        CHECK(b->collision_rays >= b->deep_rays);
        CHECK(b->records.size() == 70000);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a face of 999,999 repeated corners ends in a named error within the candidate budget, under either method",
          "[stability][gpu][limits]") {
    ValidatedContext ctx;
    auto meshes = readMesh(repeatedCornerFace(999999), MeshFormat::Obj, "face.obj");
    REQUIRE(meshes);
    REQUIRE(meshes->size() == 1);
    CHECK(meshes->front().triangleCount() == 999997);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    auto face = (*world)->addMesh(meshes->front(), {.name = "face", .self_collision = true});
    REQUIRE(face);
    // The default method: every triangle in every cell of the face's footprint, cells of
    // 999,997 footprints to sort in global memory. On llvmpipe the sort needs more loop
    // iterations than it runs (a named error); on a GPU it sorts, and the sweep stops at the
    // comparisons' budget: the triangles fan around one vertex in three shapes, so each
    // footprint visits the two thirds it is not a copy of (neighbours, 3e11 visits).
    DetectSettings reliable;
    auto r = (*world)->detect(reliable);
    REQUIRE_FALSE(r);
    INFO(r.error().message());
    CHECK(r.error().code() == ErrorCode::LimitExceeded);
    CHECK((mentions(r.error(), "max_candidate_pairs") || mentions(r.error(), "loop iterations")));
    CHECK(mentions(r.error(), "999997 footprints in one cell"));
    CHECK((*world)->state() == WorldState::Ready);
    // The peeling method: every triangle is a candidate (deep rays), and all of them overlap:
    // 5e11 box pairs, past the narrow phase's budget.
    DetectSettings peeling{.method = DetectMethod::Peeling};
    peeling.resolution = 8;
    peeling.direction = std::array<float, 3>{0.2f, 0.3f, 1.0f};
    auto p = (*world)->detect(peeling);
    REQUIRE_FALSE(p);
    CHECK(p.error().code() == ErrorCode::LimitExceeded);
    CHECK(mentions(p.error(), "max_box_pairs"));
    CHECK((*world)->state() == WorldState::Ready);
    // The world goes on: without the face, a small scene gives its pairs.
    REQUIRE((*world)->removeObject(*face));
    auto small = repeatedTriangle(3);
    REQUIRE(small);
    for (const SceneObject& o : small->scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    for (const DetectSettings& s : {small->settings, DetectSettings{}}) {
        auto again = (*world)->detect(s);
        REQUIRE(again);
        CHECK(again->pairs.size() == 3);  // ids shifted by the removed face: count only
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("two tetrahedra under thousands of slabs find every pair, on both backends", "[stability][gpu][limits]") {
    ValidatedContext ctx;
    // 2,000 slabs: 4,004 surfaces on every ray through the contact, more than are peeled;
    // 300 slabs: 604, peeled. (32,768 slabs, where the raster backend once wrapped its
    // 16-bit counts and found 0 of the pairs, run in tools/stability/pathological_report:
    // the narrow phase sweeps their 393K stacked candidates for about a minute.)
    for (std::uint32_t slabs : {2000u, 300u}) {
        auto c = slabsOverContact(slabs);
        REQUIRE(c);
        REQUIRE_FALSE(c->reference->empty());
        auto world = worldOf(ctx, *c);
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            INFO(slabs << " slabs, " << toString(backend));
            auto r = detectWith(*world, c->settings, backend);
            INFO((r ? std::string() : r.error().message()));
            REQUIRE(r);
            checkExact(r->pairs, *c->reference);
            CHECK((r->stats.peeling.deep_rays > 0) == (slabs > 1000));
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a thousand objects give the exact reference's pairs", "[stability][gpu][limits]") {
    ValidatedContext ctx;
    auto c = manyObjects(1000);
    REQUIRE(c);
    REQUIRE_FALSE(c->reference->empty());
    auto world = worldOf(ctx, *c);
    // Dilation (the raster backend's) for the grazing contacts; the compute backend samples
    // pixel centres, so it may miss those but finds nothing else.
    auto dilated = detectWith(*world, c->settings, SamplingBackend::Raster);
    REQUIRE(dilated);
    checkExact(dilated->pairs, *c->reference);
    CHECK(dilated->stats.objects == 1000);
    DetectSettings centres = c->settings;
    centres.peeling.coverage = Coverage::Centre;
    auto sampled = detectWith(*world, centres, SamplingBackend::Compute);
    REQUIRE(sampled);
    const PairComparison cmp = comparePairs(sampled->pairs, *c->reference);
    CHECK(cmp.false_positives == 0);
    CHECK(cmp.recall > 0.99);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("mutually crossing triangles: the pair budget keeps max_pairs, counts the rest, the same on any thread count",
          "[stability][gpu][limits]") {
    ValidatedContext ctx;
    auto c = crossingTriangles(600);
    REQUIRE(c);
    const std::size_t all = std::size_t{600} * 599 / 2;
    REQUIRE(c->reference->size() == all);
    // Rays near the axis cross up to 600 triangles: a layer cap keeps the peeling short
    // (those rays collide, as they would anyway).
    c->settings.peeling.layer_cap = 8;
    auto world = worldOf(ctx, *c);
    // Unbounded: every pair.
    auto full = world->detect(c->settings);
    REQUIRE(full);
    checkExact(full->pairs, *c->reference);
    CHECK(full->pairs_left_out == 0);
    CHECK_FALSE(full->incomplete);

    DetectSettings capped = c->settings;
    capped.limits.max_pairs = 20000;
    std::vector<TrianglePair> kept_before;
    for (unsigned threads : {1u, 2u}) {
        auto w = CollisionWorld::create(ctx.context(), {.threads = threads});
        REQUIRE(w);
        for (const SceneObject& o : c->scene.objects) REQUIRE((*w)->addMesh(o.mesh, o.options));
        auto r = (*w)->detect(capped);
        REQUIRE(r);
        INFO(threads << " threads");
        CHECK(r->pairs.size() == 20000);
        CHECK(r->pairs_left_out == all - 20000);
        REQUIRE(r->incomplete);
        CHECK(r->incomplete->code() == ErrorCode::LimitExceeded);
        CHECK(mentions(*r->incomplete, "max_pairs"));
        CHECK(std::is_sorted(r->pairs.begin(), r->pairs.end()));
        CHECK(std::includes(c->reference->begin(), c->reference->end(), r->pairs.begin(), r->pairs.end()));
        CHECK(r->stats.positive_tests == all);
        // Responses only for triangles in the kept pairs.
        CHECK(r->responses.size() <= 600);
        if (!kept_before.empty()) CHECK((r->pairs == kept_before));
        kept_before = r->pairs;
    }
    // The box-pair budget: the sweep stops and names it.
    DetectSettings tight = c->settings;
    tight.limits.max_candidate_pairs = 10000;
    auto stopped = world->detect(tight);
    REQUIRE_FALSE(stopped);
    CHECK(stopped.error().code() == ErrorCode::LimitExceeded);
    CHECK(world->state() == WorldState::Ready);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("coordinates inside the sampling range give the pair on both backends, beyond it a named error",
          "[stability][gpu][limits]") {
    ValidatedContext ctx;
    for (float scale : {1e-29f, 1.0f, 1e29f}) {
        auto c = scaledCrossing(scale);
        REQUIRE(c);
        auto world = worldOf(ctx, *c);
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            INFO("scale " << scale << ", " << toString(backend));
            auto r = detectWith(*world, c->settings, backend);
            REQUIRE(r);
            checkExact(r->pairs, *c->reference);
        }
    }
    SECTION("host meshes beyond +-1e30 are refused when added, moved or updated") {
        auto far = scaledCrossing(1e38f);
        REQUIRE(far);
        auto world = CollisionWorld::create(ctx.context());
        REQUIRE(world);
        auto added = (*world)->addMesh(far->scene.objects[0].mesh, {.name = "far"});
        REQUIRE_FALSE(added);
        CHECK(added.error().code() == ErrorCode::LimitExceeded);
        CHECK(mentions(added.error(), "'far'"));
        // Finite coordinates and a finite transform whose product overflows float.
        auto mid = scaledCrossing(1e20f);
        REQUIRE(mid);
        auto id = (*world)->addMesh(mid->scene.objects[0].mesh, {.name = "mid"});
        REQUIRE(id);
        const Transform3x4 huge{1e20f, 0, 0, 0, 0, 1e20f, 0, 0, 0, 0, 1e20f, 0};
        auto moved = (*world)->setTransform(*id, huge);
        REQUIRE_FALSE(moved);
        CHECK(moved.error().code() == ErrorCode::LimitExceeded);
        auto with = (*world)->addMesh(mid->scene.objects[1].mesh, {.name = "mid-2", .transform = huge});
        REQUIRE_FALSE(with);
        CHECK(with.error().code() == ErrorCode::LimitExceeded);
        std::vector<Float3> beyond = mid->scene.objects[0].mesh.positions;
        beyond[0].x = 3e30f;
        auto updated = (*world)->updateVertices(*id, beyond);
        REQUIRE_FALSE(updated);
        CHECK(updated.error().code() == ErrorCode::LimitExceeded);
    }
    SECTION("a scene narrower than 1e-30, or of subnormal coordinates, fails with LimitExceeded on both backends") {
        for (float scale : {1e-35f, 1e-40f}) {
            auto tiny = scaledCrossing(scale);
            REQUIRE(tiny);
            auto world = worldOf(ctx, *tiny);
            for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
                INFO("scale " << scale << ", " << toString(backend));
                auto r = detectWith(*world, tiny->settings, backend);
                REQUIRE_FALSE(r);
                CHECK(r.error().code() == ErrorCode::LimitExceeded);
                CHECK(mentions(r.error(), "1e-30"));
                CHECK(world->state() == WorldState::Ready);
            }
        }
    }
    SECTION("engine meshes beyond +-1e30 fail the GPU check on both backends: left out and named") {
        auto far = scaledCrossing(1e38f);
        REQUIRE(far);
        auto near = scaledCrossing(1.0f);
        REQUIRE(near);
        std::vector<EngineMesh> keep;
        auto world = worldOf(ctx, *far, &keep);
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            INFO(toString(backend));
            // Both objects bad: nothing left to test.
            auto none = detectWith(*world, far->settings, backend);
            REQUIRE_FALSE(none);
            CHECK(none.error().code() == ErrorCode::InvalidMesh);
            CHECK(mentions(none.error(), "no object left"));
            CHECK(mentions(none.error(), "1e30"));
        }
        // With a good object beside them, they are left out and named.
        keep.push_back(engineCopy(ctx.device(), near->scene.objects[0].mesh));
        REQUIRE(world->addGpuMesh(keep.back().desc, {.name = "near"}));
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            auto r = detectWith(*world, near->settings, backend);
            REQUIRE(r);
            CHECK(r->pairs.empty());
            CHECK(r->excluded.size() == 2);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
