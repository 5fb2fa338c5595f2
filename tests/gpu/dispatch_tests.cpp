// Every dispatch is split against the device's maxComputeWorkGroupCount:
// the row layout itself, the same results when the limit is forced down to a few
// workgroups (every per-pixel, per-triangle, per-row and per-block dispatch then spans
// rows with an overhang), and a detection at the largest resolution this device can hold,
// with the validation layer on (before: groupCountX 65536 at resolution 4096).
#include <catch2/catch.hpp>

#include <algorithm>

#include "broad/broad_phase.hpp"
#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "support/gpu_fixture.hpp"
#include "support/pathological_scenes.hpp"
#include "support/test_scenes.hpp"
#include "vk/device.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

TEST_CASE("dispatchShape lays workgroups out in rows within the limits", "[gpu][dispatch]") {
    using passes::dispatchShape;
    auto same = [](passes::DispatchShape s, std::uint32_t x, std::uint32_t y) { return s.x == x && s.y == y; };
    CHECK(same(dispatchShape(0, 65535, 65535), 0, 1));
    CHECK(same(dispatchShape(1, 65535, 65535), 1, 1));
    CHECK(same(dispatchShape(65535, 65535, 65535), 65535, 1));
    CHECK(same(dispatchShape(65536, 65535, 65535), 65535, 2));  // resolution 4096, one group per 256 pixels
    CHECK(same(dispatchShape(std::uint64_t{1} << 22, 65535, 65535), 65535, 65));  // 2^30 triangles
    CHECK(same(dispatchShape(10, 3, 4), 3, 4));
    CHECK(same(dispatchShape(13, 3, 4), 0, 0));  // more than x * y: refused, never recorded
}

TEST_CASE("dispatches forced into rows of three workgroups give the same results", "[gpu][dispatch]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox(0.5f);
    REQUIRE(scene);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    std::uint32_t* limit = ctx.device().properties.limits.maxComputeWorkGroupCount;
    const std::uint32_t real = limit[0];
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
        for (PackingMethod packing : {PackingMethod::Scan, PackingMethod::Paper}) {
            INFO(toString(backend) << ", " << (packing == PackingMethod::Scan ? "scan" : "paper") << " packing");
            DetectSettings s;
            s.resolution = 64;  // 16 workgroups per pixel pass: 6 rows of 3, the last with 2 over
            s.peeling.backend = backend;
            s.peeling.packing = packing;
            limit[0] = real;
            auto wide = (*world)->detect(s);
            limit[0] = 3;
            auto rows = (*world)->detect(s);
            limit[0] = real;
            REQUIRE(wide);
            REQUIRE(rows);
            CHECK((rows->pairs == wide->pairs));
            CHECK(rows->stats.collision_rays == wide->stats.collision_rays);
            CHECK(rows->stats.triangles_downloaded == wide->stats.triangles_downloaded);
            CHECK(rows->stats.peeling.depth_complexity == wide->stats.peeling.depth_complexity);
            CHECK_FALSE(rows->pairs.empty());
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("the largest resolution this device holds runs with the validation layer quiet", "[gpu][dispatch]") {
    ValidatedContext ctx;
    // Two crossing triangles: two layers, so the time goes to the per-pixel passes alone.
    auto c = scaledCrossing(1.0f);
    REQUIRE(c);
    const TestScene* scene = &c->scene;
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    const vk::Device& dev = ctx.device();
    VkDeviceSize smallest_heap = ~VkDeviceSize(0);
    for (std::uint32_t h = 0; h < dev.memory.memoryHeapCount; ++h)
        if (dev.memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) smallest_heap = std::min(smallest_heap, dev.memory.memoryHeaps[h].size);
    const auto triangles = static_cast<std::uint32_t>((*world)->triangleCount());
    // The largest power of two whose buffers the heap holds and the framebuffer fits;
    // at most 4096 here (the first past 65,535 workgroups per pixel pass), to keep CI in
    // seconds: larger devices run larger ones in tools/stability/pathological_report.
    std::uint32_t largest = 0;
    for (std::uint32_t n = 64; n <= 4096; n *= 2)
        if (passes::broadPhaseMemory(n, triangles, 2) <= smallest_heap && n <= dev.properties.limits.maxFramebufferWidth) largest = n;
    REQUIRE(largest >= 64);
    if (largest < 4096) WARN("this device holds at most resolution " << largest << ": the 65,536-group case is not reached");
    DetectSettings s = c->settings;
    s.resolution = largest;
    // One timeout covers a detection's submissions: lavapipe on two busy cores takes about
    // half a minute for one detection at 4096, past the default. This test is about validation.
    s.limits.timeout_ms = 600000;
    auto objects = scene->reference();
    auto reference = computeReferencePairs(objects);
    REQUIRE(reference);
    // The compute backend at half the resolution: at 4096 on lavapipe's 2 GiB heap its
    // fragment lists do not fit beside the peeling buffers and its steps draw instead
    // (ComputeSampler::prepare), which repeated the raster run's minute; at 2048 its own
    // passes run (16,384 groups per pixel pass; rows of groups: "dispatches forced into rows").
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
        const std::uint32_t resolution = backend == SamplingBackend::Compute ? std::max(64u, largest / 2) : largest;
        s.resolution = resolution;
        INFO("resolution " << resolution << ", " << toString(backend));
        s.peeling.backend = backend;
        auto r = (*world)->detect(s);
        if (!r) FAIL(r.error().message());
        const PairComparison cmp = comparePairs(r->pairs, *reference);
        CHECK(cmp.false_positives == 0);
        CHECK(cmp.recall > 0.99);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a resolution past the framebuffer limit samples in compute or is refused by name", "[gpu][dispatch]") {
    ValidatedContext ctx;
    auto c = scaledCrossing(1.0f);
    REQUIRE(c);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : c->scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    VkPhysicalDeviceLimits& limits = ctx.device().properties.limits;
    const VkPhysicalDeviceLimits real = limits;
    limits.maxFramebufferWidth = 32;  // as if the device rendered at most 32 x 32
    DetectSettings s = c->settings;   // resolution 64
    s.method = DetectMethod::Peeling;  // the reliable method rasterises nothing
    s.peeling.backend = SamplingBackend::Raster;
    auto raster = (*world)->detect(s);
    s.peeling.backend = SamplingBackend::Auto;
    auto automatic = (*world)->detect(s);
    s.peeling.coverage = Coverage::Dilate;
    auto dilated = (*world)->detect(s);
    limits = real;
    REQUIRE_FALSE(raster);
    CHECK(raster.error().code() == ErrorCode::UnsupportedFeature);
    CHECK(raster.error().message().find("largest framebuffer") != std::string::npos);
    REQUIRE(automatic);
    CHECK(automatic->stats.peeling.backend == SamplingBackend::Compute);
    CHECK(automatic->stats.peeling.backend_reason.find("framebuffer") != std::string::npos);
    CHECK((automatic->pairs == *c->reference));
    REQUIRE_FALSE(dilated);
    CHECK(dilated.error().code() == ErrorCode::UnsupportedFeature);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
