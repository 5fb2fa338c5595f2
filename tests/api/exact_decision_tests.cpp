// Where the reliable method's exact decision runs (DetectSettings::reliable.exact): the GPU's pair
// pass (exact arithmetic in double) and the CPU narrow phase give the same pairs and
// responses on every scene, touching and coplanar contacts above all, and the statistics
// say which one decided. Validation layer on.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "support/exact_reference.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scene_world.hpp"
#include "support/stability_scenes.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// Rotation by `angle` about the axis (1, 2, 3) / |..| and a translation, as floats: a
// stack turned this way has no coplanar face pair exact in float, only nearly coplanar
// ones, which the filter cannot settle and the exact arithmetic must.
Transform3x4 tilted(float angle, Float3 at) {
    const double n = std::sqrt(14.0), x = 1 / n, y = 2 / n, z = 3 / n, c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const auto f = [](double v) { return static_cast<float>(v); };
    return {f(t * x * x + c),     f(t * x * y - s * z), f(t * x * z + s * y), at.x,
            f(t * x * y + s * z), f(t * y * y + c),     f(t * y * z - s * x), at.y,
            f(t * x * z - s * y), f(t * y * z + s * x), f(t * z * z + c),     at.z};
}

// Boxes resting on each other face to face (exactly coplanar in float: every coordinate a
// multiple of a power of two), one turned stack of two (nearly coplanar), a ball resting
// on a pole vertex, a degenerate open strip lying in a face plane, and a self-colliding
// folded sheet whose fold touches itself.
TestScene restingScene() {
    TestScene s{"resting stack", {}};
    const auto add = [&](Result<HostMesh> m, std::string name, Transform3x4 at, bool open = false, bool self = false) {
        REQUIRE(m);
        s.objects.push_back({std::move(*m), {.name = std::move(name), .self_collision = self, .open = open, .transform = at}});
    };
    for (int k = 0; k < 4; ++k)
        add(box({0.5f, 0.5f, 0.5f}, 3), "box" + std::to_string(k),
            Transform3x4{1, 0, 0, float(k % 2), 0, 1, 0, 0.5f * float(k / 2), 0, 0, 1, float(k / 2)});
    const Transform3x4 lower = tilted(0.37f, {3.0f, 0.0f, 0.0f});
    Transform3x4 upper = lower;
    // The upper box one unit up along the turned z axis: rounded, so its bottom face is
    // within an ulp of the lower box's top face, on either side.
    for (int r = 0; r < 3; ++r) upper[4 * r + 3] += lower[4 * r + 2];
    add(box({0.5f, 0.5f, 0.5f}, 2), "turned-lower", lower);
    add(box({0.5f, 0.5f, 0.5f}, 2), "turned-upper", upper);
    add(uvSphere(0.25f, 16, 8), "ball", Transform3x4{1, 0, 0, 0.0f, 0, 1, 0, 0.0f, 0, 0, 1, 1.75f});
    HostMesh strip;  // zero-area triangles (segments) lying in the top face of box 1
    strip.positions = {{0.75f, -0.25f, 0.5f}, {1.25f, 0.25f, 0.5f}, {1.0f, 0.0f, 0.5f}, {0.75f, 0.25f, 0.5f}};
    strip.indices = {0, 1, 2, 0, 3, 1};
    s.objects.push_back({std::move(strip), {.name = "strip", .open = true}});
    auto sheet = clothGrid(1.0f, 1.0f, 8, 8);
    REQUIRE(sheet);
    // Folded: the upper half reflected onto the lower half, so its triangles coincide with
    // the lower half's (one object, no shared vertex index).
    HostMesh folded = std::move(*sheet);
    const std::size_t half = folded.positions.size();
    for (std::size_t v = 0; v < half; ++v) folded.positions.push_back(folded.positions[v]);
    const std::size_t tris = folded.indices.size();
    for (std::size_t i = 0; i < tris; i += 3)
        for (int k : {0, 2, 1}) folded.indices.push_back(folded.indices[i + k] + static_cast<std::uint32_t>(half));
    s.objects.push_back(
        {std::move(folded),
         {.name = "folded", .self_collision = true, .open = true, .transform = Transform3x4{1, 0, 0, -2.0f, 0, 1, 0, 0, 0, 0, 1, 0}}});
    return s;
}

struct Both {
    DetectResult gpu, cpu;
};

// The survivors the one pass of few pairs sorts (gpu::kSmallSortPairs; docs/exact_gpu.md).
constexpr std::size_t gpuOnePassSurvivors = 4096;

Both detectBoth(ValidatedContext& ctx, const TestScene& scene, DetectSettings settings = {}) {
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    settings.reliable.exact = ExactDecision::Gpu;
    auto gpu = (*world)->detect(settings);
    REQUIRE(gpu);
    settings.reliable.exact = ExactDecision::Cpu;
    auto cpu = (*world)->detect(settings);
    REQUIRE(cpu);
    return {std::move(*gpu), std::move(*cpu)};
}

bool sameResponses(const std::vector<TriangleResponse>& a, const std::vector<TriangleResponse>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (a[k].object != b[k].object || a[k].triangle != b[k].triangle || a[k].partner_count != b[k].partner_count ||
            std::memcmp(&a[k].direction, &b[k].direction, sizeof(Float3)) != 0)
            return false;
    return true;
}

