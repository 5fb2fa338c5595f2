// Barrier derivation, ordering, culling and validation of the render graph, on the host.
#include <catch2/catch.hpp>

#include "graph/graph.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;

namespace {
const RecordFn kNoop = [](PassContext&) {};

const PlannedPass& planned(const GraphPlan& plan, const Graph& g, const std::string& name) {
    for (const auto& p : plan.order)
        if (g.passes()[p.pass].name == name) return p;
    FAIL("pass " << name << " not in plan");
    throw;  // unreachable
}

GraphPlan compileOk(const Graph& g) {
    auto plan = g.compile();
    INFO((plan ? std::string() : plan.error().message()));
    REQUIRE(plan);
    return *plan;
}

std::string compileError(const Graph& g) {
    auto plan = g.compile();
    REQUIRE_FALSE(plan);
    CHECK(plan.error().code() == ErrorCode::GraphError);
    return plan.error().message();
}
}  // namespace

TEST_CASE("read after write on a buffer gets one compute-to-compute barrier", "[graph]") {
    Graph g;
    auto tmp = g.createBuffer("tmp", 256);
    auto out = g.importBuffer("out", 256);
    g.addPass("produce", PassKind::Compute).write(tmp).record(kNoop);
    g.addPass("consume", PassKind::Compute).read(tmp).write(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    REQUIRE(plan.order.size() == 2);
    CHECK(planned(plan, g, "produce").barriers.empty());
    const auto& b = planned(plan, g, "consume").barriers;
    REQUIRE(b.size() == 2);  // tmp: RAW; out: wait for whatever wrote it before the graph
    CHECK(b[0].resource == tmp);
    CHECK(b[0].src_stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(b[0].src_access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    CHECK(b[0].dst_stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(b[0].dst_access == VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    CHECK(b[1].resource == out);
    CHECK(b[1].src_stage == VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
}

TEST_CASE("a second reader of the same stage needs no barrier", "[graph]") {
    Graph g;
    auto tmp = g.createBuffer("tmp", 64);
    auto out1 = g.importBuffer("o1", 64);
    auto out2 = g.importBuffer("o2", 64);
    g.addPass("w", PassKind::Compute).write(tmp).record(kNoop);
    g.addPass("r1", PassKind::Compute).read(tmp).write(out1).record(kNoop);
    g.addPass("r2", PassKind::Compute).read(tmp).write(out2).record(kNoop);
    GraphPlan plan = compileOk(g);
    for (const auto& b : planned(plan, g, "r2").barriers) CHECK(b.resource != tmp);
}

TEST_CASE("a fragment reader after a compute reader gets its own visibility barrier", "[graph]") {
    Graph g;
    auto tmp = g.createBuffer("tmp", 64);
    auto out = g.importBuffer("out", 64);
    auto img = g.createImage("img", {VK_FORMAT_R32_UINT, 8, 8, 1});
    g.addPass("w", PassKind::Compute).write(tmp).record(kNoop);
    g.addPass("rc", PassKind::Compute).read(tmp).write(out).record(kNoop);
    g.addPass("rf", PassKind::Raster).read(tmp).colorAttachment(img).record(kNoop);
    g.addPass("use", PassKind::Compute).use(img, Use::StorageRead).readWrite(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    bool found = false;
    for (const auto& b : planned(plan, g, "rf").barriers)
        if (b.resource == tmp) {
            found = true;
            CHECK(b.src_access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
            CHECK((b.dst_stage & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT) != 0);
        }
    CHECK(found);
}

TEST_CASE("write after read is an execution dependency without a flush", "[graph]") {
    Graph g;
    auto tmp = g.createBuffer("tmp", 64);
    auto out = g.importBuffer("out", 64);
    g.addPass("w1", PassKind::Compute).write(tmp).record(kNoop);
    g.addPass("r", PassKind::Compute).read(tmp).write(out).record(kNoop);
    g.addPass("w2", PassKind::Compute).write(tmp).record(kNoop);
    g.addPass("r2", PassKind::Compute).read(tmp).readWrite(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    const auto& b = planned(plan, g, "w2").barriers;
    REQUIRE(b.size() == 1);
    CHECK(b[0].src_stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    // The reader's stage is in the first scope; the earlier write was already made visible.
    CHECK(b[0].dst_access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST_CASE("an attachment sampled by a later compute pass transitions its layout", "[graph]") {
    Graph g;
    auto color = g.createImage("color", {VK_FORMAT_R32_UINT, 64, 64, 1});
    auto out = g.importBuffer("sum", 4);
    g.addPass("draw", PassKind::Raster).colorAttachment(color).record(kNoop);
    g.addPass("sum", PassKind::Compute).sampled(color).readWrite(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    const auto& first = planned(plan, g, "draw").barriers;
    REQUIRE(first.size() == 1);
    CHECK(first[0].old_layout == VK_IMAGE_LAYOUT_UNDEFINED);
    CHECK(first[0].new_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    const auto& second = planned(plan, g, "sum").barriers;
    const Barrier* img = nullptr;
    for (const auto& b : second)
        if (b.resource == color) img = &b;
    REQUIRE(img);
    CHECK(img->old_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    CHECK(img->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    CHECK(img->src_stage == VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    CHECK((img->src_access & VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT) != 0);
    CHECK(img->dst_stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(img->dst_access == VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    CHECK((plan.image_usage[color.index] & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) != 0);
    CHECK((plan.image_usage[color.index] & VK_IMAGE_USAGE_SAMPLED_BIT) != 0);
}

TEST_CASE("depth attachment usage and layout", "[graph]") {
    Graph g;
    auto depth = g.createImage("depth", {VK_FORMAT_D32_SFLOAT, 16, 16, 1});
    auto out = g.importBuffer("out", 4);
    g.addPass("z", PassKind::Raster).depthAttachment(depth).readWrite(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    const auto& b = planned(plan, g, "z").barriers;
    REQUIRE_FALSE(b.empty());
    CHECK(b[0].new_layout == VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    CHECK((plan.image_usage[depth.index] & VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) != 0);
}

TEST_CASE("mip levels are tracked separately and merged into ranges", "[graph]") {
    Graph g;
    auto pyramid = g.createImage("pyr", {VK_FORMAT_R32G32B32A32_SFLOAT, 16, 16, 5});
    auto out = g.importBuffer("out", 4);
    g.addPass("level0", PassKind::Compute).use(pyramid, Use::StorageWrite, 0, 1).record(kNoop);
    g.addPass("level1", PassKind::Compute).use(pyramid, Use::StorageRead, 0, 1).use(pyramid, Use::StorageWrite, 1, 1).record(kNoop);
    g.addPass("rest", PassKind::Compute).use(pyramid, Use::StorageReadWrite, 1, 4).record(kNoop);
    g.addPass("fetch", PassKind::Compute).use(pyramid, Use::StorageRead).readWrite(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    const auto& l1 = planned(plan, g, "level1").barriers;
    REQUIRE(l1.size() == 2);
    CHECK(l1[0].base_mip == 0);  // RAW on level 0
    CHECK(l1[0].src_access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    CHECK(l1[1].base_mip == 1);  // first use of level 1: layout UNDEFINED -> GENERAL
    CHECK(l1[1].old_layout == VK_IMAGE_LAYOUT_UNDEFINED);
    const auto& rest = planned(plan, g, "rest").barriers;
    // level 1 RAW plus levels 2..4 first use merged into one range
    REQUIRE(rest.size() == 2);
    CHECK(rest[1].base_mip == 2);
    CHECK(rest[1].mip_count == 3);
}

TEST_CASE("repeated passes ping-pong and each reads what the previous wrote", "[graph]") {
    Graph g;
    ResourceId keys[2] = {g.createBuffer("keys0", 64), g.createBuffer("keys1", 64)};
    auto out = g.importBuffer("out", 64);
    g.addPass("init", PassKind::Compute).write(keys[1]).record(kNoop);
    g.repeatPass("peel", PassKind::Compute, 4, [&](PassBuilder& p, std::uint32_t i) {
        p.read(keys[(i + 1) % 2]).write(keys[i % 2]).record(kNoop);
    });
    g.addPass("final", PassKind::Compute).read(keys[1]).write(out).record(kNoop);
    GraphPlan plan = compileOk(g);
    REQUIRE(plan.order.size() == 6);
    for (std::uint32_t i = 0; i < 4; ++i) {
        const auto& b = planned(plan, g, "peel[" + std::to_string(i) + "]").barriers;
        bool raw = false;
        for (const auto& x : b)
            if (x.resource == keys[(i + 1) % 2] && x.src_access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) raw = true;
        CHECK(raw);
    }
    CHECK(g.passes()[plan.order[1].pass].name == "peel[0]");
}

TEST_CASE("passes whose results nobody uses are culled", "[graph]") {
    Graph g;
    auto used = g.createBuffer("used", 64);
    auto unused = g.createBuffer("unused", 64);
    auto out = g.importBuffer("out", 64);
    g.addPass("dead", PassKind::Compute).write(unused).record(kNoop);
    g.addPass("live", PassKind::Compute).write(used).record(kNoop);
    g.addPass("sink", PassKind::Compute).read(used).write(out).record(kNoop);
    g.addPass("effect", PassKind::Compute).sideEffects().record(kNoop);
    GraphPlan plan = compileOk(g);
    REQUIRE(plan.culled.size() == 1);
    CHECK(g.passes()[plan.culled[0]].name == "dead");
    CHECK(plan.order.size() == 3);
    CHECK(plan.lifetime[unused.index].first == ~0u);
    CHECK(plan.lifetime[used.index] == std::make_pair(0u, 1u));
}

TEST_CASE("host readback buffers get a final barrier to the host", "[graph]") {
    Graph g;
    auto rb = g.importBuffer("readback", 64, true);
    g.addPass("pack", PassKind::Compute).write(rb).record(kNoop);
    GraphPlan plan = compileOk(g);
    REQUIRE(plan.final_barriers.size() == 1);
    CHECK(plan.final_barriers[0].dst_stage == VK_PIPELINE_STAGE_2_HOST_BIT);
    CHECK(plan.final_barriers[0].dst_access == VK_ACCESS_2_HOST_READ_BIT);
    CHECK(plan.final_barriers[0].src_stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

TEST_CASE("imported images end in their requested layout", "[graph]") {
    Graph g;
    auto img = g.importImage("target", nullptr, {VK_FORMAT_R8G8B8A8_UNORM, 8, 8, 1}, VK_IMAGE_LAYOUT_UNDEFINED,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    g.addPass("draw", PassKind::Raster).colorAttachment(img).record(kNoop);
    GraphPlan plan = compileOk(g);
    REQUIRE(plan.final_barriers.size() == 1);
    CHECK(plan.final_barriers[0].old_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    CHECK(plan.final_barriers[0].new_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

TEST_CASE("transfer passes use transfer stages", "[graph]") {
    Graph g;
    auto src = g.createBuffer("src", 64);
    auto dst = g.importBuffer("dst", 64, true);
    g.addPass("fill", PassKind::Transfer).use(src, Use::TransferDst).record(kNoop);
    g.addPass("copy", PassKind::Transfer).use(src, Use::TransferSrc).use(dst, Use::TransferDst).record(kNoop);
    GraphPlan plan = compileOk(g);
    const auto& b = planned(plan, g, "copy").barriers;
    REQUIRE_FALSE(b.empty());
    CHECK(b[0].src_stage == VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    CHECK(b[0].dst_access == VK_ACCESS_2_TRANSFER_READ_BIT);
    CHECK((plan.buffer_usage[src.index] & VK_BUFFER_USAGE_TRANSFER_SRC_BIT) != 0);
}

TEST_CASE("malformed graphs are rejected with a plain message", "[graph]") {
    SECTION("reading before anything writes") {
        Graph g;
        auto tmp = g.createBuffer("tmp", 64);
        auto out = g.importBuffer("out", 64);
        g.addPass("r", PassKind::Compute).read(tmp).write(out).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("pass 'r' reads 'tmp' before any pass writes it"));
    }
    SECTION("attachment in a compute pass") {
        Graph g;
        auto img = g.createImage("img", {VK_FORMAT_R32_UINT, 8, 8, 1});
        g.addPass("c", PassKind::Compute).colorAttachment(img).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("cannot use 'img' as an attachment"));
    }
    SECTION("buffer used as an image") {
        Graph g;
        auto buf = g.createBuffer("buf", 8);
        g.addPass("c", PassKind::Compute).sampled(buf).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("uses buffer 'buf' as sampled"));
    }
    SECTION("mip range outside the image") {
        Graph g;
        auto img = g.createImage("img", {VK_FORMAT_R32_UINT, 8, 8, 2});
        g.addPass("c", PassKind::Compute).use(img, Use::StorageWrite, 2, 1).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("outside its 2 levels"));
    }
    SECTION("the same resource twice in one pass") {
        Graph g;
        auto buf = g.createBuffer("buf", 8);
        g.addPass("c", PassKind::Compute).write(buf).read(buf).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("declares 'buf' twice"));
    }
    SECTION("raster pass without attachments or render area") {
        Graph g;
        auto buf = g.importBuffer("buf", 8);
        g.addPass("r", PassKind::Raster).readWrite(buf).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("needs renderArea()"));
    }
    SECTION("no record callback") {
        Graph g;
        auto buf = g.importBuffer("buf", 8);
        g.addPass("c", PassKind::Compute).write(buf);
        CHECK_THAT(compileError(g), Catch::Contains("no record callback"));
    }
    SECTION("indirect arguments from an image") {
        Graph g;
        auto img = g.createImage("img", {VK_FORMAT_R32_UINT, 8, 8, 1});
        g.addPass("c", PassKind::Compute).indirect(img).record(kNoop);
        CHECK_THAT(compileError(g), Catch::Contains("indirect"));
    }
}

TEST_CASE("a pass keeps the stage tag it declares, untagged passes have 0", "[graph]") {
    Graph g;
    const ResourceId buf = g.importBuffer("buf", 64);
    g.addPass("tagged", PassKind::Compute).stage(3).write(buf).record(kNoop);
    g.addPass("plain", PassKind::Compute).readWrite(buf).record(kNoop);
    CHECK(g.passes()[0].stage == 3);
    CHECK(g.passes()[1].stage == 0);
    compileOk(g);
}
