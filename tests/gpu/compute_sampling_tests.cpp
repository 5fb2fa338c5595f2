// The compute sampling backend against the raster backend on the same device, validation
// on: the same depth complexity, collision-ray image (pixel for pixel) and records (byte
// for byte) on generated scenes, single and dual peeling, layer caps, open surfaces,
// one-invocation and tiled triangles, and samples exactly on edges; with depth-aware
// separation also the rays' depth intervals (bit for bit).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "broad/peeling/sampling/backend_choice.hpp"
#include "mesh/mesh_upload.hpp"
#include "graph/executor.hpp"
#include "shaders/all.hpp"
#include "support/gpu_fixture.hpp"
#include "support/record_dispatch.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

// Rotation about an arbitrary axis and a move.
HostMesh placed(Result<HostMesh> made, float ax, float ay, float az, float angle, Float3 t) {
    REQUIRE(made);
    HostMesh m = std::move(*made);
    const float len = std::sqrt(ax * ax + ay * ay + az * az);
    ax /= len, ay /= len, az /= len;
    const float c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    Transform3x4 tr = {c + ax * ax * k,      ax * ay * k - az * s, ax * az * k + ay * s, t.x,
                       ay * ax * k + az * s, c + ay * ay * k,      ay * az * k - ax * s, t.y,
                       az * ax * k - ay * s, az * ay * k + ax * s, c + az * az * k,      t.z};
    REQUIRE(transformMesh(m, tr));
    return m;
}

HostMesh moved(Result<HostMesh> made, Float3 t) {
    REQUIRE(made);
    HostMesh m = std::move(*made);
    REQUIRE(transformMesh(m, Transform3x4{1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}));
    return m;
}

struct Scene {
    std::vector<HostMesh> meshes;
    std::vector<bool> open;
};

struct Compared {
    BroadPhaseResult raster, compute;
};

BroadPhaseResult runWith(test::ValidatedContext& ctx, BroadPhase& bp, const UploadedMeshes& up, BroadPhaseSettings s,
                         SamplingBackend backend) {
    s.backend = backend;
    s.keep_ray_image = true;
    auto r = bp.run(up.meshes, s);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    CHECK(r->backend == backend);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    return std::move(*r);
}

// Both backends, then every output compared exactly.
Compared compareBackends(test::ValidatedContext& ctx, BroadPhase& bp, const Scene& scene, const BroadPhaseSettings& s) {
    std::vector<const HostMesh*> ptrs;
    for (const auto& m : scene.meshes) ptrs.push_back(&m);
    auto up = uploadMeshes(ctx.device(), ptrs, {.open = scene.open});
    REQUIRE(up);
    Compared c{runWith(ctx, bp, *up, s, SamplingBackend::Raster), runWith(ctx, bp, *up, s, SamplingBackend::Compute)};
    const auto& a = c.raster;
    const auto& b = c.compute;
    CHECK(a.depth_complexity == b.depth_complexity);
    CHECK(a.fragments == b.fragments);
    CHECK(a.layers == b.layers);
    CHECK(a.peel_steps == b.peel_steps);
    CHECK(a.collision_rays == b.collision_rays);
    REQUIRE(a.ray_image.size() == b.ray_image.size());
    std::size_t differ = 0;
    std::ostringstream where;
    const std::uint32_t n = s.resolution;
    for (std::size_t i = 0; i < a.ray_image.size(); ++i)
        if (a.ray_image[i] != b.ray_image[i] && differ++ < 8) where << " (" << i % n << "," << i / n << ")";
    INFO("rays that differ:" << where.str());
    CHECK(differ == 0);
    REQUIRE(a.records.size() == b.records.size());
    // memcmp of empty vectors would pass null pointers (undefined; UBSan reports it).
    CHECK((a.records.empty() || std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(CandidateTriangle)) == 0));
    CHECK(a.fragments > 0);
    REQUIRE(a.ray_depth.size() == (s.depth_aware ? a.ray_image.size() : 0));
    REQUIRE(b.ray_depth.size() == a.ray_depth.size());
    CHECK((a.ray_depth.empty() || std::memcmp(a.ray_depth.data(), b.ray_depth.data(), a.ray_depth.size() * sizeof(a.ray_depth[0])) == 0));
    return c;
}