// `world` (a scene of three coincident grids) with grids 1 and 2 moved along x by x1 and x2,
// detected with `settings`, against a new world moved the same way (no earlier result, no
// memory made ready): the same pairs and responses. Returns the world's result.
DetectResult detectMovedAsNew(ValidatedContext& ctx, const TestScene& grids, CollisionWorld& world, const DetectSettings& settings,
                              float x1, float x2) {
    const Transform3x4 t1 = {1, 0, 0, x1, 0, 1, 0, 0, 0, 0, 1, 0}, t2 = {1, 0, 0, x2, 0, 1, 0, 0, 0, 0, 1, 0};
    auto fresh = sceneWorld(ctx, grids);
    for (CollisionWorld* w : {&world, fresh.get()}) {
        REQUIRE(w->setTransform(1, t1));
        REQUIRE(w->setTransform(2, t2));
    }
    auto r = world.detect(settings);
    REQUIRE(r);
    auto expected = fresh->detect(settings);
    REQUIRE(expected);
    CHECK(r->pairs == expected->pairs);
    CHECK(sameResponses(r->responses, expected->responses));
    return std::move(*r);
}

// A GPU-sorted result like `first` (same pairs and responses) made in memory made ready during
// the wait: room for an eighth more of both arrays, the time in prepare_ms, within collect_ms.
void checkMadeReady(const DetectResult& next, const DetectResult& first) {
    const std::size_t n = first.pairs.size(), responses = first.responses.size();
    CHECK(next.pairs == first.pairs);
    CHECK(sameResponses(next.responses, first.responses));
    CHECK(next.pairs.capacity() >= n + n / 8);
    CHECK(next.responses.capacity() >= responses + responses / 8);
    CHECK(next.stats.host.prepare_ms > 0.0);
    CHECK(next.stats.host.prepare_ms <= next.stats.host.collect_ms);
}

// The two paths agree bit for bit, match the exact reference, and say which decided.
void requireSame(const Both& r, const std::vector<TrianglePair>& reference, const std::string& what) {
    INFO(what << ": GPU " << r.gpu.pairs.size() << " pairs, CPU " << r.cpu.pairs.size() << ", reference " << reference.size());
    CHECK(r.gpu.pairs == r.cpu.pairs);
    CHECK(sameResponses(r.gpu.responses, r.cpu.responses));
    const PairComparison cmp = comparePairs(r.gpu.pairs, reference);
    CHECK(cmp.false_negatives == 0);
    CHECK(cmp.false_positives == 0);
    const DetectStats &g = r.gpu.stats, &c = r.cpu.stats;
    CHECK(g.cells.exact_ran);
    CHECK_FALSE(c.cells.exact_ran);
    CHECK(g.cpu_exact_tests == 0);
    CHECK(c.gpu_exact_tests == 0);
    CHECK(g.gpu_exact_tests == g.cells.exact_tests);
    CHECK(g.triangle_tests == g.gpu_exact_tests);
    CHECK(c.triangle_tests == c.cpu_exact_tests);
    // The GPU decided what the CPU would have tested: the filter's survivors.
    CHECK(g.gpu_exact_tests >= c.cells.survivors);
    if (!reference.empty()) CHECK(g.gpu_exact_tests > 0);
    // Only decided pairs crossed the bus (before the host's rare deduplication).
    CHECK(g.cells.survivors <= c.cells.survivors);
    CHECK(g.cells.survivors >= r.gpu.pairs.size());
}

}  // namespace

TEST_CASE("exact decision: GPU and CPU give the same pairs and responses on resting, coplanar and folded contacts",
          "[api][gpu][reliable][exact]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64: the CPU decides (tested below)");
        return;
    }
    const TestScene scene = restingScene();
    auto ref = computeReferencePairs(scene.reference(), {.threads = 2});
    REQUIRE(ref);
    REQUIRE(ref->size() > 100);  // touching faces, the ball's pole, the strip, the fold
    // The exact decision inside the pair pass, and in a pass of its own over the queue of
    // what the filter left.
    for (std::uint32_t resolution : {1u, 7u, 64u})
        for (ExactPass pass : {ExactPass::Inline, ExactPass::Queued}) {
            DetectSettings s;
            s.resolution = resolution;
            s.reliable.exact_pass = pass;
            const Both r = detectBoth(ctx, scene, s);
            requireSame(r, *ref, "resolution " + std::to_string(resolution) + ", exact pass " + toString(pass));
            CHECK(r.gpu.stats.cells.exact_queued == (pass == ExactPass::Queued));
            // Neighbours by position only: the fold's coincident copies share positions, not indices.
            CHECK(r.gpu.stats.cells.exact_neighbours > 0);
        }
}

