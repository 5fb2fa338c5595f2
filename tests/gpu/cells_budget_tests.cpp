// The cell stage's budget (CellStageSettings::max_candidate_pairs): the
// cells of the footprint boxes, the pairs of footprints sharing a cell (what the sweep
// compares) and the candidate pairs are each checked against it; past one the run fails
// with LimitExceeded naming the count, no buffer grows beyond the budget, and the stage
// runs again afterwards. Also: projection rows that are huge or not finite (what the fit
// writes for a scene narrower or thinner than about 2^-62) still give every pair.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "gpu/cells_test_support.hpp"
#include "support/error_text.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

using test::mentions;

// `copies` copies of one triangle sharing its indices (neighbours, never candidates) in a
// self-colliding object, and a triangle through them (object 1): cells deep in
// comparisons, with few candidates.
CellScene stack(std::uint32_t copies) {
    CellScene s;
    HostMesh m{"stack", {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {}};
    for (std::uint32_t k = 0; k < copies; ++k) m.indices.insert(m.indices.end(), {0u, 1u, 2u});
    s.meshes.push_back(std::move(m));
    s.meshes.push_back(HostMesh{"cross", {{-0.3f, -0.2f, -0.5f}, {0.3f, -0.2f, -0.5f}, {0.0f, 0.1f, 0.5f}}, {0, 1, 2}});
    s.self = {1, 0};
    return s;
}

// `count` triangles in one self-colliding object, each in its own plane through the z axis
// and holding a piece of it: every two intersect, in many cells each.
CellScene crossing(std::uint32_t count) {
    CellScene s;
    HostMesh m{"crossing", {}, {}};
    for (std::uint32_t k = 0; k < count; ++k) {
        const double angle = std::acos(-1.0) * double(k) / double(count);
        const auto x = static_cast<float>(std::cos(angle)), y = static_cast<float>(std::sin(angle));
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), {{x, y, 0.0f}, {-x, -y, 0.0f}, {0.0f, 0.0f, 1.0f + float(k) / float(count)}});
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    }
    s.meshes.push_back(std::move(m));
    s.self = {1};
    return s;
}

struct Staged {
    UploadedScene up;
    passes::CellStageInput in;
    std::unique_ptr<graph::Executor> executor;  // what the stage's runs are submitted on
};

Staged stage(ValidatedContext& ctx, const CellScene& scene, std::uint32_t resolution, std::array<double, 3> direction) {
    Staged s{uploadScene(ctx.device(), scene), {}, std::make_unique<graph::Executor>(ctx.device())};
    s.in.objects = s.up.objects;
    s.in.projection = fitProjection(scene, direction);
    s.in.resolution = resolution;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) s.in.self_collision.push_back(scene.selfOf(i) ? 1 : 0);
    return s;
}

Result<passes::CellStageResult> runWith(passes::CellStage& cells, const Staged& s, std::uint64_t budget,
                                        passes::CellStageCapacity initial = {}) {
    passes::CellStageSettings settings;
    settings.max_candidate_pairs = budget;
    settings.initial = initial;
    return cells.run(*s.executor, s.in, settings);
}

// What a run needs of the budget: the largest of its three counts (comparisons divided
// by kCellsComparisonsPerBudget, rounded up).
std::uint64_t need(const passes::CellStageStats& st) {
    const std::uint64_t per = gpu::kCellsComparisonsPerBudget;
    return std::max({st.box_cells, (st.comparisons + per - 1) / per, st.candidates + st.repeats});
}

}  // namespace