std::unique_ptr<BroadPhase> makeBroadPhase(test::ValidatedContext& ctx) {
    auto created = BroadPhase::create(ctx.device(), PeelingMethod::create);
    REQUIRE(created);
    return std::move(*created);
}

struct Fixture {
    test::ValidatedContext ctx;
    std::unique_ptr<BroadPhase> owned = makeBroadPhase(ctx);
    BroadPhase& bp = *owned;
};

Scene spheresAndBox() {
    Scene s;
    s.meshes.push_back(placed(uvSphere(1.0f, 20, 10), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}));
    s.meshes.push_back(placed(uvSphere(0.9f, 18, 9), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}));
    s.meshes.push_back(placed(box({0.5f, 0.5f, 0.5f}, 3), 0.2f, 0.4f, 1, 1.1f, {0.1f, 0.8f, -0.3f}));
    return s;
}

}  // namespace

TEST_CASE_METHOD(Fixture, "compute sampling equals raster: spheres and a box, single and dual, 64 to 256", "[gpu][compute-sampling]") {
    const Scene scene = spheresAndBox();
    for (std::uint32_t res : {64u, 256u})
        for (bool dual : {false, true}) {
            INFO("resolution " << res << (dual ? " dual" : " single"));
            BroadPhaseSettings s;
            s.resolution = res;
            s.dual = dual;
            s.direction = {0.2f, -0.3f, 1.0f};
            Compared c = compareBackends(ctx, bp, scene, s);
            CHECK(c.raster.collision_rays > 0);
        }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster: interlocked tori and a twisted tube", "[gpu][compute-sampling]") {
    Scene scene;
    scene.meshes.push_back(placed(torus(0.9f, 0.3f, 32, 12), 1, 0.1f, 0.2f, 0.3f, {-0.45f, 0.02f, 0.01f}));
    scene.meshes.push_back(placed(torus(0.9f, 0.3f, 32, 12), 0.1f, 1, 0.3f, 1.5f, {0.45f, -0.03f, 0.05f}));
    scene.meshes.push_back(placed(twistedTube(1.0f, 0.2f, 64, 10, 1.5f), 0.2f, 0.3f, 1, 0.2f, {0.1f, 0.9f, -0.2f}));
    for (bool dual : {false, true}) {
        INFO((dual ? "dual" : "single"));
        BroadPhaseSettings s;
        s.resolution = 128;
        s.dual = dual;
        s.direction = {0.1f, 0.2f, 1.0f};
        Compared c = compareBackends(ctx, bp, scene, s);
        CHECK(c.raster.collision_rays > 0);
    }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster: layer caps", "[gpu][compute-sampling]") {
    Scene scene;
    for (int i = 0; i < 4; ++i)
        scene.meshes.push_back(placed(box({0.35f, 0.35f, 0.35f}, 2), 0.3f, 1, 0.2f, 0.1f * float(i) + 0.2f,
                                      {0.03f, 0.02f, -1.8f + 1.2f * float(i)}));
    for (std::uint32_t cap : {3u, 4u})
        for (bool dual : {false, true}) {
            INFO("cap " << cap << (dual ? " dual" : " single"));
            BroadPhaseSettings s;
            s.resolution = 64;
            s.layer_cap = cap;
            s.dual = dual;
            if (cap == 3u) s.compute.list_budget_bytes = 0;  // drawing per step
            Compared c = compareBackends(ctx, bp, scene, s);
            CHECK(c.raster.depth_complexity == 8);
            CHECK(c.compute.layers == cap);
            CHECK(c.raster.collision_rays > 0);
        }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster: open cloth by depth proximity", "[gpu][compute-sampling]") {
    Scene scene;
    scene.meshes.push_back(placed(clothGrid(3.0f, 3.0f, 16, 16, {.sag = 0.3f}), 1, 0.1f, 0.2f, 1.3f, {0.02f, 0.03f, 0.01f}));
    scene.meshes.push_back(placed(uvSphere(0.8f, 16, 8), 0.3f, 1, 0.2f, 0.41f, {0.1f, 0.05f, 0.2f}));
    scene.open = {true, false};
    for (bool dual : {false, true}) {
        INFO((dual ? "dual" : "single"));
        BroadPhaseSettings s;
        s.resolution = 128;
        s.dual = dual;
        s.open_epsilon = 0.05f;
        if (dual) s.compute.list_budget_bytes = 0;  // drawing per step
        Compared c = compareBackends(ctx, bp, scene, s);
        CHECK(c.raster.collision_rays > 0);
    }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster: samples exactly on edges follow the tie rule", "[gpu][compute-sampling]") {
    // Axis-aligned boxes in a region that puts their silhouette edges, the diagonals of
    // their faces and many vertices exactly on pixel centres of a 64x64 image.
    Scene scene;
    scene.meshes.push_back(moved(box({0.53125f, 0.53125f, 0.5f}, 2), {0, 0, 0.01f}));
    scene.meshes.push_back(moved(box({0.28125f, 0.78125f, 0.25f}, 3), {0.5f, 0.25f, 0.3f}));
    scene.meshes.push_back(moved(box({0.40625f, 0.15625f, 0.3f}, 1), {-0.75f, -0.6875f, -0.2f}));
    // Corners half-way between two sub-pixel positions (1/512 px = 1/8192 here) snap to the
    // even one: the edges then pass exactly through pixel centres again.
    constexpr float half_step = 1.0f / 8192.0f;
    scene.meshes.push_back(moved(box({0.15625f + half_step, 0.21875f + 3 * half_step, 0.2f}, 1), {1.25f, -1.25f, 0.4f}));
    BroadPhaseSettings s;
    s.resolution = 64;
    s.region = std::array<float, 6>{-2, -2, -2, 2, 2, 2};
    for (bool dual : {false, true}) {
        INFO((dual ? "dual" : "single"));
        s.dual = dual;
        Compared c = compareBackends(ctx, bp, scene, s);
        CHECK(c.raster.collision_rays > 0);
    }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster whether triangles take one invocation or tiles, peeled from lists or by drawing", "[gpu][compute-sampling]") {
    // Coarse boxes have faces of a few big triangles; the fine sphere has small ones.
    Scene scene;
    scene.meshes.push_back(placed(box({1.2f, 1.2f, 1.2f}, 1), 0.3f, 1, 0.2f, 0.41f, {-0.3f, 0.02f, 0.03f}));
    scene.meshes.push_back(placed(box({0.6f, 0.6f, 0.6f}, 1), 1, 0.2f, 0.5f, 0.73f, {0.9f, -0.11f, 0.29f}));
    scene.meshes.push_back(placed(uvSphere(0.7f, 48, 24), 0.3f, 1, 0.2f, 0.41f, {-0.6f, 0.5f, 0.3f}));
    for (std::uint32_t small_box : {0u, 64u, 1u << 20}) {
        INFO("small box " << small_box);
        BroadPhaseSettings s;
        s.resolution = 256;
        s.dual = small_box == 64u;
        s.compute.small_box = small_box;
        // Fragment lists, one layer stored by the count pass and the rest gathered (this is
        // the first compute run of this broad phase); drawing per step with step 0 in the
        // count pass; drawing every step.
        s.compute.list_budget_bytes = small_box == 0u ? s.compute.list_budget_bytes : 0u;
        s.compute.list_layers = 1;
        s.compute.fuse_first_step = small_box != 64u;
        Compared c = compareBackends(ctx, bp, scene, s);
        CHECK(c.compute.compute_fragment_lists == (small_box == 0u));
        const bool gathered = std::any_of(c.compute.passes.begin(), c.compute.passes.end(),
                                          [](const graph::PassTiming& p) { return p.name == "csample-gather"; });
        CHECK(gathered == (small_box == 0u));
        CHECK(c.raster.collision_rays > 0);
        if (small_box == 0u) CHECK(c.compute.compute_small == 0);
        CHECK(c.compute.compute_big > 0);  // at 256, the boxes' faces exceed the 64-px extent
        CHECK(c.compute.compute_items >= c.compute.compute_big);
    }
}