TEST_CASE("exact decision: GPU and CPU agree on the test scenes and the stability cases", "[api][gpu][reliable][exact]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64");
        return;
    }
    auto scenes = allTestScenes(0.5f);
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto ref = computeReferencePairs(scene.reference(), {.threads = 2});
        REQUIRE(ref);
        requireSame(detectBoth(ctx, scene), *ref, scene.name);
    }
    for (auto make : {+[] { return exactlyTouching(true); }, +[] { return exactlyTouching(false); }, +[] { return edgeEdgeTouch(); },
                      +[] { return vertexFaceTouch(); }, +[] { return zeroAreaTriangle(); }, +[] { return needleSliver(); },
                      +[] { return coplanarOpenQuads(false); }, +[] { return nonManifoldFin(); }, +[] { return thinWall(true); }}) {
        auto c = make();
        REQUIRE(c);
        requireSame(detectBoth(ctx, c->scene), c->reference, c->name);
    }
    auto far = farFromOrigin(1e6f);  // its reference is of the same geometry at the origin
    REQUIRE(far);
    auto ref = computeReferencePairs(far->scene.reference(), {.threads = 2});
    REQUIRE(ref);
    requireSame(detectBoth(ctx, far->scene), *ref, far->name);
}

TEST_CASE("exact decision: Auto decides on the GPU where it can, and bad settings are refused by name", "[api][gpu][reliable][exact]") {
    ValidatedContext ctx;
    const TestScene scene = restingScene();
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    auto automatic = (*world)->detect();
    REQUIRE(automatic);
    const bool fp64 = ctx.device().shader_float64;
    CHECK(automatic->stats.cells.exact_ran == fp64);
    CHECK((automatic->stats.gpu_exact_tests > 0) == fp64);
    CHECK((automatic->stats.cpu_exact_tests > 0) == !fp64);
    if (fp64) {
        // ExactPass::Auto: inside the pair pass at first and for this scene's few canonical
        // candidates (the switch to the queued pass: cells_stage_tests.cpp); Queued forced
        // gives the same pairs. Inline, the whole filter runs first; queued, its plane step
        // alone (the exact pass settles the rest): never fewer exact tests queued.
        CHECK_FALSE(automatic->stats.cells.exact_queued);
        REQUIRE(automatic->stats.cells.candidates - automatic->stats.cells.duplicates < 32768);
        DetectSettings queued;
        queued.reliable.exact_pass = ExactPass::Queued;
        auto next = (*world)->detect(queued);
        REQUIRE(next);
        CHECK(next->stats.cells.exact_queued);
        CHECK(next->pairs == automatic->pairs);
        CHECK(next->stats.gpu_exact_tests >= automatic->stats.gpu_exact_tests);
        auto again = (*world)->detect();
        REQUIRE(again);
        CHECK_FALSE(again->stats.cells.exact_queued);
    }

    DetectSettings peeling;
    peeling.method = DetectMethod::Peeling;
    peeling.reliable.exact = ExactDecision::Gpu;
    auto refused = (*world)->detect(peeling);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(refused.error().message(), Catch::Contains("reliable method"));
    peeling.reliable.exact = ExactDecision::Auto;  // the peeling method decides on the CPU
    auto on_cpu = (*world)->detect(peeling);
    REQUIRE(on_cpu);
    CHECK(on_cpu->stats.gpu_exact_tests == 0);
    CHECK(on_cpu->stats.cpu_exact_tests == on_cpu->stats.triangle_tests);

    DetectSettings bad;
    bad.reliable.exact = static_cast<ExactDecision>(7);
    auto out_of_range = (*world)->detect(bad);
    REQUIRE_FALSE(out_of_range);
    CHECK(out_of_range.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(out_of_range.error().message(), Catch::Contains("ExactDecision"));
    DetectSettings bad_pass;
    bad_pass.reliable.exact_pass = static_cast<ExactPass>(9);
    auto pass_out_of_range = (*world)->detect(bad_pass);
    REQUIRE_FALSE(pass_out_of_range);
    CHECK(pass_out_of_range.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(pass_out_of_range.error().message(), Catch::Contains("reliable.exact_pass"));
    CHECK((*world)->detect());  // usable afterwards
}

TEST_CASE("exact decision: the record paths refuse pairs_decided", "[narrow][exact]") {
    NarrowOptions options;
    options.pairs_decided = true;
    std::vector<CandidateTriangle> none;
    ThreadPool serial(1);
    auto r = runNarrowPhase(none, options, serial);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(r.error().message(), Catch::Contains("pairs_decided"));
}

namespace {

// One world, the same settings twice: pairs sorted on the GPU (`on_gpu`: Gpu, or Auto for
// the one pass of few pairs, after a detection that sizes its copies for the scene), then
// on the CPU. The exact pass fixed (ExactPass::Auto may change between the two detections,
// and with it the filter that ran first and the count of exact tests; not the pairs). The
// queued pass may still skip its filter in the second (CellStats::filter_ran).
Both sortedBoth(CollisionWorld& world, DetectSettings settings = {}, PairSort on_gpu = PairSort::Gpu) {
    if (settings.reliable.exact_pass == ExactPass::Auto) settings.reliable.exact_pass = ExactPass::Queued;
    settings.reliable.pair_sort = on_gpu;
    if (on_gpu == PairSort::Auto) REQUIRE(world.detect(settings));
    auto gpu = world.detect(settings);
    REQUIRE(gpu);
    settings.reliable.pair_sort = PairSort::Cpu;
    auto cpu = world.detect(settings);
    REQUIRE(cpu);
    return {std::move(*gpu), std::move(*cpu)};
}

void requireSameSorted(const Both& r, const std::string& what) {
    INFO(what << ": GPU-sorted " << r.gpu.pairs.size() << " pairs, CPU-sorted " << r.cpu.pairs.size());
    CHECK(r.gpu.stats.reliable.pairs_sorted_on_gpu);
    CHECK_FALSE(r.cpu.stats.reliable.pairs_sorted_on_gpu);
    // The GPU-sorted result's responses are the GPU's (ResponseSource::Auto) unless pairs were
    // left out (max_pairs: the host computes them over the pairs kept): equal either way.
    CHECK(r.gpu.stats.reliable.responses_on_gpu == (r.gpu.pairs_left_out == 0));
    CHECK_FALSE(r.cpu.stats.reliable.responses_on_gpu);
    // The pairs named while the GPU computed the responses (a milestone) only with them, and
    // only after a detection of kNameDuringGpuFrom pairs or more (the one before: about as many).
    if (r.gpu.stats.reliable.pairs_named_during_gpu) CHECK(r.gpu.stats.reliable.responses_on_gpu);
    if (r.gpu.pairs.size() < kNameDuringGpuFrom / 2) CHECK_FALSE(r.gpu.stats.reliable.pairs_named_during_gpu);
    CHECK_FALSE(r.cpu.stats.reliable.pairs_named_during_gpu);
    CHECK((r.gpu.stats.host.milestone_ms > 0.0) == r.gpu.stats.reliable.pairs_named_during_gpu);
    CHECK(r.gpu.pairs == r.cpu.pairs);
    CHECK(sameResponses(r.gpu.responses, r.cpu.responses));
    CHECK(r.gpu.pairs_left_out == r.cpu.pairs_left_out);
    CHECK(r.gpu.incomplete.has_value() == r.cpu.incomplete.has_value());
    CHECK(r.gpu.stats.triangles_downloaded == r.cpu.stats.triangles_downloaded);
    CHECK(r.gpu.stats.positive_tests == r.cpu.stats.positive_tests);
    // What the filter rejected or the exact test decided: every canonical candidate (the
    // second detection may skip a filter that rejected little: docs/exact_gpu.md).
    CHECK(r.gpu.stats.gpu_exact_tests + r.gpu.stats.cells.filtered == r.cpu.stats.gpu_exact_tests + r.cpu.stats.cells.filtered);
    CHECK(r.gpu.stats.cpu_exact_tests == 0);
}

}  // namespace

TEST_CASE("pair sort: pairs sorted on the GPU give the CPU sort's result to the bit", "[api][gpu][reliable][exact]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;  // refusal below
    const TestScene resting = restingScene();
    auto resting_world = sceneWorld(ctx, resting);
    for (std::uint32_t resolution : {1u, 7u, 64u}) {
        DetectSettings s;
        s.resolution = resolution;
        requireSameSorted(sortedBoth(*resting_world, s), "resting scene, resolution " + std::to_string(resolution));
    }
    auto scenes = allTestScenes(0.5f);
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) requireSameSorted(sortedBoth(*sceneWorld(ctx, scene)), scene.name);
    for (auto make : {+[] { return exactlyTouching(true); }, +[] { return zeroAreaTriangle(); }, +[] { return coplanarOpenQuads(false); },
                      +[] { return nonManifoldFin(); }}) {
        auto c = make();
        REQUIRE(c);
        requireSameSorted(sortedBoth(*sceneWorld(ctx, c->scene)), c->name);
    }
    // max_pairs: both keep the first pairs in order and count the rest.
    DetectSettings few;
    few.limits.max_pairs = 37;
    const Both cut = sortedBoth(*resting_world, few);
    CHECK(cut.gpu.pairs.size() == 37);
    CHECK(cut.gpu.pairs_left_out > 0);
    requireSameSorted(cut, "resting scene, max_pairs 37");
    // An overflow: three coincident grids need more survivors than the first run holds;
    // the GPU sorts the final run's.
    auto grids_made = coincidentGrids(40);
    REQUIRE(grids_made);
    const TestScene& grids = *grids_made;
    auto grid_world = sceneWorld(ctx, grids);
    const Both rerun = sortedBoth(*grid_world);
    CHECK(rerun.gpu.stats.cells.runs > 1);
    // Nothing known before the first detection: the host's copy held fewer pairs than found,
    // so the GPU sorted (and copied) once more.
    CHECK(std::count_if(rerun.gpu.stats.gpu_passes.begin(), rerun.gpu.stats.gpu_passes.end(),
                        [](const PassTime& p) { return p.name == "pairs-sort"; }) >= 2);
    requireSameSorted(rerun, "coincident grids");
    // A pair filter (the GPU's mask) and pipelined detections in both slots.
    REQUIRE(resting_world->setPairFilter([](ObjectId a, ObjectId b) { return (a + b) % 2 == 0; }));
    requireSameSorted(sortedBoth(*resting_world), "resting scene, filtered");
    DetectSettings gpu_sort;
    gpu_sort.reliable.pair_sort = PairSort::Gpu;
    REQUIRE(grid_world->submit(gpu_sort));
    REQUIRE(grid_world->submit(gpu_sort));
    auto first = grid_world->collect();
    auto second = grid_world->collect();
    REQUIRE(first);
    REQUIRE(second);
    CHECK(first->pairs == rerun.cpu.pairs);
    CHECK(second->pairs == rerun.cpu.pairs);
    CHECK(sameResponses(second->responses, rerun.cpu.responses));
    // Auto: the GPU sorts once the world's last detection had kGpuPairSortFrom pairs or more,
    // on a device that runs long loops (llvmpipe ends them: there the host sorts).
    auto automatic = sceneWorld(ctx, grids);
    auto a1 = automatic->detect();
    REQUIRE(a1);
    REQUIRE(a1->pairs.size() >= kGpuPairSortFrom);
    CHECK_FALSE(a1->stats.reliable.pairs_sorted_on_gpu);  // nothing known before the first
    auto a2 = automatic->detect();
    REQUIRE(a2);
    CHECK(a2->stats.reliable.pairs_sorted_on_gpu == (ctx.device().info.loop_iteration_limit == 0));
    CHECK(a2->pairs == a1->pairs);
    // Below it the one pass sorts them (the next test case), never the device-pairs passes.
    auto small = sceneWorld(ctx, resting);
    for (int k = 0; k < 2; ++k) {
        auto r = small->detect();
        REQUIRE(r);
        REQUIRE(r->pairs.size() < kGpuPairSortFrom);
        CHECK(r->stats.reliable.pairs_sorted_on_gpu == r->stats.reliable.pairs_sorted_in_one_pass);
        CHECK(std::none_of(r->stats.gpu_passes.begin(), r->stats.gpu_passes.end(), [](const PassTime& p) { return p.name == "pairs-sort"; }));
    }
    // Refused by name where the GPU cannot sort.
    const auto refused = [&](DetectSettings s, const char* words) {
        auto r = small->detect(s);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("reliable.pair_sort") && Catch::Contains(words));
    };
    refused({.method = DetectMethod::Peeling, .reliable = {.pair_sort = PairSort::Gpu}}, "reliable method");
    refused({.reliable = {.exact = ExactDecision::Cpu, .pair_sort = PairSort::Gpu}}, "exact decision on the GPU");
    refused({.reliable = {.pair_sort = PairSort(9)}}, "PairSort");
    // Responses on the CPU after a GPU sort (the reference path), and Gpu's refusals.
    DetectSettings cpu_responses;
    cpu_responses.reliable.pair_sort = PairSort::Gpu;
    cpu_responses.reliable.responses = ResponseSource::Cpu;
    auto on_host = grid_world->detect(cpu_responses);
    REQUIRE(on_host);
    CHECK(on_host->stats.reliable.pairs_sorted_on_gpu);
    CHECK_FALSE(on_host->stats.reliable.responses_on_gpu);
    CHECK(sameResponses(on_host->responses, rerun.cpu.responses));
    DetectSettings gpu_responses;
    gpu_responses.reliable.responses = ResponseSource::Gpu;  // sorts on the GPU too, even below kGpuPairSortFrom
    auto on_gpu = small->detect(gpu_responses);
    REQUIRE(on_gpu);
    CHECK(on_gpu->stats.reliable.pairs_sorted_on_gpu);
    CHECK(on_gpu->stats.reliable.responses_on_gpu);
    const auto refused_responses = [&](DetectSettings s, const char* words) {
        s.reliable.responses = ResponseSource::Gpu;
        auto r = small->detect(s);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("reliable.responses") && Catch::Contains(words));
    };
    refused_responses({.reliable = {.pair_sort = PairSort::Cpu}}, "pair_sort");
    refused_responses({.reliable = {.device_pairs = true}}, "device_pairs");
    refused_responses({.reliable = {.exact = ExactDecision::Cpu}}, "exact decision on the GPU");
    auto bad_source = small->detect({.reliable = {.responses = ResponseSource(9)}});
    REQUIRE_FALSE(bad_source);
    CHECK_THAT(bad_source.error().message(), Catch::Contains("reliable.responses") && Catch::Contains("ResponseSource"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("detectInto and collectInto give detect()'s result in the caller's memory", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto grids = coincidentGrids(24);
    REQUIRE(grids);
    auto world = sceneWorld(ctx, *grids);
    auto fresh = world->detect();
    REQUIRE(fresh);
    REQUIRE(fresh->pairs.size() > 100);
    // The same result three frames running, the pairs' memory kept after the first; then a
    // frame with fewer pairs (one grid moved away) and one with more again.
    DetectResult kept;
    const TrianglePair* memory = nullptr;
    DetectSettings gpu_sort;
    if (ctx.device().shader_float64) gpu_sort.reliable.pair_sort = PairSort::Gpu;
    for (int frame = 0; frame < 3; ++frame) {
        REQUIRE(world->detectInto(kept, gpu_sort));
        CHECK(kept.pairs == fresh->pairs);
        CHECK(sameResponses(kept.responses, fresh->responses));
        CHECK(kept.stats.positive_tests == fresh->stats.positive_tests);
        if (frame > 0) CHECK(kept.pairs.data() == memory);  // either pair path: the caller's memory reused
        // Into the caller's memory, where the last detection (the same scene) had enough pairs.
        CHECK(kept.stats.reliable.pairs_named_during_gpu == (ctx.device().shader_float64 && fresh->pairs.size() >= kNameDuringGpuFrom));
        CHECK(kept.stats.host.prepare_ms == 0.0);  // nothing made ready: the caller's memory
        memory = kept.pairs.data();
    }
    REQUIRE(world->setTransform(2, {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0}));
    auto fewer = world->detect();
    REQUIRE(fewer);
    REQUIRE(world->detectInto(kept));
    CHECK(kept.pairs == fewer->pairs);
    CHECK(sameResponses(kept.responses, fewer->responses));
    REQUIRE(world->setTransform(2, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}));
    REQUIRE(world->submit());
    REQUIRE(world->submit());
    REQUIRE(world->collectInto(kept));
    CHECK(kept.pairs == fresh->pairs);
    DetectResult second;
    REQUIRE(world->collectInto(second));
    CHECK(second.pairs == fresh->pairs);
    CHECK(sameResponses(second.responses, fresh->responses));
    // Errors leave the caller's result, not a half-written one, and are returned.
    CHECK_FALSE(world->collectInto(kept));
    DetectSettings bad;
    bad.resolution = 0u;
    CHECK_FALSE(world->detectInto(kept, bad));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// GPU-sorted results under a megabyte (the calling thread makes their memory ready) and the
// host's pair path (none made ready for detect(); detectInto's memory reused): a kept result's
// successor would otherwise fault its new pages in after the wait.
namespace {

Both onePassBoth(CollisionWorld& world, DetectSettings settings = {}) { return sortedBoth(world, settings, PairSort::Auto); }

// `fits`: the one pass must have sorted them (its survivors fit); otherwise the host did.
void requireSameOnePass(const Both& r, const std::string& what, bool fits) {
    INFO(what << ": " << r.gpu.pairs.size() << " pairs");
    CHECK(r.gpu.stats.reliable.pairs_sorted_in_one_pass == fits);
    CHECK(r.gpu.stats.reliable.pairs_sorted_on_gpu == fits);
    CHECK(r.gpu.stats.reliable.responses_on_gpu == (fits && r.gpu.pairs_left_out == 0));
    CHECK_FALSE(r.cpu.stats.reliable.pairs_sorted_in_one_pass);
    CHECK(std::none_of(r.gpu.stats.gpu_passes.begin(), r.gpu.stats.gpu_passes.end(), [](const PassTime& p) { return p.name == "pairs-sort"; }));
    if (fits) CHECK(r.gpu.stats.host.narrow_threads == 1);
    CHECK(r.gpu.pairs == r.cpu.pairs);
    CHECK(sameResponses(r.gpu.responses, r.cpu.responses));
    CHECK(r.gpu.pairs_left_out == r.cpu.pairs_left_out);
    CHECK(r.gpu.incomplete.has_value() == r.cpu.incomplete.has_value());
    CHECK(r.gpu.stats.positive_tests == r.cpu.stats.positive_tests);
    CHECK(r.gpu.stats.cpu_exact_tests == 0);
}

}  // namespace

TEST_CASE("pair sort: few pairs sorted in one GPU pass give the CPU sort's result to the bit", "[api][gpu][reliable][exact]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;  // no exact decision on the GPU: the host sorts
    const TestScene resting = restingScene();
    auto resting_world = sceneWorld(ctx, resting);
    for (std::uint32_t resolution : {1u, 7u, 64u}) {
        DetectSettings s;
        s.resolution = resolution;
        requireSameOnePass(onePassBoth(*resting_world, s), "resting scene, resolution " + std::to_string(resolution), true);
    }
    auto scenes = allTestScenes(0.5f);
    REQUIRE(scenes);
    for (const TestScene& scene : *scenes) {
        auto world = sceneWorld(ctx, scene);
        const Both r = onePassBoth(*world);
        // Survivors repeat a rare pair: below 3,000 pairs they fit the pass's 4,096.
        if (r.cpu.pairs.size() < 3000 || r.cpu.pairs.size() > gpuOnePassSurvivors)
            requireSameOnePass(r, scene.name, r.cpu.pairs.size() < 3000);
        else
            CHECK(r.gpu.pairs == r.cpu.pairs);
    }
    for (auto make : {+[] { return exactlyTouching(true); }, +[] { return zeroAreaTriangle(); }, +[] { return coplanarOpenQuads(false); },
                      +[] { return nonManifoldFin(); }}) {
        auto c = make();
        REQUIRE(c);
        requireSameOnePass(onePassBoth(*sceneWorld(ctx, c->scene)), c->name, true);
    }
    // max_pairs: the first pairs in order, the rest counted, their responses the host's.
    DetectSettings few;
    few.limits.max_pairs = 37;
    const Both cut = onePassBoth(*resting_world, few);
    CHECK(cut.gpu.pairs.size() == 37);
    CHECK(cut.gpu.pairs_left_out > 0);
    requireSameOnePass(cut, "resting scene, max_pairs 37", true);
    // A pair filter the GPU's mask holds.
    REQUIRE(resting_world->setPairFilter([](ObjectId a, ObjectId b) { return (a + b) % 2 == 0; }));
    requireSameOnePass(onePassBoth(*resting_world), "resting scene, filtered", true);
    // detectInto: the caller's memory, the same result.
    DetectResult into;
    REQUIRE(resting_world->detectInto(into));
    CHECK(into.stats.reliable.pairs_sorted_in_one_pass);
    CHECK(into.pairs == onePassBoth(*resting_world).cpu.pairs);
    // At the pass's limit: a self-colliding coplanar fan of 90 triangles (4,005 pairs, each
    // triangle with 89 partners) fits its 4,096 survivors, one of 92 (4,186) does not; and a
    // triangle with 2,000 partners (one run of 2,000 terms).
    for (std::uint32_t n : {90u, 92u}) {
        TestScene fan{"fan of " + std::to_string(n), {}};
        fan.objects.push_back({coplanarFan(n), {.name = "fan", .self_collision = true, .open = true}});
        const Both r = onePassBoth(*sceneWorld(ctx, fan));
        const bool fits = r.gpu.stats.cells.survivors <= gpuOnePassSurvivors;
        REQUIRE(fits == (n == 90));
        INFO(fan.name);
        CHECK(r.cpu.pairs.size() == std::size_t{n} * (n - 1) / 2);
        if (fits) {
            requireSameOnePass(r, fan.name, true);
        } else {  // Auto then sorts on the host or, from kGpuPairSortFrom pairs on, the device-pairs passes
            CHECK_FALSE(r.gpu.stats.reliable.pairs_sorted_in_one_pass);
            CHECK(r.gpu.pairs == r.cpu.pairs);
            CHECK(sameResponses(r.gpu.responses, r.cpu.responses));
        }
    }
    const TestScene comb = combScene(2000);
    auto comb_world = sceneWorld(ctx, comb);
    auto first_comb = comb_world->detect();  // the first detection's copies hold what the pass can write
    REQUIRE(first_comb);
    CHECK(first_comb->stats.reliable.pairs_sorted_in_one_pass);
    const Both teeth = onePassBoth(*comb_world);
    REQUIRE(teeth.cpu.pairs.size() == 2000);
    REQUIRE(teeth.cpu.responses.size() == 2001);
    requireSameOnePass(teeth, comb.name, true);
    // Too many survivors (coincident grids, with a rerun of the cell stage): the host sorts
    // them, the same pairs.
    auto grids = coincidentGrids(40);
    REQUIRE(grids);
    auto grid_world = sceneWorld(ctx, *grids);
    auto first = grid_world->detect();
    REQUIRE(first);
    REQUIRE(first->pairs.size() > gpuOnePassSurvivors);
    CHECK_FALSE(first->stats.reliable.pairs_sorted_in_one_pass);
    DetectSettings host_sort;
    host_sort.reliable.pair_sort = PairSort::Cpu;
    auto on_host = grid_world->detect(host_sort);
    REQUIRE(on_host);
    CHECK(first->pairs == on_host->pairs);
    CHECK(sameResponses(first->responses, on_host->responses));
}

TEST_CASE("detect() makes a small GPU-sorted result's memory ready during the wait, detectInto reuses memory on both paths", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    auto grids = coincidentGrids(12);
    REQUIRE(grids);
    auto world = sceneWorld(ctx, *grids);
    DetectSettings host_sort;
    host_sort.reliable.pair_sort = PairSort::Cpu;
    auto on_host = world->detect(host_sort);
    REQUIRE(on_host);
    const std::size_t n = on_host->pairs.size(), responses = on_host->responses.size();
    INFO(n << " pairs, " << responses << " responses");
    REQUIRE(n * sizeof(TrianglePair) >= (std::size_t{16} << 10));
    REQUIRE(n * sizeof(TrianglePair) < (std::size_t{1} << 20));
    CHECK_FALSE(on_host->stats.reliable.pairs_sorted_on_gpu);
    auto again = world->detect(host_sort);
    REQUIRE(again);
    CHECK(again->pairs == on_host->pairs);
    CHECK(again->stats.host.prepare_ms == 0.0);  // the host's path: nothing made ready
    // detectInto on the host's path writes into the caller's memory.
    DetectResult into;
    REQUIRE(world->detectInto(into, host_sort));
    const TrianglePair* memory = into.pairs.data();
    REQUIRE(world->detectInto(into, host_sort));
    CHECK(into.pairs.data() == memory);
    CHECK(into.pairs == on_host->pairs);
    CHECK(sameResponses(into.responses, on_host->responses));
    CHECK(into.stats.host.prepare_ms == 0.0);
    if (!ctx.device().shader_float64) return;  // no GPU sort without the exact decision on the GPU
    DetectSettings gpu_sort;
    gpu_sort.reliable.pair_sort = PairSort::Gpu;
    auto first = world->detect(gpu_sort);
    REQUIRE(first);
    CHECK(first->pairs == on_host->pairs);
    CHECK(first->stats.reliable.pairs_sorted_on_gpu);
    std::vector<DetectResult> kept;  // every result kept, as the bench's `default` does
    for (int frame = 0; frame < 2; ++frame) {
        auto next = world->detect(gpu_sort);
        REQUIRE(next);
        checkMadeReady(*next, *first);
        kept.push_back(std::move(*next));
    }
    // Fewer pairs (the memory made ready is larger than the result), none, then more again:
    // each time what a new world (nothing made ready) finds.
    const auto moved = [&](float x1, float x2, const char* what) {
        INFO(what);
        DetectResult r = detectMovedAsNew(ctx, *grids, *world, gpu_sort, x1, x2);
        CHECK(r.pairs.size() == r.stats.positive_tests);
        const std::size_t found = r.pairs.size();
        kept.push_back(std::move(r));
        return found;
    };
    const std::size_t third = moved(0.0f, 100.0f, "one grid moved out: a third of the pairs");
    CHECK(third < n / 2);
    CHECK(third > 0);
    CHECK(moved(-100.0f, 100.0f, "every grid apart: no pair") == 0);
    CHECK(moved(0.0f, 0.0f, "back in place: more pairs than the memory made ready") == n);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("detect() makes the next result's memory ready while the GPU works, and its results stay detect()'s", "[api][gpu][reliable]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;  // no GPU sort without the exact decision on the GPU
    auto grids = coincidentGrids(32);  // three coincident grids: over a megabyte of pairs
    REQUIRE(grids);
    DetectSettings gpu_sort;
    gpu_sort.reliable.pair_sort = PairSort::Gpu;
    auto world = sceneWorld(ctx, *grids);
    auto first = world->detect(gpu_sort);  // nothing known yet: no memory made ready
    REQUIRE(first);
    const std::size_t n = first->pairs.size();
    INFO(n << " pairs, " << first->responses.size() << " responses");
    REQUIRE(n * sizeof(TrianglePair) >= (std::size_t{1} << 20));
    CHECK(first->stats.reliable.pairs_sorted_on_gpu);
    CHECK(first->stats.reliable.responses_on_gpu);
    CHECK(first->stats.host.prepare_ms <= first->stats.host.collect_ms);
    for (int frame = 0; frame < 2; ++frame) {
        auto next = world->detect(gpu_sort);
        REQUIRE(next);
        checkMadeReady(*next, *first);
        CHECK(next->stats.reliable.pairs_named_during_gpu);  // into the memory made ready
        CHECK(next->stats.host.prepare_ms + next->stats.host.milestone_ms <= next->stats.host.collect_ms);
    }
    // submit() + collect() make it ready too; detectInto uses the caller's memory instead.
    REQUIRE(world->submit(gpu_sort));
    auto collected = world->collect();
    REQUIRE(collected);
    CHECK(collected->pairs == first->pairs);
    CHECK(collected->pairs.capacity() >= n + n / 8);
    // Fewer pairs (one grid moved half out), then more again: each time what a new world
    // (nothing made ready) finds.
    const auto moved = [&](float x, const char* what) {
        INFO(what);
        const DetectResult r = detectMovedAsNew(ctx, *grids, *world, gpu_sort, 0.0f, x);
        // The memory made ready for a larger result is given back where it is mostly empty.
        INFO(r.pairs.size() << " pairs in a capacity of " << r.pairs.capacity());
        CHECK((r.pairs.capacity() * sizeof(TrianglePair) < (std::size_t{1} << 20) || r.pairs.capacity() <= 2 * r.pairs.size()));
        return r.pairs.size();
    };
    CHECK(moved(0.5f, "one grid moved by half its width") < n);
    CHECK(moved(0.0f, "back in place") == n);
    CHECK(moved(100.0f, "one grid moved out: a third of the pairs") < n / 2);
    CHECK(moved(0.0f, "back in place again") == n);
    // Named only after the fence when asked: the same result, none of it named during the GPU.
    DetectSettings after_fence = gpu_sort;
    after_fence.reliable.pair_naming = PairNaming::AfterFence;
    for (int frame = 0; frame < 2; ++frame) {
        auto r = world->detect(after_fence);
        REQUIRE(r);
        CHECK(r->pairs == first->pairs);
        CHECK(sameResponses(r->responses, first->responses));
        CHECK(r->stats.reliable.responses_on_gpu);
        CHECK_FALSE(r->stats.reliable.pairs_named_during_gpu);
        CHECK(r->stats.host.milestone_ms == 0.0);
        DetectResult into;
        REQUIRE(world->detectInto(into, after_fence));
        CHECK(into.pairs == first->pairs);
        CHECK_FALSE(into.stats.reliable.pairs_named_during_gpu);
    }
    auto named = world->detect(gpu_sort);  // and during the GPU again under Auto
    REQUIRE(named);
    CHECK(named->pairs == first->pairs);
    CHECK(named->stats.reliable.pairs_named_during_gpu);
    // A naming refused at its first piece (more pairs than limits.max_pairs: the host keeps
    // the first ones after the fence) still took its time during the wait: it is in
    // milestone_ms, which with wait_ms and prepare_ms stays within collect_ms.
    DetectSettings capped = gpu_sort;
    capped.limits.max_pairs = n / 2;
    auto refused = world->detect(capped);
    REQUIRE(refused);
    CHECK_FALSE(refused->stats.reliable.pairs_named_during_gpu);
    CHECK(refused->pairs.size() == n / 2);
    CHECK(refused->pairs_left_out == n - n / 2);
    CHECK(std::equal(refused->pairs.begin(), refused->pairs.end(), first->pairs.begin()));
    CHECK(refused->stats.host.milestone_ms > 0.0);
    const HostStats& h = refused->stats.host;
    CHECK(h.prepare_ms + h.milestone_ms + h.wait_ms <= h.collect_ms);
    auto bad = world->detect({.reliable = {.pair_naming = PairNaming(7)}});
    REQUIRE_FALSE(bad);
    CHECK_THAT(bad.error().message(), Catch::Contains("reliable.pair_naming") && Catch::Contains("PairNaming"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
