// Graph::planKey: the executor reuses the last plan while the key is unchanged, so equal
// keys must mean equal plans, and every declaration compile() reads must change the key.
#include <catch2/catch.hpp>

#include <functional>
#include <random>
#include <string>

#include "graph/graph.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;

namespace {
const RecordFn kRecordNothing = [](PassContext&) {};

bool sameBarrier(const Barrier& a, const Barrier& b) {
    return a.resource == b.resource && a.is_image == b.is_image && a.src_stage == b.src_stage && a.src_access == b.src_access &&
           a.dst_stage == b.dst_stage && a.dst_access == b.dst_access && a.old_layout == b.old_layout && a.new_layout == b.new_layout &&
           a.base_mip == b.base_mip && a.mip_count == b.mip_count;
}

bool sameBarriers(const std::vector<Barrier>& a, const std::vector<Barrier>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!sameBarrier(a[i], b[i])) return false;
    return true;
}

bool samePlan(const GraphPlan& a, const GraphPlan& b) {
    if (a.order.size() != b.order.size()) return false;
    for (std::size_t i = 0; i < a.order.size(); ++i)
        if (a.order[i].pass != b.order[i].pass || !sameBarriers(a.order[i].barriers, b.order[i].barriers)) return false;
    return a.culled == b.culled && sameBarriers(a.final_barriers, b.final_barriers) && a.image_usage == b.image_usage &&
           a.buffer_usage == b.buffer_usage && a.lifetime == b.lifetime;
}

std::vector<std::uint64_t> keyOf(const Graph& g) {
    std::vector<std::uint64_t> key;
    g.planKey(key);
    return key;
}

// What compile() ignores, varied by `cosmetic`: names, sizes, formats and extents, clear
// values, callbacks.
struct Cosmetic {
    std::string suffix;
    VkDeviceSize size = 256;
    VkFormat format = VK_FORMAT_R32_UINT;
    std::uint32_t extent = 64;
    float clear = 0;
    RecordFn record = kRecordNothing;
};

// Every field compile() reads, each switchable on its own.
struct Spec {
    bool src_is_image = true, out_imported = true, out_readback = true;
    std::uint32_t mips = 3;
    VkImageLayout initial = VK_IMAGE_LAYOUT_UNDEFINED, final_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    PassKind sum_kind = PassKind::Compute;
    bool side_effects = false, has_record = true;
    std::uint32_t area = 0;  // raster pass render area (0: the attachments')
    bool area_height_only = false;
    bool extra_access = false;
    Use sum_use = Use::StorageRead;
    std::uint32_t base_mip = 0, mip_count = VK_REMAINING_MIP_LEVELS;
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
    bool other_resource = false;
};

void build(Graph& g, const Spec& s, const Cosmetic& c = {}) {
    const ResourceId src = s.src_is_image ? g.createImage("src" + c.suffix, {c.format, c.extent, c.extent, s.mips})
                                          : g.createBuffer("src" + c.suffix, c.size);
    const ResourceId color = g.createImage("color" + c.suffix, {c.format, c.extent, c.extent, 1});
    const ResourceId shown = g.importImage("shown" + c.suffix, nullptr, {c.format, c.extent, c.extent, s.mips}, s.initial, s.final_layout);
    const ResourceId out = s.out_imported ? g.importBuffer("out" + c.suffix, c.size, s.out_readback) : g.createBuffer("out" + c.suffix, c.size);
    const ResourceId spare = g.importBuffer("spare" + c.suffix, c.size);
    g.addPass("fill" + c.suffix, PassKind::Compute).write(src).record(c.record);
    auto draw = g.addPass("draw" + c.suffix, PassKind::Raster);
    VkClearValue clear{};
    clear.color.float32[0] = c.clear;
    draw.colorAttachment(color, s.load, clear).record(c.record);
    if (s.area) draw.renderArea(s.area_height_only ? 64 : s.area, s.area_height_only ? s.area : 64);
    auto sum = g.addPass("sum" + c.suffix, s.sum_kind);
    if (s.sum_kind == PassKind::Transfer) sum.use(s.other_resource ? spare : out, Use::TransferDst);
    else sum.use(src, s.sum_use, s.src_is_image ? s.base_mip : 0, s.src_is_image ? s.mip_count : VK_REMAINING_MIP_LEVELS)
             .sampled(color)
             .write(s.other_resource ? spare : out);
    if (s.extra_access && s.sum_kind != PassKind::Transfer) sum.use(shown, Use::StorageReadWrite);
    if (s.has_record) sum.record(c.record);
    auto side = g.addPass("side" + c.suffix, PassKind::Compute).read(src).record(c.record);
    if (s.side_effects) side.sideEffects();
}

}  // namespace