TEST_CASE_METHOD(Fixture, "compute sampling equals raster with depth-aware separation: every scene above", "[gpu][compute-sampling]") {
    Scene tori;
    tori.meshes.push_back(placed(torus(0.9f, 0.3f, 32, 12), 1, 0.1f, 0.2f, 0.3f, {-0.45f, 0.02f, 0.01f}));
    tori.meshes.push_back(placed(torus(0.9f, 0.3f, 32, 12), 0.1f, 1, 0.3f, 1.5f, {0.45f, -0.03f, 0.05f}));
    tori.meshes.push_back(placed(twistedTube(1.0f, 0.2f, 64, 10, 1.5f), 0.2f, 0.3f, 1, 0.2f, {0.1f, 0.9f, -0.2f}));
    Scene boxes;
    for (int i = 0; i < 4; ++i)
        boxes.meshes.push_back(placed(box({0.35f, 0.35f, 0.35f}, 2), 0.3f, 1, 0.2f, 0.1f * float(i) + 0.2f,
                                      {0.03f, 0.02f, -1.8f + 1.2f * float(i)}));
    Scene cloth;
    cloth.meshes.push_back(placed(clothGrid(3.0f, 3.0f, 16, 16, {.sag = 0.3f}), 1, 0.1f, 0.2f, 1.3f, {0.02f, 0.03f, 0.01f}));
    cloth.meshes.push_back(placed(uvSphere(0.8f, 16, 8), 0.3f, 1, 0.2f, 0.41f, {0.1f, 0.05f, 0.2f}));
    cloth.open = {true, false};
    struct Case {
        const char* name;
        const Scene* scene;
        std::uint32_t resolution, cap;
    };
    const Scene spheres = spheresAndBox();
    for (const Case& k : {Case{"spheres and a box", &spheres, 128, 0}, Case{"tori and a twisted tube", &tori, 128, 0},
                          Case{"boxes in a row, capped", &boxes, 64, 3}, Case{"open cloth", &cloth, 128, 0}})
        for (bool dual : {false, true}) {
            INFO(k.name << (dual ? ", dual" : ", single"));
            BroadPhaseSettings s;
            s.resolution = k.resolution;
            s.layer_cap = k.cap;
            s.dual = dual;
            s.open_epsilon = 0.05f;
            s.direction = {0.1f, 0.2f, 1.0f};
            s.depth_aware = true;
            if (dual) s.compute.list_budget_bytes = 0;  // drawing per step
            Compared c = compareBackends(ctx, bp, *k.scene, s);
            CHECK(c.raster.collision_rays > 0);
            CHECK_FALSE(c.raster.records.empty());
        }
}

