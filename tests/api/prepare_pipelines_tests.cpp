// CollisionWorld::preparePipelines: after it, no detection with the settings it was given,
// on any world of the Context and whatever form its scene picks, compiles a pipeline.
#include <catch2/catch.hpp>

#include <mutex>

#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scene_world.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

std::uint64_t pipelinesCreated(ValidatedContext& ctx) {
    std::lock_guard lock(ctx.device().pipelines_mutex);
    return ctx.device().pipelines_created;
}

// Detects with `s` on `world` and returns how many pipelines the detection compiled.
std::uint64_t compiledBy(ValidatedContext& ctx, CollisionWorld& world, const DetectSettings& s) {
    const std::uint64_t before = pipelinesCreated(ctx);
    auto r = world.detect(s);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    CHECK_FALSE(r->pairs.empty());
    return pipelinesCreated(ctx) - before;
}

}  // namespace

TEST_CASE("preparePipelines: later detections of the reliable method compile nothing, whatever form they take", "[api][gpu][pipelines]") {
    ValidatedContext ctx;
    auto spheres = overlappingSpheres();
    REQUIRE(spheres);
    auto world = sceneWorld(ctx, *spheres);
    const std::uint64_t before = pipelinesCreated(ctx);  // the world's own (made at its creation)

    // What an engine asks for at load time: the default detection, its results on the GPU
    // too (device pairs and responses), the GPU's sort and responses for the host, and
    // proximity. Both forms of the exact decision follow from ExactPass::Auto.
    DetectSettings all;
    all.reliable.pair_sort = PairSort::Gpu;
    all.reliable.responses = ResponseSource::Gpu;
    all.proximity.distance = 0.01;
    DetectSettings on_gpu;
    on_gpu.reliable.device_pairs = true;
    on_gpu.reliable.device_responses = true;
    std::uint32_t made = 0;
    for (const DetectSettings& s : {DetectSettings{}, all, on_gpu}) {
        auto prepared = world->preparePipelines(s);
        INFO((prepared ? std::string() : prepared.error().message()));
        REQUIRE(prepared);
        CHECK(prepared->ms > 0);
        made += prepared->created;
    }
    CHECK(made > 10);
    CHECK(pipelinesCreated(ctx) - before == made);
    // Preparing again makes nothing.
    auto again = world->preparePipelines(all);
    REQUIRE(again);
    CHECK(again->created == 0u);

    // Each form the settings or the scene may pick, on this world and on a new one.
    DetectSettings inline_exact, queued_exact, host_sort, plain_proximity;
    inline_exact.reliable.exact_pass = ExactPass::Inline;
    queued_exact.reliable.exact_pass = ExactPass::Queued;
    host_sort.reliable.pair_sort = PairSort::Cpu;
    host_sort.reliable.responses = ResponseSource::Cpu;
    plain_proximity.proximity.distance = 0.02;
    for (const DetectSettings& s : {DetectSettings{}, inline_exact, queued_exact, all, on_gpu, host_sort, plain_proximity})
        CHECK(compiledBy(ctx, *world, s) == 0u);
    auto other = sceneWorld(ctx, *spheres);
    CHECK(compiledBy(ctx, *other, queued_exact) == 0u);
    CHECK(compiledBy(ctx, *other, all) == 0u);

    // What was not prepared is still compiled by the detection that first needs it: the
    // count above can tell.
    DetectSettings contacts;
    contacts.contacts.objects = true;
    CHECK(compiledBy(ctx, *world, contacts) > 0u);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("preparePipelines: the peeling method's samplers and object contacts, with a detection in flight", "[api][gpu][pipelines]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox();
    REQUIRE(scene);
    auto world = sceneWorld(ctx, *scene);
    // A reliable detection in flight: preparing submits nothing, so it may run beside it.
    REQUIRE(world->submit({}));
    DetectSettings peeling;
    peeling.method = DetectMethod::Peeling;
    peeling.resolution = 256;
    peeling.contacts.objects = true;
    auto prepared = world->preparePipelines(peeling);
    INFO((prepared ? std::string() : prepared.error().message()));
    REQUIRE(prepared);
    CHECK(prepared->created > 0u);
    auto collected = world->collect();
    REQUIRE(collected);

    // Auto prepared both samplers: an explicit backend compiles nothing.
    DetectSettings raster = peeling, compute = peeling;
    raster.peeling.backend = SamplingBackend::Raster;
    compute.peeling.backend = SamplingBackend::Compute;
    CHECK(compiledBy(ctx, *world, raster) == 0u);
    CHECK(compiledBy(ctx, *world, compute) == 0u);
    CHECK(compiledBy(ctx, *world, peeling) == 0u);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("preparePipelines: bad settings get detect()'s errors and compile nothing", "[api][gpu][pipelines]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox();
    REQUIRE(scene);
    auto world = sceneWorld(ctx, *scene);
    const std::uint64_t before = pipelinesCreated(ctx);
    DetectSettings bad_method;
    bad_method.method = static_cast<DetectMethod>(77);
    DetectSettings bad_resolution;
    bad_resolution.resolution = 0;
    DetectSettings rays_on_reliable;
    rays_on_reliable.peeling.collision_rays = true;
    for (const auto& [s, words] : {std::pair{bad_method, "method 77"}, std::pair{bad_resolution, "resolution"},
                                   std::pair{rays_on_reliable, "collision_rays belongs to the peeling method"}}) {
        auto refused = world->preparePipelines(s);
        REQUIRE_FALSE(refused);
        CHECK(refused.error().code() == ErrorCode::InvalidArgument);
        INFO(refused.error().message());
        CHECK(mentions(refused.error(), words));
        auto detected = world->detect(s);
        REQUIRE_FALSE(detected);
        CHECK(detected.error().message() == refused.error().message());
    }
    CHECK(pipelinesCreated(ctx) == before);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