TEST_CASE("plan key: what compile() ignores leaves the key and the plan as they were", "[graph]") {
    Graph a, b;
    build(a, {});
    build(b, {}, {"-renamed-to-a-name-past-the-short-string-buffer", 1 << 20, VK_FORMAT_R16_SFLOAT, 4096, 1.0f,
                  [](PassContext&) { /* another callback */ }});
    CHECK(keyOf(a) == keyOf(b));
    auto pa = a.compile(), pb = b.compile();
    REQUIRE(pa);
    REQUIRE(pb);
    CHECK(samePlan(*pa, *pb));
}

TEST_CASE("plan key: every declaration compile() reads changes it", "[graph]") {
    Graph base;
    build(base, {});
    const auto base_key = keyOf(base);
    const std::vector<std::pair<const char*, std::function<void(Spec&)>>> changes = {
        {"resource kind", [](Spec& s) { s.src_is_image = false; }},
        {"imported", [](Spec& s) { s.out_imported = false; }},
        {"host readback", [](Spec& s) { s.out_readback = false; }},
        {"mip levels", [](Spec& s) { s.mips = 2; }},
        {"initial layout", [](Spec& s) { s.initial = VK_IMAGE_LAYOUT_GENERAL; }},
        {"final layout", [](Spec& s) { s.final_layout = VK_IMAGE_LAYOUT_GENERAL; }},
        {"pass kind", [](Spec& s) { s.sum_kind = PassKind::Transfer; }},
        {"side effects", [](Spec& s) { s.side_effects = true; }},
        {"record callback missing", [](Spec& s) { s.has_record = false; }},
        {"render width", [](Spec& s) { s.area = 32; }},
        {"render height", [](Spec& s) { s.area = 32, s.area_height_only = true; }},
        {"access count", [](Spec& s) { s.extra_access = true; }},
        {"access use", [](Spec& s) { s.sum_use = Use::StorageReadWrite; }},
        {"base mip", [](Spec& s) { s.base_mip = 1, s.mip_count = 2; }},
        {"mip count", [](Spec& s) { s.mip_count = 1; }},
        {"load op", [](Spec& s) { s.load = VK_ATTACHMENT_LOAD_OP_LOAD; }},
        {"accessed resource", [](Spec& s) { s.other_resource = true; }},
    };
    for (const auto& [what, change] : changes) {
        INFO(what);
        Spec s;
        change(s);
        Graph g;
        build(g, s);
        CHECK(keyOf(g) != base_key);
    }
}

TEST_CASE("plan key: random graphs with equal keys compile to equal plans or the same error", "[graph]") {
    // Small graphs from few choices, so that structurally equal ones recur with different
    // names and sizes; every pair with equal keys must compile alike.
    std::mt19937 rng(7);
    auto pick = [&](std::uint32_t n) { return std::uniform_int_distribution<std::uint32_t>(0, n - 1)(rng); };
    struct Built {
        std::vector<std::uint64_t> key;
        Result<GraphPlan> plan = Error(ErrorCode::GraphError, "");
    };
    std::vector<Built> built;
    const Use uses[] = {Use::StorageRead, Use::StorageWrite, Use::StorageReadWrite, Use::Sampled, Use::TransferDst};
    for (int i = 0; i < 400; ++i) {
        Graph g;
        std::vector<ResourceId> res;
        const std::uint32_t n_res = 1 + pick(3);
        for (std::uint32_t r = 0; r < n_res; ++r) {
            const std::string name = "r" + std::to_string(r) + "-" + std::to_string(i);
            switch (pick(3)) {
                case 0: res.push_back(g.createBuffer(name, 16 + pick(1000))); break;
                case 1: res.push_back(g.importBuffer(name, 16 + pick(1000), pick(2) == 1)); break;
                default: res.push_back(g.createImage(name, {VK_FORMAT_R32_UINT, 1 + pick(64), 1 + pick(64), 1 + pick(2)})); break;
            }
        }
        const std::uint32_t n_pass = 1 + pick(3);
        for (std::uint32_t p = 0; p < n_pass; ++p) {
            const Use u = uses[pick(5)];
            auto b = g.addPass("p" + std::to_string(p) + "-" + std::to_string(i), u == Use::TransferDst ? PassKind::Transfer : PassKind::Compute);
            b.use(res[pick(n_res)], u);
            if (pick(2)) b.sideEffects();
            b.record(kRecordNothing);
        }
        Built out;
        g.planKey(out.key);
        out.plan = g.compile();
        built.push_back(std::move(out));
    }
    int equal_pairs = 0;
    for (std::size_t i = 0; i < built.size(); ++i)
        for (std::size_t j = i + 1; j < built.size(); ++j) {
            if (built[i].key != built[j].key) continue;
            ++equal_pairs;
            REQUIRE(bool(built[i].plan) == bool(built[j].plan));
            if (built[i].plan) CHECK(samePlan(*built[i].plan, *built[j].plan));
        }
    CHECK(equal_pairs > 0);  // the choices are few enough that keys repeat
}