TEST_CASE_METHOD(Fixture, "the backend is reported with a reason, and Auto follows the device", "[gpu][compute-sampling]") {
    const Scene scene = spheresAndBox();
    std::vector<const HostMesh*> ptrs;
    for (const auto& m : scene.meshes) ptrs.push_back(&m);
    auto up = uploadMeshes(ctx.device(), ptrs);
    REQUIRE(up);
    BroadPhaseSettings s;
    s.resolution = 64;
    auto r = bp.run(up->meshes, s);
    REQUIRE(r);
    CHECK(r->backend != SamplingBackend::Auto);
    CHECK_FALSE(r->backend_reason.empty());
    const auto& props = ctx.device().properties;
    const BackendChoice expected = chooseSamplingBackend(props, computeSamplingSupported(ctx.device()), SamplingBackend::Auto, 64, r->triangles, -1.0);
    CHECK(r->backend == expected.backend);
    s.backend = SamplingBackend::Compute;
    auto c = bp.run(up->meshes, s);
    REQUIRE(c);
    CHECK(c->backend == SamplingBackend::Compute);
    CHECK(c->backend_reason == "requested");
    // The per-pass names stay those of the raster backend, so timings line up; step 0's
    // peeling is done by the depth-complexity pass unless the tuning says otherwise.
    auto names = [](const BroadPhaseResult& res) {
        std::vector<std::string> out;
        for (const auto& p : res.passes) out.push_back(p.name);
        return out;
    };
    auto has = [](const std::vector<std::string>& v, const char* name) { return std::find(v.begin(), v.end(), name) != v.end(); };
    REQUIRE(c->peel_steps >= 2);
    REQUIRE(c->depth_complexity <= s.compute.list_layers);
    CHECK(c->compute_fragment_lists);
    const auto listed = names(*c);
    for (const char* name : {"csample-setup", "depth-complexity", "peel[0]", "classify[0]", "peel[1]"}) CHECK(has(listed, name));
    CHECK_FALSE(has(listed, "csample-gather"));  // the count pass stored every key
    s.compute.list_budget_bytes = 0;  // draw per step, step 0 in the count pass
    auto fused = bp.run(up->meshes, s);
    REQUIRE(fused);
    CHECK_FALSE(fused->compute_fragment_lists);
    CHECK_FALSE(has(names(*fused), "peel[0]"));
    CHECK_FALSE(has(names(*fused), "csample-gather"));
    CHECK(has(names(*fused), "peel[1]"));
    s.compute.fuse_first_step = false;
    auto unfused = bp.run(up->meshes, s);
    REQUIRE(unfused);
    CHECK(has(names(*unfused), "peel[0]"));
    s.compute = {};
    s.compute.list_budget_bytes = 1;  // the lists do not fit: drawing per step
    auto fallback = bp.run(up->meshes, s);
    REQUIRE(fallback);
    CHECK_FALSE(fallback->compute_fragment_lists);
    CHECK(has(names(*fallback), "peel[0]"));
    for (const auto* other : {&*fused, &*unfused, &*fallback}) CHECK(other->collision_rays == c->collision_rays);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(Fixture, "fragment lists grow to the depth complexity a run needed", "[gpu][compute-sampling]") {
    Scene scene;
    for (int i = 0; i < 4; ++i)
        scene.meshes.push_back(placed(uvSphere(0.5f, 12, 6), 0.3f, 1, 0.2f, 0.2f, {0.02f, 0.03f, -1.8f + 1.2f * float(i)}));
    std::vector<const HostMesh*> ptrs;
    for (const auto& m : scene.meshes) ptrs.push_back(&m);
    auto up = uploadMeshes(ctx.device(), ptrs);
    REQUIRE(up);
    BroadPhaseSettings s;
    s.resolution = 64;
    s.backend = SamplingBackend::Compute;
    s.keep_ray_image = true;
    s.compute.list_layers = 2;
    auto gathered = [](const BroadPhaseResult& r) {
        return std::any_of(r.passes.begin(), r.passes.end(), [](const graph::PassTiming& p) { return p.name == "csample-gather"; });
    };
    auto first = bp.run(up->meshes, s);
    REQUIRE(first);
    CHECK(first->depth_complexity == 8);
    CHECK(gathered(*first));  // 2 layers stored, 8 needed
    auto second = bp.run(up->meshes, s);
    REQUIRE(second);
    CHECK_FALSE(gathered(*second));  // 8 stored now
    CHECK(second->ray_image == first->ray_image);
    CHECK(second->collision_rays == 0);
    s.compute.list_budget_bytes = 64 * 64 * 8 * 4;  // room for 4 layers: no lists at all
    auto drawn = bp.run(up->meshes, s);
    REQUIRE(drawn);
    CHECK_FALSE(drawn->compute_fragment_lists);
    CHECK(drawn->ray_image == first->ray_image);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The bin pass alone (csample_bin.comp): each big triangle gets ceil(tiles / tiles per item)
// work items, all written by the invocation that bins it, and tiles per item is 1 while
// every tile fits the item buffer. A triangle whose pixel box is a whole 4096^2 image has
// 512^2 = 262,144 tiles: before, that was one loop of 262,144 iterations, and llvmpipe
// ends a shader invocation's loops past 65,535 iterations without an error
// (DeviceInfo::loop_iteration_limit): three quarters of the items were never written, and
// the draw passes read whatever the buffer held instead (a tile drawn twice, tiles never).
TEST_CASE("compute sampling: the bin pass writes every work item of a triangle with 262,144 tiles", "[gpu][compute-sampling][limits]") {
    test::ValidatedContext ctx;
    vk::Device& device = ctx.device();
    auto pipeline = vk::Pipeline::createCompute(device, shaders::csample_bin_comp, {}, sizeof(gpu::Push), "bin-test");
    REQUIRE(pipeline);
    constexpr std::uint32_t kId = 5, kTriangles = kId + 1, kTiles = 512 * 512;
    constexpr std::uint32_t kCapacity = kTiles + gpu::kCsExtraItems;  // one tile per item fits
    using vk::MemoryKind;
    auto frame = vk::Buffer::create(device, sizeof(gpu::Frame), 0, MemoryKind::Upload, "bin-frame");
    auto cs = vk::Buffer::create(device, sizeof(gpu::CsFrame), 0, MemoryKind::Upload, "bin-cs-frame");
    auto tris = vk::Buffer::create(device, kTriangles * sizeof(gpu::CsTriangle), 0, MemoryKind::Upload, "bin-triangles");
    auto big = vk::Buffer::create(device, 4, 0, MemoryKind::Upload, "bin-big");
    auto counters = vk::Buffer::create(device, sizeof(gpu::CsCounters), 0, MemoryKind::Readback, "bin-counters");
    auto items = vk::Buffer::create(device, VkDeviceSize(kCapacity) * 8, 0, MemoryKind::Readback, "bin-items");
    REQUIRE((frame && cs && tris && big && counters && items));
    auto* t = static_cast<gpu::CsTriangle*>(tris->mapped());
    std::memset(t, 0, kTriangles * sizeof(gpu::CsTriangle));
    t[kId].box_lo = 0;
    t[kId].box_hi = 4095u | (4095u << 16);
    tris->flush();
    *static_cast<std::uint32_t*>(big->mapped()) = kId;
    big->flush();
    gpu::CsCounters c{};
    c.big_count = 1;
    c.tiles_per_item = 1;
    c.tiles = kTiles;
    std::memcpy(counters->mapped(), &c, sizeof c);
    counters->flush();
    std::memset(items->mapped(), 0xFF, VkDeviceSize(kCapacity) * 8);  // unwritten: (~0, ~0)
    items->flush();
    gpu::CsFrame cf{};
    cf.triangles = tris->address();
    cf.big = big->address();
    cf.items = items->address();
    cf.counters = counters->address();
    cf.item_capacity = kCapacity;
    std::memcpy(cs->mapped(), &cf, sizeof cf);
    cs->flush();
    gpu::Frame f{};
    f.compute_sampling = cs->address();
    std::memcpy(frame->mapped(), &f, sizeof f);
    frame->flush();
    graph::Graph g;
    const auto items_id = g.importBuffer("bin-items", *items, true);
    const auto counters_id = g.importBuffer("bin-counters", *counters, true);
    const VkPipeline handle = pipeline->handle();
    const VkPipelineLayout layout = pipeline->layout();
    const VkDeviceAddress frame_address = frame->address();
    g.addPass("bin", graph::PassKind::Compute).readWrite(counters_id).write(items_id).record([=](graph::PassContext& pc) {
        gpu::Push push{frame_address, 0, 0, 0, 0};
        test::recordDispatch(pc, handle, layout, push);
    });
    graph::Executor executor(device);
    REQUIRE(executor.run(g));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    counters->invalidate();
    items->invalidate();
    std::memcpy(&c, counters->mapped(), sizeof c);
    const auto* out = static_cast<const std::uint32_t*>(items->mapped());
    REQUIRE(c.item_count >= 1);
    REQUIRE(c.item_count <= kCapacity);
    std::uint32_t wrong = 0, first_wrong = ~0u;
    for (std::uint32_t k = 0; k < c.item_count; ++k)
        if (out[2 * k] != kId || out[2 * k + 1] != k) {
            first_wrong = std::min(first_wrong, k);
            ++wrong;
        }
    INFO(c.item_count << " items, the first wrong at " << first_wrong);
    CHECK(wrong == 0);
    // Now at most kCsMaxTriangleItems items, which the draw passes read as that many
    // tiles each (triangleTilesPerItem): every tile in one item.
    CHECK(c.tiles_per_item == 1);
    CHECK(c.item_count == gpu::kCsMaxTriangleItems);
    CHECK(std::uint64_t(c.item_count) * ((kTiles + gpu::kCsMaxTriangleItems - 1) / gpu::kCsMaxTriangleItems) == kTiles);
}

// The draw passes with more tiles per item than the run's tiles_per_item: a sliver along
// the diagonal of a 1024^2 image has 128^2 = 16,384 tiles in its pixel box, 4 per item
// (kCsMaxTriangleItems), and every covered sample is drawn once, as the raster backend does.
TEST_CASE_METHOD(Fixture, "compute sampling equals raster on a triangle whose box takes several tiles per work item", "[gpu][compute-sampling][limits]") {
    Scene scene;
    HostMesh m;
    m.name = "sliver";
    m.positions = {{-0.9995f, -0.9991f, 0.0f}, {0.9993f, 0.9996f, 0.0f}, {-0.9991f, -0.9997f, 0.0f}};  // inside the region
    m.indices = {0, 1, 2};
    scene.meshes.push_back(std::move(m));
    scene.open.push_back(true);
    BroadPhaseSettings s;
    s.resolution = 1024;
    s.region = std::array<float, 6>{-1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f};
    s.compute.list_budget_bytes = 0;  // draw per step
    Compared c = compareBackends(ctx, bp, scene, s);
    CHECK(c.compute.compute_big == 1);
    CHECK(c.compute.compute_items == gpu::kCsMaxTriangleItems);  // 16,384 tiles, 4 per item
    CHECK(c.compute.depth_complexity == 1);
    CHECK(c.raster.fragments > 500);
}

TEST_CASE("Auto picks compute on GH100 parts, by triangle size elsewhere", "[compute-sampling]") {
    VkPhysicalDeviceProperties p{};
    auto named = [&](std::uint32_t vendor, VkPhysicalDeviceType type, const char* name) {
        p.vendorID = vendor;
        p.deviceType = type;
        std::snprintf(p.deviceName, sizeof(p.deviceName), "%s", name);
    };
    named(0x10DE, VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, "NVIDIA H200");
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 1024, 1000, 50.0).backend == SamplingBackend::Compute);
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Raster, 1024, 1000, 50.0).backend == SamplingBackend::Raster);
    named(0x10005, VK_PHYSICAL_DEVICE_TYPE_CPU, "llvmpipe (LLVM 15.0.6, 256 bits)");
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 1024, 1000, 50.0).backend == SamplingBackend::Raster);
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 1024, 1000, 5.0).backend == SamplingBackend::Compute);
    CHECK(chooseSamplingBackend(p, false, SamplingBackend::Auto, 1024, 1000, 5.0).backend == SamplingBackend::Raster);
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Compute, 1024, 1000, 50.0).backend == SamplingBackend::Compute);
    named(0x10DE, VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, "NVIDIA GeForce RTX 4090");
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 1024, 1000, 50.0).backend == SamplingBackend::Raster);
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 1024, 1000, 0.5).backend == SamplingBackend::Compute);
    // Unknown size: estimated from resolution and triangle count.
    CHECK(chooseSamplingBackend(p, true, SamplingBackend::Auto, 256, 10'000'000, -1.0).backend == SamplingBackend::Compute);
    CHECK_FALSE(chooseSamplingBackend(p, true, SamplingBackend::Auto, 256, 10'000'000, -1.0).reason.empty());
}