TEST_CASE("cells: past the budget a run fails naming the count, at the budget it gives every pair", "[cells][gpu][limits]") {
    ValidatedContext ctx;
    struct Case {
        const char* name;
        CellScene scene;
        std::uint32_t resolution;
        std::array<double, 3> direction;
    };
    Case cases[] = {
        // Cells of up to kCellsDeepShared count every two entries (huge cells count their
        // sort, and their copies cost nothing: 3,000 copies would not bind).
        {"stack of 1,000 neighbours", stack(1000), 2, {0.2, 0.3, 1.0}},
        {"300 mutually crossing triangles", crossing(300), 4, {1.0, 0.31, 0.17}},
    };
    for (Case& c : cases) {
        INFO(c.name);
        auto cells = passes::CellStage::create(ctx.device());
        REQUIRE(cells);
        const Staged s = stage(ctx, c.scene, c.resolution, c.direction);
        // Unbounded (the stage's own limit): the counts the budget is checked against.
        auto full = (*cells)->run(*s.executor, s.in);
        REQUIRE(full);
        const passes::CellStageStats st = full->stats;
        requireAllFound(CellRun{*full, toObjectPairs(s.up.objects, full->pairs)}, referencePairs(c.scene));
        CHECK(st.entries <= st.box_cells);
        const std::uint64_t enough = need(st);

        // Each count past its budget, the others within it where the scene allows.
        const std::uint64_t per = gpu::kCellsComparisonsPerBudget;
        struct Limit {
            std::uint64_t budget;
            std::uint64_t count;
            const char* says;
        };
        std::vector<Limit> limits = {{st.box_cells - 1, st.box_cells, "footprint boxes span"}};
        if (st.comparisons > per * st.box_cells) limits.push_back({st.box_cells, st.comparisons, "pairs of footprints share a cell"});
        // The overlapping pairs the sweep found: written, or dropped as repeats in deep cells.
        const std::uint64_t overlapping = st.candidates + st.repeats;
        if (overlapping > std::max(st.box_cells, (st.comparisons + per - 1) / per))
            limits.push_back({enough - 1, overlapping, "candidate pairs"});
        for (const Limit& l : limits) {
            INFO("budget " << l.budget << ": " << l.says);
            auto fresh = passes::CellStage::create(ctx.device());
            REQUIRE(fresh);
            auto r = runWith(**fresh, s, l.budget);
            REQUIRE_FALSE(r);
            CHECK(r.error().code() == ErrorCode::LimitExceeded);
            CHECK(mentions(r.error(), l.says));
            CHECK(mentions(r.error(), " " + std::to_string(l.count) + " "));
            CHECK(mentions(r.error(), "max_candidate_pairs (" + std::to_string(l.budget) + ")"));
            // Nothing grew for it.
            const passes::CellStageCapacity& cap = (*fresh)->capacity();
            CHECK(std::max({cap.entries, cap.items, cap.candidates, cap.survivors}) <= l.budget);
            // The stage goes on: the next run with enough budget gives every pair.
            auto again = runWith(**fresh, s, enough);
            REQUIRE(again);
            CHECK(again->pairs == full->pairs);
        }
        // The scenes are chosen so that each count binds once.
        CHECK(limits.size() >= 2);

        // Exactly the budget the run needs: complete, from capacities of 1 grown to at
        // most the budget.
        auto fresh = passes::CellStage::create(ctx.device());
        REQUIRE(fresh);
        auto exact = runWith(**fresh, s, enough, {1, 1, 1, 1});
        REQUIRE(exact);
        CHECK(exact->pairs == full->pairs);
        CHECK(exact->stats.runs >= 2);
        const passes::CellStageCapacity& cap = (*fresh)->capacity();
        CHECK(std::max({cap.entries, cap.items, cap.candidates, cap.survivors}) <= enough);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: first capacities never exceed a small budget, a budget of 0 fails at once", "[cells][gpu][limits]") {
    ValidatedContext ctx;
    const CellScene scene = crossing(40);
    const Staged s = stage(ctx, scene, 4, {1.0, 0.31, 0.17});
    auto cells = passes::CellStage::create(ctx.device());
    REQUIRE(cells);
    auto full = (*cells)->run(*s.executor, s.in);
    REQUIRE(full);
    const std::uint64_t enough = need(full->stats);
    // The estimates (8 entries and 2 candidates per triangle, at least 4,096) are above it.
    REQUIRE(enough < 4096);
    auto fresh = passes::CellStage::create(ctx.device());
    REQUIRE(fresh);
    auto r = runWith(**fresh, s, enough);
    REQUIRE(r);
    CHECK(r->pairs == full->pairs);
    const passes::CellStageCapacity& cap = (*fresh)->capacity();
    CHECK(std::max({cap.entries, cap.items, cap.candidates, cap.survivors}) <= enough);

    auto none = passes::CellStage::create(ctx.device());
    REQUIRE(none);
    auto zero = runWith(**none, s, 0);
    REQUIRE_FALSE(zero);
    CHECK(zero.error().code() == ErrorCode::LimitExceeded);
    CHECK(mentions(zero.error(), "max_candidate_pairs (0)"));
    // A budget beyond the stage's own limit (2^31 - 1 elements) is that limit.
    auto unbounded = runWith(**none, s, std::numeric_limits<std::uint64_t>::max());
    REQUIRE(unbounded);
    CHECK(unbounded->pairs == full->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: projection rows of 2^62 or more, or not finite when written on the GPU, still give every pair",
          "[cells][gpu][limits]") {
    ValidatedContext ctx;
    CellScene scene;
    for (float x : {0.0f, 0.6f}) {
        auto ball = uvSphere(0.5f, 16, 8);
        REQUIRE(ball);
        scene.meshes.push_back(std::move(*ball));
        scene.transforms.push_back(translation(x, 0.1f * x, 0.0f));
    }
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 20);
    const gpu::Projection fitted = fitProjection(scene, {0.2, 0.3, 1.0});
    const float huge = std::ldexp(1.0f, 70), nan = std::numeric_limits<float>::quiet_NaN();
    auto scaled = [&](std::initializer_list<int> rows, float by) {
        gpu::Projection p = fitted;
        for (int r : rows) p.row[r] = {p.row[r].x * by, p.row[r].y * by, p.row[r].z * by, p.row[r].w * by};
        return p;
    };
    auto cells = passes::CellStage::create(ctx.device());
    REQUIRE(cells);
    // Given by the host: rows times 2^70 (finite), scaled back below 2^62 on the GPU.
    for (auto rows : {std::initializer_list<int>{2}, std::initializer_list<int>{0, 1}}) {
        CellRunOptions opt;
        opt.resolution = 32;
        opt.projection = scaled(rows, huge);
        INFO("row " << *rows.begin() << " times 2^70");
        requireAllFound(runCells(ctx, **cells, scene, opt), reference);
    }
    // Written by an earlier pass (as the detection's fit writes it): a depth row of NaN
    // (a fit that divided by a subnormal depth extent), an x row of infinity.
    const UploadedScene up = uploadScene(ctx.device(), scene);
    for (auto rows : {std::initializer_list<int>{2}, std::initializer_list<int>{0}}) {
        INFO("row " << *rows.begin() << " not finite");
        const gpu::Projection pr = *rows.begin() == 2 ? scaled(rows, nan) : scaled(rows, std::numeric_limits<float>::infinity());
        passes::CellStageInput in;
        in.objects = up.objects;
        in.resolution = 32;
        const passes::CellStageResult out = runWithWrittenProjection(ctx, **cells, in, pr);
        requireAllFound(CellRun{out, toObjectPairs(up.objects, out.pairs)}, reference);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
