// Shaders whose loops can run past DeviceInfo::loop_iteration_limit (llvmpipe ends a shader
// invocation's loops once their iterations together pass 65,535, without an error), run
// alone on inputs built to pass it: the result is complete, or the pass says it was cut
// short so that the run fails by name. docs/stability.md, "Loop limits", has the audit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "common/broadphase.h"
#include "graph/executor.hpp"
#include "shaders/all.hpp"
#include "support/gpu_fixture.hpp"
#include "support/record_dispatch.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

struct Sliver {
    float ax, ay, cx, cy;  // its longest edge, in pixels
};

}  // namespace

// Depth-aware separation's triangle-bounds pass (tri_bounds.comp) gives every ray within
// reach of an edge-on triangle its depth range (edge_depth), in one invocation per triangle:
// rows of the band around the triangle's longest edge, and each row's columns. One such
// sliver across a 4096^2 image is some 48,000 iterations; a subgroup runs each loop as long
// as its longest lane, so these four slivers of one subgroup (one per band shape: 5 rows of
// 4,096 pixels, 35 of about 660, 305 of about 70, 4,100 of about 11) need some 108,000
// together. On llvmpipe the rays past the first 65,535 got nothing (before: silently); now
// the pass flags kLoopLimitSplat, which the peeling method reports as LimitExceeded.
TEST_CASE("depth-aware bounds: edge-on slivers across a 4096^2 image reach every ray, or flag the loop limit", "[gpu][limits][peeling]") {
    ValidatedContext ctx;
    vk::Device& device = ctx.device();
    auto pipeline = vk::Pipeline::createCompute(device, shaders::tri_bounds_comp, {}, sizeof(gpu::Push), "tri-bounds-test");
    REQUIRE(pipeline);
    constexpr std::uint32_t n = 4096;
    const std::vector<Sliver> slivers = {
        {0.5f, 2.5f, 4095.5f, 3.5f}, {0.5f, 10.5f, 4095.5f, 40.5f}, {0.5f, 100.5f, 4095.5f, 400.5f}, {0.5f, 0.5f, 4095.5f, 4095.5f}};
    // Each sliver: the edge a-c at depth 0.1 and a third corner 1.2 pixels off its middle at
    // depth 0.9 (thin, and far steeper than kEdgeOnSlope: edge-on). World = sampling space.
    std::vector<float> positions;
    for (const Sliver& s : slivers) {
        const float dx = s.cx - s.ax, dy = s.cy - s.ay, len = std::sqrt(dx * dx + dy * dy);
        const float bx = 0.5f * (s.ax + s.cx) - 1.2f * dy / len, by = 0.5f * (s.ay + s.cy) + 1.2f * dx / len;
        for (float v : {s.ax / n, s.ay / n, 0.1f, s.cx / n, s.cy / n, 0.1f, bx / n, by / n, 0.9f}) positions.push_back(v);
    }
    const auto tris = static_cast<std::uint32_t>(slivers.size());
    std::vector<std::uint32_t> indices(3 * tris);
    for (std::uint32_t i = 0; i < 3 * tris; ++i) indices[i] = i;
    using vk::MemoryKind;
    const VkDeviceSize edge_bytes = VkDeviceSize(n) * n * 8;
    auto frame = vk::Buffer::create(device, sizeof(gpu::Frame), 0, MemoryKind::Upload, "tb-frame");
    auto objects = vk::Buffer::create(device, sizeof(gpu::ObjectGpu), 0, MemoryKind::Upload, "tb-objects");
    auto projection = vk::Buffer::create(device, sizeof(gpu::Projection), 0, MemoryKind::Upload, "tb-projection");
    auto mesh = vk::Buffer::create(device, positions.size() * 4 + indices.size() * 4, 0, MemoryKind::Upload, "tb-mesh");
    auto bounds = vk::Buffer::create(device, tris * sizeof(gpu::TriangleBounds), 0, MemoryKind::DeviceLocal, "tb-bounds");
    auto header = vk::Buffer::create(device, sizeof(gpu::Header), 0, MemoryKind::Readback, "tb-header");
    auto edge = vk::Buffer::create(device, edge_bytes, 0, MemoryKind::Readback, "tb-edge-depth");
    REQUIRE((frame && objects && projection && mesh && bounds && header && edge));
    std::memcpy(mesh->mapped(), positions.data(), positions.size() * 4);
    std::memcpy(static_cast<char*>(mesh->mapped()) + positions.size() * 4, indices.data(), indices.size() * 4);
    mesh->flush();
    gpu::ObjectGpu o{};
    o.vertices = mesh->address();
    o.indices = mesh->address() + positions.size() * 4;
    o.vertex_stride = 12;
    o.vertex_count = 3 * tris;
    o.triangle_count = tris;
    o.model[0] = {1, 0, 0, 0};
    o.model[1] = {0, 1, 0, 0};
    o.model[2] = {0, 0, 1, 0};
    std::memcpy(objects->mapped(), &o, sizeof o);
    objects->flush();
    gpu::Projection pr{};
    pr.row[0] = {1, 0, 0, 0};
    pr.row[1] = {0, 1, 0, 0};
    pr.row[2] = {0, 0, 1, 0};
    std::memcpy(projection->mapped(), &pr, sizeof pr);
    projection->flush();
    std::memset(header->mapped(), 0, sizeof(gpu::Header));
    header->flush();
    std::memset(edge->mapped(), 0, edge_bytes);
    edge->flush();
    gpu::Frame f{};
    f.objects = objects->address();
    f.projection = projection->address();
    f.header = header->address();
    f.tri_bounds = bounds->address();
    f.edge_depth = edge->address();
    f.resolution = n;
    f.object_count = 1;
    f.triangle_count = tris;
    f.depth_aware = 1;
    std::memcpy(frame->mapped(), &f, sizeof f);
    frame->flush();
    graph::Graph g;
    const auto edge_id = g.importBuffer("tb-edge-depth", *edge, true);
    const auto header_id = g.importBuffer("tb-header", *header, true);
    const auto bounds_id = g.importBuffer("tb-bounds", *bounds);
    const VkPipeline handle = pipeline->handle();
    const VkPipelineLayout layout = pipeline->layout();
    const VkDeviceAddress frame_address = frame->address();
    g.addPass("tri-bounds", graph::PassKind::Compute).readWrite(edge_id).readWrite(header_id).write(bounds_id).record([=](graph::PassContext& pc) {
        gpu::Push push{frame_address, 0, 0, 0, 0};
        recordDispatch(pc, handle, layout, push);
    });
    graph::Executor executor(device);
    REQUIRE(executor.run(g));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    header->invalidate();
    edge->invalidate();
    gpu::Header h;
    std::memcpy(&h, header->mapped(), sizeof h);
    // The rays along each sliver's longest edge: every one within reach, so each has a depth.
    const auto* ed = static_cast<const std::uint32_t*>(edge->mapped());
    std::size_t missing = 0, checked = 0;
    for (const Sliver& s : slivers)
        for (int k = 1; k < 1000; ++k) {
            const float t = float(k) / 1000.0f;
            const auto x = static_cast<std::uint32_t>(s.ax + t * (s.cx - s.ax)), y = static_cast<std::uint32_t>(s.ay + t * (s.cy - s.ay));
            const std::size_t p = std::size_t(y) * n + x;
            ++checked;
            if (ed[2 * p] == 0 || ed[2 * p + 1] == 0) ++missing;
        }
    INFO(missing << " of " << checked << " rays on the slivers without their depth; loop limit flag " << h.loop_limit);
    CHECK(h.depth_complexity == 0);  // nothing else written
    if (h.loop_limit == 0) {
        CHECK(missing == 0);
        CHECK(ctx.device().info.loop_iteration_limit == 0);  // this input passes llvmpipe's limit
    } else {
        CHECK(h.loop_limit == gpu::kLoopLimitSplat);
        CHECK(ctx.device().info.loop_iteration_limit != 0);
    }
}

// Compute sampling's draw passes (here the count pass, csample_count.comp): a workgroup per
// work item, and each invocation loops over the item's tiles. A run's tiles_per_item
// passes 65,535 only past 4.3e9 tiles (a buffer of at least kCsExtraItems items), beyond
// any lavapipe run; set here directly: 100,000 tiles of a triangle over a 4096^2 image in
// one item. On llvmpipe the loop ended after 65,535 tiles (before: silently); now the pass
// flags kLoopLimitDraw, which the peeling method reports as LimitExceeded.
TEST_CASE("compute sampling: a work item of 100,000 tiles draws them all, or flags the loop limit", "[gpu][limits][compute-sampling]") {
    ValidatedContext ctx;
    vk::Device& device = ctx.device();
    auto pipeline = vk::Pipeline::createCompute(device, shaders::csample_count_comp, {}, sizeof(gpu::Push), "csample-count-test");
    REQUIRE(pipeline);
    constexpr std::uint32_t n = 4096, kPerItem = 100000;
    const std::uint32_t bits = device.properties.limits.subPixelPrecisionBits;
    const int far = int((3 * n) << bits);
    using vk::MemoryKind;
    const VkDeviceSize ray_bytes = VkDeviceSize(n) * n * 8;
    auto frame = vk::Buffer::create(device, sizeof(gpu::Frame), 0, MemoryKind::Upload, "cc-frame");
    auto cs = vk::Buffer::create(device, sizeof(gpu::CsFrame), 0, MemoryKind::Upload, "cc-cs-frame");
    auto tri = vk::Buffer::create(device, sizeof(gpu::CsTriangle), 0, MemoryKind::Upload, "cc-triangle");
    auto items = vk::Buffer::create(device, 8, 0, MemoryKind::Upload, "cc-items");
    auto counters = vk::Buffer::create(device, sizeof(gpu::CsCounters), 0, MemoryKind::Upload, "cc-counters");
    auto header = vk::Buffer::create(device, sizeof(gpu::Header), 0, MemoryKind::Readback, "cc-header");
    auto rays = vk::Buffer::create(device, ray_bytes, 0, MemoryKind::Readback, "cc-ray-fragments");
    REQUIRE((frame && cs && tri && items && counters && header && rays));
    gpu::CsTriangle t{};
    t.x[0] = -1000, t.y[0] = -1000, t.x[1] = far, t.y[1] = -1000, t.x[2] = -1000, t.y[2] = far;  // covers the image
    t.box_lo = 0;
    t.box_hi = (n - 1) | ((n - 1) << 16);
    t.z = 0.5f;
    std::memcpy(tri->mapped(), &t, sizeof t);
    tri->flush();
    const std::uint32_t item[2] = {0, 0};
    std::memcpy(items->mapped(), item, sizeof item);
    items->flush();
    gpu::CsCounters c{};
    c.item_count = 1;
    c.tiles_per_item = kPerItem;
    c.total_groups = 1;
    std::memcpy(counters->mapped(), &c, sizeof c);
    counters->flush();
    std::memset(header->mapped(), 0, sizeof(gpu::Header));
    header->flush();
    std::memset(rays->mapped(), 0, ray_bytes);
    rays->flush();
    gpu::CsFrame cf{};
    cf.triangles = tri->address();
    cf.items = items->address();
    cf.counters = counters->address();
    cf.item_capacity = 1;
    cf.subpixel_bits = bits;
    std::memcpy(cs->mapped(), &cf, sizeof cf);
    cs->flush();
    gpu::Frame f{};
    f.header = header->address();
    f.compute_sampling = cs->address();
    f.ray_fragments = rays->address();
    f.resolution = n;
    std::memcpy(frame->mapped(), &f, sizeof f);
    frame->flush();
    graph::Graph g;
    const auto rays_id = g.importBuffer("cc-ray-fragments", *rays, true);
    const auto header_id = g.importBuffer("cc-header", *header, true);
    const VkPipeline handle = pipeline->handle();
    const VkPipelineLayout layout = pipeline->layout();
    const VkDeviceAddress frame_address = frame->address();
    g.addPass("count", graph::PassKind::Compute).readWrite(rays_id).readWrite(header_id).record([=](graph::PassContext& pc) {
        gpu::Push push{frame_address, 0, 0, 0, 0};
        recordDispatch(pc, handle, layout, push);
    });
    graph::Executor executor(device);
    REQUIRE(executor.run(g));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    header->invalidate();
    rays->invalidate();
    gpu::Header h;
    std::memcpy(&h, header->mapped(), sizeof h);
    const auto* counts = static_cast<const std::uint64_t*>(rays->mapped());
    std::uint64_t drawn = 0;
    for (std::size_t p = 0; p < std::size_t(n) * n; ++p) drawn += counts[p];
    const std::uint64_t expected = std::uint64_t(kPerItem) * gpu::kCsTile * gpu::kCsTile;  // every tile inside the box, covered
    INFO(drawn << " samples drawn of " << expected << "; loop limit flag " << h.loop_limit);
    if (h.loop_limit == 0) {
        CHECK(drawn == expected);
        CHECK(ctx.device().info.loop_iteration_limit == 0);  // this input passes llvmpipe's limit
    } else {
        CHECK(h.loop_limit == gpu::kLoopLimitDraw);
        CHECK(ctx.device().info.loop_iteration_limit != 0);
    }
}
