// The cell stage's machinery: overflow and rerun, identical results run to run, the
// big-triangle and deep-cell paths, the projection written by an earlier pass, the filter
// switched off, and bad input (errors naming object and triangle, or a conservative
// result for denormal coordinates).
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>

#include "gpu/cells_test_support.hpp"
#include "support/device_copy.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

CellScene mixedScene() {
    CellScene s;
    s.meshes.push_back(generated(uvSphere(1.0f, 32, 16), "sphere"));
    s.meshes.push_back(generated(torus(0.9f, 0.3f, 40, 12), "torus"));
    s.meshes.push_back(generated(box({0.6f, 0.6f, 0.6f}, 1), "box"));  // 12 big triangles
    s.transforms = {kIdentityTransform, translation(0.3f, 0.2f, 0.1f), translation(-0.4f, 0.1f, 0.3f)};
    s.self = {0, 1, 0};
    return s;
}

}  // namespace

TEST_CASE("cells: tiny capacities overflow, grow and rerun to the same pairs", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    const CellScene scene = mixedScene();
    CellRunOptions opt;
    opt.resolution = 256;
    const CellRun normal = runCells(ctx, **stage, scene, opt);
    requireAllFound(normal, referencePairs(scene));
    CHECK(normal.result.stats.big_triangles > 0);

    auto fresh = passes::CellStage::create(ctx.device());
    REQUIRE(fresh);
    opt.settings.initial = {1, 1, 1, 1};
    const CellRun grown = runCells(ctx, **fresh, scene, opt);
    CHECK(grown.result.stats.runs >= 3);  // items, then entries, then candidates, then survivors
    CHECK(grown.pairs == normal.pairs);
    CHECK(grown.result.stats.entries == normal.result.stats.entries);
    CHECK(grown.result.stats.candidates == normal.result.stats.candidates);
    CHECK((*fresh)->capacity().entries >= normal.result.stats.entries);
    CHECK((*fresh)->capacity().survivors >= normal.result.stats.survivors);

    // Only the candidates and survivors too small: the sweep counts every candidate
    // through the overflow, and the survivors are sized for them with it, so one rerun.
    auto counted = passes::CellStage::create(ctx.device());
    REQUIRE(counted);
    opt.settings.initial = {static_cast<std::uint32_t>(normal.result.stats.entries), 4096, 1, 1};
    const CellRun sized = runCells(ctx, **counted, scene, opt);
    CHECK(sized.result.stats.runs == 2);
    CHECK(sized.pairs == normal.pairs);

    // The grown buffers stay: the next run needs one submission.
    opt.settings.initial = {};
    const CellRun again = runCells(ctx, **fresh, scene, opt);
    CHECK(again.result.stats.runs == 1);
    CHECK(again.pairs == normal.pairs);

    // A run limit that overflow cannot meet is an error, not a partial result.
    auto limited = passes::CellStage::create(ctx.device());
    REQUIRE(limited);
    UploadedScene up = uploadScene(ctx.device(), scene);
    passes::CellStageInput in;
    in.objects = up.objects;
    in.projection = fitProjection(scene, {0, 0, 1});
    in.resolution = 256;
    passes::CellStageSettings s;
    s.initial = {1, 1, 1, 1};
    s.max_runs = 1;
    graph::Executor executor(ctx.device());
    auto r = (*limited)->run(executor, in, s);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::OutOfMemory);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The setup writes its records through shared memory, word by word (packTriangle and
// packGeometry in cells_setup.glsl.inc): every field must land where cells.h puts it, for
// every triangle, the last workgroup's partial tail included (1,932 triangles).
TEST_CASE("cells: the setup's records hold every field where cells.h puts it", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    CellScene scene = mixedScene();
    const float c = std::cos(0.5f), s = std::sin(0.5f);  // turned and scaled: the model's rows all count
    scene.transforms[1] = {1.5f * c, -1.5f * s, 0, 0.3f, 1.5f * s, 1.5f * c, 0, 0.2f, 0, 0, 1.5f, 0.1f, 0, 0, 0, 1};
    CellRunOptions opt;
    opt.resolution = 64;
    opt.direction = {0.3, 0.5, 1.0};
    const CellRun run = runCells(ctx, **stage, scene, opt);
    REQUIRE(run.pairs.size() > 50);

    const std::uint32_t n = (*stage)->triangleCount();
    REQUIRE(n % gpu::kCellsGroupSize != 0);
    const BufferRead reads[] = {{(*stage)->trianglesBuffer(), VkDeviceSize(n) * sizeof(gpu::CellsTriangle)},
                                {(*stage)->geometryBuffer(), VkDeviceSize(n) * sizeof(gpu::CellsGeometry)}};
    const auto bytes = copyToHost(ctx.device(), reads);
    std::vector<gpu::CellsTriangle> tris(n);
    std::vector<gpu::CellsGeometry> geos(n);
    std::memcpy(tris.data(), bytes[0].data(), bytes[0].size());
    std::memcpy(geos.data(), bytes[1].data(), bytes[1].size());

    const gpu::Projection pr = fitProjection(scene, opt.direction);
    const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
    std::uint32_t t = 0, planes = 0;
    for (std::size_t o = 0; o < scene.meshes.size(); ++o) {
        const HostMesh& m = scene.meshes[o];
        const std::vector<Float3> world = worldPositions(m, scene.transformOf(o));
        for (std::size_t local = 0; local < m.triangleCount(); ++local, ++t) {
            const gpu::CellsTriangle& r = tris[t];
            const gpu::CellsGeometry& g = geos[t];
            INFO("object " << o << ", triangle " << local);
            CHECK(r.key == (std::uint32_t(o) | (scene.selfOf(o) ? gpu::kCellsKeySelf : 0u)));
            CHECK((r.mode & gpu::kCellsEdges) != 0);
            CHECK((r.mode & ~(gpu::kCellsEdges | gpu::kCellsPlane)) == 0);
            planes += (r.mode & gpu::kCellsPlane) != 0 ? 1 : 0;
            CHECK((r.spare[0] | r.spare[1] | r.spare[2] | g.spare[0] | g.spare[1] | g.spare[2]) == 0);
            if ((*stage)->filterSupported()) CHECK(g.eps == 0.0f);  // the CPU's world vertices, bit for bit
            CHECK(r.pad > 0.0f);
            CHECK(r.ez >= 0.0f);
            const std::uint32_t lo_x = r.cells_lo & 0xFFFF, lo_y = r.cells_lo >> 16, hi_x = r.cells_hi & 0xFFFF, hi_y = r.cells_hi >> 16;
            CHECK((lo_x <= hi_x && lo_y <= hi_y && hi_x < opt.resolution && hi_y < opt.resolution));
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t index = m.indices[3 * local + k];
                CHECK(g.index[k] == index);
                const Float3 w = (*stage)->filterSupported() ? world[index] : Float3{g.v[3 * k], g.v[3 * k + 1], g.v[3 * k + 2]};
                CHECK((bits(g.v[3 * k]) == bits(w.x) && bits(g.v[3 * k + 1]) == bits(w.y) && bits(g.v[3 * k + 2]) == bits(w.z)));
                // The sampling coordinates within their bounds of the projection of w.
                const auto row = [&](int i) {
                    const gpu::vec4& q = pr.row[i];
                    return double(q.x) * w.x + double(q.y) * w.y + double(q.z) * w.z + double(q.w);
                };
                CHECK(std::fabs(double(r.x[k]) - row(0) * opt.resolution) <= double(r.pad));
                CHECK(std::fabs(double(r.y[k]) - row(1) * opt.resolution) <= double(r.pad));
                CHECK(std::fabs(double(r.z[k]) - row(2)) <= double(r.ez) + 1e-6);
                CHECK((r.zmin <= r.z[k] && r.z[k] <= r.zmax));
                CHECK((lo_x <= std::uint32_t(std::max(0.0f, r.x[k])) + 1 && std::uint32_t(std::max(0.0f, r.x[k])) <= hi_x + 1));
            }
        }
    }
    CHECK(t == n);
    CHECK(planes > n / 2);  // mostly non-degenerate projections: the plane words hold something
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: dispatches split into rows of workgroups give the same pairs", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(6);
    CellScene scene = mixedScene();
    scene.meshes.push_back(soup(rng, 2000, -0.5f, 0.5f, 0.02f, "soup"));
    scene.self.push_back(1);
    CellRunOptions opt;
    opt.resolution = 300;  // 90K cells: 88 scan blocks
    const CellRun whole = runCells(ctx, **stage, scene, opt);
    requireAllFound(whole, referencePairs(scene));
    for (std::uint32_t x : {1u, 3u, 7u}) {
        INFO("rows of " << x << " workgroups");
        opt.settings.max_workgroups_x = x;
        const CellRun split = runCells(ctx, **stage, scene, opt);
        CHECK(split.pairs == whole.pairs);
        CHECK(split.result.stats.entries == whole.result.stats.entries);
        CHECK(split.result.stats.candidates == whole.result.stats.candidates);
    }
}

// A submission holds at most one chunk of the pair pass, so that work left running after a
// timeout ends soon: chunks must decide exactly what one pass decides, with the filter and
// with the exact decision, and a chunk that overflows the survivors reruns the stage.
TEST_CASE("cells: the pair pass in chunks decides what one pass decides", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(11);
    CellScene scene = mixedScene();
    scene.meshes.push_back(soup(rng, 1500, -0.5f, 0.5f, 0.03f, "soup"));
    scene.self.push_back(1);
    for (auto [exact, exact_pass] : {std::pair{false, ExactPass::Auto}, std::pair{true, ExactPass::Inline}, std::pair{true, ExactPass::Queued}}) {
        INFO((exact ? "exact decision, " : "filter") << (exact ? toString(exact_pass) : ""));
        CellRunOptions opt;
        opt.resolution = 128;
        opt.settings.exact = exact;
        opt.settings.exact_pass = exact_pass;
        const CellRun whole = runCells(ctx, **stage, scene, opt);
        REQUIRE(whole.result.stats.candidates > 500);
        auto pairPasses = [](const CellRun& run) {
            return std::count_if(run.result.passes.begin(), run.result.passes.end(),
                                 [](const graph::PassTiming& p) { return p.name == "cells-pairs"; });
        };
        auto exactPasses = [](const CellRun& run) {
            return std::count_if(run.result.passes.begin(), run.result.passes.end(),
                                 [](const graph::PassTiming& p) { return p.name == "cells-exact"; });
        };
        CHECK(pairPasses(whole) == 1);  // automatic: one chunk on a scene this small
        CHECK(whole.result.stats.exact_queued == (exact_pass == ExactPass::Queued));
        if (exact) REQUIRE(whole.result.stats.exact_tests > 100);
        for (std::uint32_t chunk : {97u, 1000u, 1u << 20}) {
            INFO("chunks of " << chunk << " candidates");
            opt.settings.pair_chunk = chunk;
            const CellRun split = runCells(ctx, **stage, scene, opt);
            CHECK(split.pairs == whole.pairs);
            CHECK(split.result.stats.runs == 1);
            CHECK(split.result.stats.candidates == whole.result.stats.candidates);
            CHECK(split.result.stats.survivors == whole.result.stats.survivors);
            CHECK(split.result.stats.filtered == whole.result.stats.filtered);
            CHECK(split.result.stats.exact_tests == whole.result.stats.exact_tests);
            CHECK(split.result.stats.duplicates == whole.result.stats.duplicates);
            CHECK(std::uint64_t(pairPasses(split)) == std::max<std::uint64_t>(1, (whole.result.stats.candidates + chunk - 1) / chunk));
            // Queued: each chunk's exact pass over that chunk's queue.
            CHECK(exactPasses(split) == (exact_pass == ExactPass::Queued ? pairPasses(split) : 0));
        }
        // Tiny survivor capacity: a chunk overflows it, counting only the survivors so far;
        // the stage sizes for every candidate then, so chunks cost no more reruns than one pass.
        opt.settings.initial.survivors = 1;
        opt.settings.pair_chunk = 0;
        auto fresh = passes::CellStage::create(ctx.device());
        REQUIRE(fresh);
        const CellRun one_pass = runCells(ctx, **fresh, scene, opt);
        auto fresh_chunked = passes::CellStage::create(ctx.device());
        REQUIRE(fresh_chunked);
        opt.settings.pair_chunk = 211;
        const CellRun grown = runCells(ctx, **fresh_chunked, scene, opt);
        CHECK(one_pass.pairs == whole.pairs);
        CHECK(grown.pairs == whole.pairs);
        CHECK(one_pass.result.stats.runs >= 2);
        CHECK(grown.result.stats.runs == one_pass.result.stats.runs);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// ExactPass::Auto: the one kernel at first and for few canonical candidates, the exact pass
// of its own once the last run had passes::kExactQueuedFrom of them, and back below
// kExactInlineBelow; the same pairs every time.
TEST_CASE("cells: the exact pass follows the last run's canonical candidates", "[cells][gpu]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64: no exact decision on the GPU");
        return;
    }
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(23);
    CellScene dense;  // a soup of slivers in a thin slab: many canonical candidates, most disjoint
    dense.meshes.push_back(soup(rng, 8000, -0.5f, 0.5f, 0.08f, "dense"));
    for (Float3& p : dense.meshes.back().positions) p.z *= 0.05f;
    dense.self.push_back(1);
    CellScene sparse = mixedScene();
    CellRunOptions opt;
    opt.resolution = 16;
    opt.settings.exact = true;
    const auto canonical = [](const CellRun& r) { return r.result.stats.candidates - r.result.stats.duplicates; };
    const CellRun first = runCells(ctx, **stage, dense, opt);
    INFO(canonical(first) << " canonical candidates, " << first.result.stats.exact_tests << " exact tests");
    REQUIRE(canonical(first) >= passes::kExactQueuedFrom);
    CHECK_FALSE(first.result.stats.exact_queued);  // inline at first
    const CellRun queued = runCells(ctx, **stage, dense, opt);
    CHECK(queued.result.stats.exact_queued);
    CHECK(queued.pairs == first.pairs);
    CHECK(queued.result.stats.exact_tests >= first.result.stats.exact_tests);  // the plane sides filter alone
    const CellRun few = runCells(ctx, **stage, sparse, opt);
    REQUIRE(canonical(few) < passes::kExactInlineBelow);
    CHECK(few.result.stats.exact_queued);  // as the last run said
    const CellRun back = runCells(ctx, **stage, sparse, opt);
    CHECK_FALSE(back.result.stats.exact_queued);
    CHECK(back.pairs == few.pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: before the exact pass a filter that rejects little is skipped, then measured again", "[cells][gpu]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64: no exact decision on the GPU");
        return;
    }
    // Two coplanar sheets, one shifted by a third of a square: every candidate is coplanar,
    // which the plane sides never reject.
    CellScene flat;
    flat.meshes.push_back(generated(clothGrid(1.0f, 1.0f, 24, 24), "sheet"));
    flat.meshes.push_back(generated(clothGrid(1.0f, 1.0f, 24, 24), "shifted sheet"));
    flat.transforms = {kIdentityTransform, translation(1.0f / 72, 1.0f / 72, 0.0f)};
    flat.self = {0, 0};
    std::mt19937 rng(31);
    CellScene soupy;  // slivers in a box: most candidates are proved disjoint
    soupy.meshes.push_back(soup(rng, 3000, -0.5f, 0.5f, 0.05f, "soup"));
    soupy.self.push_back(1);
    CellRunOptions opt;
    opt.resolution = 16;
    opt.settings.exact = true;
    opt.settings.exact_pass = ExactPass::Queued;
    const auto canonical = [](const CellRun& r) { return r.result.stats.candidates - r.result.stats.duplicates; };

    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    const auto reference = referencePairs(flat);
    REQUIRE(reference.size() > 1000);
    const CellRun measured = runCells(ctx, **stage, flat, opt);
    INFO(canonical(measured) << " canonical candidates, " << measured.result.stats.filtered << " filtered");
    CHECK(measured.result.stats.filter_ran);
    REQUIRE(double(measured.result.stats.filtered) < passes::kFilterUsefulShare * double(canonical(measured)));
    CHECK(measured.pairs == reference);
    for (std::uint32_t k = 0; k < passes::kFilterRecheckRuns; ++k) {
        const CellRun skipped = runCells(ctx, **stage, flat, opt);
        CHECK_FALSE(skipped.result.stats.filter_ran);
        CHECK(skipped.result.stats.filtered == 0);
        CHECK(skipped.result.stats.exact_tests == canonical(skipped));  // every canonical candidate decided exactly
        CHECK(skipped.pairs == reference);
    }
    const CellRun again = runCells(ctx, **stage, flat, opt);
    CHECK(again.result.stats.filter_ran);  // measured again
    CHECK(again.pairs == reference);

    // Where the filter pays for itself it runs every time; and never skipped when asked so.
    auto other = passes::CellStage::create(ctx.device());
    REQUIRE(other);
    const CellRun rejecting = runCells(ctx, **other, soupy, opt);
    REQUIRE(double(rejecting.result.stats.filtered) >= passes::kFilterUsefulShare * double(canonical(rejecting)));
    const CellRun next = runCells(ctx, **other, soupy, opt);
    CHECK(next.result.stats.filter_ran);
    CHECK(next.pairs == rejecting.pairs);
    opt.settings.skip_unhelpful_filter = false;
    auto pinned = passes::CellStage::create(ctx.device());
    REQUIRE(pinned);
    for (int k = 0; k < 2; ++k) CHECK(runCells(ctx, **pinned, flat, opt).result.stats.filter_ran);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: identical results run to run", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(5);
    CellScene scene = mixedScene();
    scene.meshes.push_back(soup(rng, 3000, -0.5f, 0.5f, 0.02f, "soup"));
    scene.self.push_back(1);
    CellRunOptions opt;
    opt.resolution = 128;
    const CellRun first = runCells(ctx, **stage, scene, opt);
    REQUIRE(first.pairs.size() > 100);
    for (int k = 0; k < 3; ++k) {
        const CellRun next = runCells(ctx, **stage, scene, opt);
        CHECK(next.pairs == first.pairs);
        CHECK(next.result.stats.entries == first.result.stats.entries);
        CHECK(next.result.stats.candidates == first.result.stats.candidates);
        CHECK(next.result.stats.duplicates == first.result.stats.duplicates);
        CHECK(next.result.stats.filtered == first.result.stats.filtered);
        CHECK(next.result.stats.survivors == first.result.stats.survivors);
    }
}

TEST_CASE("cells: deep cells (sorted in shared and in global memory) and big triangles", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(8);
    CellScene scene;
    scene.meshes.push_back(soup(rng, 2500, 0.0f, 1.0f, 0.03f, "a"));
    scene.meshes.push_back(soup(rng, 2500, 0.0f, 1.0f, 0.03f, "b"));
    scene.meshes.push_back(generated(box({0.3f, 0.3f, 0.3f}, 1), "box"));
    scene.transforms = {kIdentityTransform, kIdentityTransform, translation(0.5f, 0.5f, 0.5f)};
    scene.self = {1, 0, 0};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 200);
    for (std::uint32_t n : {1u, 3u, 8u, 512u}) {
        INFO("resolution " << n);
        CellRunOptions opt;
        opt.resolution = n;
        const CellRun run = runCells(ctx, **stage, scene, opt);
        requireAllFound(run, reference);
        if (n <= 3) CHECK(run.result.stats.deep_cells > 0);
        if (n == 1) CHECK(run.result.stats.max_cell > gpu::kCellsDeepShared);
        if (n == 512) CHECK(run.result.stats.big_triangles > 0);
    }
}

// Huge cells (more than kCellsDeepShared entries) are sorted in global memory, and copies --
// triangles of one self-testing object with the same three local positions, in any order
// -- are a run the sweep skips (they share every vertex position: neighbours). What must
// not be skipped: copies in different objects (pairs), copies in an object that does not
// test itself (never paired anyway), a copy and a distinct triangle sharing a vertex
// position (the narrow phase's rule, not the sweep's), triangles crossing the copies.
// Exact on the GPU: the survivors are the reference's pairs, at one cell (huge), two,
// and 16 (shallow and shared-memory cells) alike.
TEST_CASE("cells: huge cells with coincident copies, within one object and across objects, give the exact pairs", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(31);
    const Float3 t0{0.1f, 0.1f, 0.5f}, t1{0.9f, 0.15f, 0.52f}, t2{0.45f, 0.85f, 0.48f};
    CellScene scene;
    HostMesh a = soup(rng, 500, 0.0f, 1.0f, 0.04f, "a");
    for (int k = 0; k < 300; ++k) {
        if (k % 3 == 0) addTriangle(a, t0, t1, t2);
        else if (k % 3 == 1) addTriangle(a, t2, t0, t1);  // the same corners, turned
        else addTriangle(a, t1, t0, t2);                  // and flipped
    }
    // 100 copies sharing their indices with the first copy above: index neighbours too.
    const std::uint32_t first = a.indices[500 * 3];
    for (int k = 0; k < 100; ++k) a.indices.insert(a.indices.end(), {first, first + 1, first + 2});
    // A distinct triangle sharing one corner's position with the copies: a neighbour of each.
    addTriangle(a, t0, {0.3f, 0.7f, 0.9f}, {0.6f, 0.2f, 0.1f});
    scene.meshes.push_back(std::move(a));
    HostMesh b = soup(rng, 300, 0.0f, 1.0f, 0.04f, "b");
    for (int k = 0; k < 200; ++k) addTriangle(b, t0, t1, t2);  // coincident with a's: pairs
    scene.meshes.push_back(std::move(b));
    HostMesh c{"c", {}, {}};
    for (int k = 0; k < 150; ++k) addTriangle(c, t2, t1, t0);  // copies without self-collision
    scene.meshes.push_back(std::move(c));
    HostMesh cross{"cross", {}, {}};
    addTriangle(cross, {0.4f, 0.3f, 0.0f}, {0.5f, 0.3f, 1.0f}, {0.45f, 0.4f, 0.5f});
    scene.meshes.push_back(std::move(cross));
    scene.self = {1, 1, 0, 1};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 200 * 400);  // b's copies with a's, and more
    // Both deep sweeps: the one a GPU runs (no loop counters) and, on llvmpipe, the counted
    // one (the scene stays within its limit).
    for (auto [n, guard] : {std::pair{1u, true}, std::pair{1u, false}, std::pair{2u, true}, std::pair{2u, false}, std::pair{16u, true}}) {
        INFO("resolution " << n << (guard ? "" : ", no loop guard"));
        CellRunOptions opt;
        opt.resolution = n;
        opt.direction = {0.2, 0.1, 1.0};
        opt.settings.exact = true;
        opt.settings.loop_guard = guard;
        const CellRun run = runCells(ctx, **stage, scene, opt);
        INFO("deepest cell " << run.result.stats.max_cell << ", candidates " << run.result.stats.candidates);
        if (n == 1) {
            CHECK(run.result.stats.huge_cells == 1);
            CHECK(run.result.stats.max_cell > gpu::kCellsDeepShared);
        }
        requireExactPairs(run, reference);
    }
}

// The shallow sweep works in tiles: the cells whose first entry lies in one chunk of
// kCellsEntryChunk entries, the last of them running into the next chunk, a deep last cell
// left to the deep sweep, each tile ordered by depth in shared memory. Columns of small
// triangles, one cell each, with counts that put cell boundaries anywhere relative to the
// chunks (empty cells, one entry, a chunk's worth exactly, one more, deep ones between
// shallow ones), at a few depths only (ties in zlo, coplanar pairs), in two objects, one
// testing itself: the exact pairs, the same candidates whether the sweep runs in one
// submission or in chunks of whole tiles, and with the rows of workgroups split.
TEST_CASE("cells: the shallow sweep's tiles hold cells across chunk boundaries, deep cells and depth ties", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    constexpr std::uint32_t kN = 16;  // cells per side over [0, 1]^2, world projection
    std::mt19937 rng(50);
    const std::uint32_t counts[] = {0, 0, 1, 2, 3, 7, 31, 64, 100, 200, 255, 256, 257, 300};
    std::uniform_int_distribution<std::size_t> pick(0, std::size(counts) - 1);
    std::uniform_real_distribution<float> in_cell(0.3f, 0.5f), level(0.0f, 1.0f);
    CellScene scene;
    HostMesh a{"a", {}, {}}, b{"b", {}, {}};
    std::uint32_t triangles = 0;
    for (std::uint32_t cell = 0; cell < kN * kN; ++cell) {
        const float x0 = float(cell % kN) / kN, y0 = float(cell / kN) / kN, w = 1.0f / kN;
        const std::uint32_t k = counts[pick(rng)];
        for (std::uint32_t t = 0; t < k; ++t) {
            const float x = x0 + w * in_cell(rng), y = y0 + w * in_cell(rng);
            const float z = 0.1f * std::floor(8.0f * level(rng)) + 0.1f, h = float(t % 3) * 0.03f;  // flat ones tie
            addTriangle(t % 2 ? b : a, {x, y, z}, {x + 0.15f * w, y, z + h}, {x, y + 0.15f * w, z + 0.5f * h});
        }
        triangles += k;
    }
    scene.meshes = {a, b};
    scene.self = {1, 0};
    const auto reference = referencePairs(scene);
    REQUIRE(triangles > 4 * gpu::kCellsEntryChunk);
    REQUIRE(reference.size() > 1000);
    CellRunOptions opt;
    opt.resolution = kN;
    opt.projection = worldProjection();
    opt.settings.exact = true;
    const CellRun whole = runCells(ctx, **stage, scene, opt);
    CHECK(whole.result.stats.deep_cells > 0);
    CHECK(whole.result.stats.max_cell == 300);
    requireExactPairs(whole, reference);
    for (std::uint32_t work : {1u, 5000u}) {  // chunks of one tile, and of a few
        INFO("sweep chunks of " << work << " comparisons");
        opt.settings.sweep_work = work;
        const CellRun split = runCells(ctx, **stage, scene, opt);
        CHECK(split.result.stats.sweep_chunks > 1);
        CHECK(split.result.stats.candidates == whole.result.stats.candidates);
        CHECK(split.pairs == whole.pairs);
        requireExactPairs(split, reference);
    }
    opt.settings.sweep_work = 0;
    opt.settings.max_workgroups_x = 3;
    const CellRun rows = runCells(ctx, **stage, scene, opt);
    CHECK(rows.result.stats.candidates == whole.result.stats.candidates);
    CHECK(rows.pairs == whole.pairs);
}

// Poles' fans of slivers: every triangle of a fan shares the pole's vertex, so each walk in
// its cell visits the whole fan, and every pair is a neighbour pair the sweep drops. The
// shallow tiles read a partner's vertex indices from the geometry; the deep sweep reads
// them from shared memory, with each entry's box carried through its sort, and loads the
// partner's entry only for a pair it may keep. Fans of 40 and 100 (shallow) and 600
// triangles (deep), each pierced by needles of its own object and of another: the exact
// pairs, and no fan pair among the candidates.
TEST_CASE("cells: poles' fans of slivers, pierced by needles, give the exact pairs and no neighbour candidates", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    constexpr std::uint32_t kN = 16;  // cells per side over [0, 1]^2, world projection
    constexpr float kRim = 0.02f;     // every fan within one cell of 1/16
    std::mt19937 rng(61);
    std::uniform_real_distribution<float> angle(0.0f, 6.2831853f), radius(0.3f * kRim, 0.6f * kRim);
    HostMesh fans{"fans", {}, {}}, other{"needles", {}, {}};
    const struct {
        Float3 pole;
        std::uint32_t slivers;
    } cones[] = {{{0.22f, 0.22f, 0.5f}, 40}, {{0.53f, 0.53f, 0.5f}, 100}, {{0.78f, 0.34f, 0.5f}, 600}};
    std::uint64_t fan_pairs = 0;
    for (const auto& cone : cones) {
        const auto pole = static_cast<std::uint32_t>(fans.positions.size());
        fans.positions.push_back(cone.pole);
        for (std::uint32_t k = 0; k < cone.slivers; ++k) {
            const float a = 6.2831853f * float(k) / float(cone.slivers);
            fans.positions.push_back({cone.pole.x + kRim * std::cos(a), cone.pole.y + kRim * std::sin(a), cone.pole.z - 0.01f});
        }
        for (std::uint32_t k = 0; k < cone.slivers; ++k)
            fans.indices.insert(fans.indices.end(), {pole, pole + 1 + k, pole + 1 + (k + 1) % cone.slivers});
        fan_pairs += std::uint64_t{cone.slivers} * (cone.slivers - 1) / 2;
        // Vertical needles through the cone's surface: 3 of the fans' own object, 3 of another.
        for (int n = 0; n < 6; ++n) {
            const float a = angle(rng), r = radius(rng);
            const float x = cone.pole.x + r * std::cos(a), y = cone.pole.y + r * std::sin(a);
            addTriangle(n < 3 ? fans : other, {x, y, 0.45f}, {x + 0.004f, y + 0.001f, 0.45f}, {x + 0.002f, y, 0.56f});
        }
    }
    CellScene scene;
    scene.meshes = {fans, other};
    scene.self = {1, 0};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() >= 6 * 3);  // every needle crosses its cone
    CellRunOptions opt;
    opt.resolution = kN;
    opt.projection = worldProjection();
    opt.settings.exact = true;
    const CellRun run = runCells(ctx, **stage, scene, opt);
    CHECK(run.result.stats.deep_cells == 1);
    CHECK(run.result.stats.max_cell >= 606);
    requireExactPairs(run, reference);
    // The needles' pairs only (each needle meets at most its fan and the other needles).
    INFO("candidates " << run.result.stats.candidates << ", the fans' neighbour pairs " << fan_pairs);
    CHECK(run.result.stats.candidates <= 6 * (40 + 100 + 600) + 3 * 15);
    CHECK(run.result.stats.exact_neighbours == 0);
}

// The fill's workgroups of 256 triangles take their slots per cell through a table in
// shared memory where their footprints crowd into few cells, one footprint at a time
// where they are spread (cells_fill.comp, the GPU form; lavapipe runs the per-footprint
// form unless told). Each object here is three such workgroups: small triangles in a patch
// of a few cells (the table), triangles of 7 x 7 cells in a patch of 2,500 cells (crowded,
// but more cells than the table holds: most take their slots alone) and small ones all over
// the grid (spread). The two objects cross in every patch: the exact pairs, whatever way
// each footprint found its slot, and the same entries and candidates in both forms.
TEST_CASE("cells: the fill's workgroups crowded into few cells, crowded past the table and spread give the exact pairs", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    constexpr std::uint32_t kN = 128;  // cells per side over [0, 1]^2, world projection
    std::mt19937 rng(51);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto block = [&](HostMesh& m, float x0, float x1, float size) {
        for (std::uint32_t t = 0; t < gpu::kCellsGroupSize; ++t) {
            const float x = x0 + (x1 - x0 - size) * unit(rng), y = x0 + (x1 - x0 - size) * unit(rng);
            const float z = 0.45f + 0.1f * unit(rng);
            addTriangle(m, {x, y, z}, {x + size, y, 0.45f + 0.1f * unit(rng)}, {x, y + size, 0.45f + 0.1f * unit(rng)});
        }
    };
    CellScene scene;
    HostMesh a{"a", {}, {}}, b{"b", {}, {}};
    for (HostMesh* m : {&a, &b}) {
        block(*m, 0.20f, 0.25f, 0.01f);  // about 6 x 6 cells: every workgroup cell in the table
        block(*m, 0.50f, 0.90f, 0.045f);  // 7 x 7 cells each in 51 x 51: crowded, past the table
        block(*m, 0.00f, 1.00f, 0.004f);  // all over the grid: spread
    }
    scene.meshes = {a, b};
    scene.self = {1, 0};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 1000);
    CellRunOptions opt;
    opt.resolution = kN;
    opt.projection = worldProjection();
    opt.settings.exact = true;
    opt.settings.fill_slots = passes::CellStageSettings::FillSlots::PerFootprint;
    const CellRun per_footprint = runCells(ctx, **stage, scene, opt);
    requireExactPairs(per_footprint, reference);
    opt.settings.fill_slots = passes::CellStageSettings::FillSlots::PerCell;  // what a GPU runs (Auto)
    for (int round = 0; round < 2; ++round) {
        INFO("slots per cell, round " << round);
        const CellRun run = runCells(ctx, **stage, scene, opt);
        requireExactPairs(run, reference);
        CHECK(run.result.stats.entries == per_footprint.result.stats.entries);
        CHECK(run.result.stats.candidates == per_footprint.result.stats.candidates);
        CHECK(run.pairs == per_footprint.pairs);
    }
}

// Boxes within a cell: two objects' small triangles share one cell and overlap in depth
// everywhere, but lie in different parts of it. The sweep pairs only entries whose boxes
// within the cell meet, so of the k * k depth-overlapping pairs only the one crossing pair
// (whose boxes meet) becomes a candidate -- on the shallow path, the sorted deep path and
// the chunked deep path alike.
TEST_CASE("cells: triangles apart within a shared cell are not paired", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    // Sampling = world (worldProjection); N = 4, so cell (1, 1) is [0.25, 0.5]^2.
    // Standing triangles spanning depth 0.3 to 0.7, their x within [x0, x1].
    const auto standing = [](HostMesh& m, std::uint32_t count, float x0, float x1) {
        for (std::uint32_t k = 0; k < count; ++k) {
            const float x = x0 + (x1 - x0 - 0.005f) * float(k % 20) / 19.0f, y = 0.27f + 0.2f * float(k / 20) / float(count / 20 + 1);
            addTriangle(m, {x, y, 0.3f}, {x + 0.005f, y, 0.7f}, {x, y + 0.005f, 0.5f});
        }
    };
    for (std::uint32_t per_object : {100u, 300u, 700u}) {  // 200 entries (shallow), 600 (sorted), 1,400 (chunks)
        INFO(per_object << " triangles per object");
        CellScene scene;
        HostMesh a, b;
        a.name = "left";
        b.name = "right";
        standing(a, per_object, 0.26f, 0.32f);
        standing(b, per_object, 0.40f, 0.48f);
        // One crossing pair between the two groups: a flat triangle at depth 0.5 and a
        // standing one through it.
        addTriangle(a, {0.35f, 0.30f, 0.5f}, {0.37f, 0.30f, 0.5f}, {0.36f, 0.32f, 0.5f});
        addTriangle(b, {0.36f, 0.29f, 0.4f}, {0.36f, 0.33f, 0.4f}, {0.36f, 0.31f, 0.6f});
        scene.meshes = {a, b};
        const auto reference = referencePairs(scene);
        REQUIRE(reference.size() == 1);
        CellRunOptions opt;
        opt.resolution = 4;
        opt.projection = worldProjection();
        const CellRun run = runCells(ctx, **stage, scene, opt);
        requireAllFound(run, reference);
        CHECK(run.result.stats.max_cell >= 2 * per_object);
        if (per_object > 100) CHECK(run.result.stats.deep_cells > 0);
        CHECK(run.result.stats.candidates == 1);
    }
}

// Entry keys hold the box only up to kCellsBoxedObjects objects; past it they keep the
// whole 31-bit object and the box is the whole cell. Both layouts on one scene: a soup of
// single-triangle objects and a self-intersecting tube, once as 33,001 objects (the tube's
// self flag and object ids past 2^15 must survive), once as two self-colliding objects.
TEST_CASE("cells: more objects than boxed entry keys hold", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(33001);
    const HostMesh soup_mesh = soup(rng, 33000, 0.0f, 1.0f, 0.02f, "soup");
    const HostMesh tube = generated(twistedTube(0.4f, 0.08f, 64, 8, 1.5f), "tube");
    const Transform centre = translation(0.5f, 0.5f, 0.5f);
    CellScene many, few;
    for (std::size_t t = 0; t < soup_mesh.triangleCount(); ++t) {
        HostMesh one;
        one.name = "soup triangle";
        for (int k = 0; k < 3; ++k) {
            one.positions.push_back(soup_mesh.positions[soup_mesh.indices[3 * t + k]]);
            one.indices.push_back(static_cast<std::uint32_t>(k));
        }
        many.meshes.push_back(std::move(one));
    }
    many.meshes.push_back(tube);
    many.transforms.assign(many.meshes.size(), kIdentityTransform);
    many.transforms.back() = centre;
    many.self.assign(many.meshes.size(), 0);
    many.self.back() = 1;
    REQUIRE(many.meshes.size() > gpu::kCellsBoxedObjects);
    const auto reference = referencePairs(many);
    INFO("reference " << reference.size());
    std::size_t tube_self = 0, past_boxed = 0;
    for (const TrianglePair& p : reference) {
        tube_self += p.object_a == p.object_b;
        past_boxed += p.object_b > gpu::kCellsBoxedObjects;
    }
    REQUIRE(tube_self > 0);
    REQUIRE(past_boxed > 0);
    CellRunOptions opt;
    opt.resolution = 128;
    opt.shared_buffers = true;
    const CellRun run_many = runCells(ctx, **stage, many, opt);
    requireAllFound(run_many, reference);
    few.meshes = {soup_mesh, tube};
    few.transforms = {kIdentityTransform, centre};
    few.self = {1, 1};
    const auto reference_few = referencePairs(few);
    const CellRun run_few = runCells(ctx, **stage, few, opt);
    requireAllFound(run_few, reference_few);
    // The boxes prune on the two-object scene only.
    CHECK(run_few.result.stats.candidates < run_many.result.stats.candidates);
}

TEST_CASE("cells: projection written by an earlier pass of the same graph", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    const CellScene scene = mixedScene();
    CellRunOptions opt;
    opt.resolution = 64;
    const CellRun expected = runCells(ctx, **stage, scene, opt);

    UploadedScene up = uploadScene(ctx.device(), scene);
    const gpu::Projection pr = fitProjection(scene, opt.direction);
    passes::CellStageInput in;
    in.objects = up.objects;
    in.resolution = 64;
    in.self_collision = scene.self;
    auto other = passes::CellStage::create(ctx.device());
    REQUIRE(other);
    const passes::CellStageResult out = runWithWrittenProjection(ctx, **other, in, pr);
    REQUIRE(expected.pairs.size() > 50);
    CHECK(toObjectPairs(up.objects, out.pairs) == expected.pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("cells: without the filter every pair the filter keeps survives", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(9);
    CellScene scene = mixedScene();
    scene.meshes.push_back(soup(rng, 2000, -0.6f, 0.6f, 0.03f, "soup"));
    scene.self.push_back(1);
    CellRunOptions opt;
    opt.resolution = 96;
    const CellRun with = runCells(ctx, **stage, scene, opt);
    opt.settings.filter = false;
    const CellRun without = runCells(ctx, **stage, scene, opt);
    CHECK_FALSE(without.result.stats.filter_ran);
    CHECK(without.result.stats.filtered == 0);
    const auto reference = referencePairs(scene);
    requireAllFound(with, reference);
    requireAllFound(without, reference);
    CHECK(comparePairs(without.pairs, with.pairs).false_negatives == 0);  // with ⊆ without
    if (ctx.device().shader_float64) {
        CHECK(with.result.stats.filtered > 0);
        CHECK(without.pairs.size() > with.pairs.size());
    }
}

TEST_CASE("cells: bad input is refused, naming the object and triangle", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    CellScene scene;
    scene.meshes.push_back(generated(uvSphere(1.0f, 8, 4), "a"));
    scene.meshes.push_back(generated(uvSphere(1.0f, 8, 4), "b"));
    auto attempt = [&](const CellScene& s, auto&& edit) {
        UploadedScene up = uploadScene(ctx.device(), s);
        passes::CellStageInput in;
        in.objects = up.objects;
        in.projection = fitProjection(scene, {0, 0, 1});
        in.resolution = 32;
        edit(in, up);
        graph::Executor executor(ctx.device());
        auto r = (*stage)->run(executor, in);
        REQUIRE_NO_VALIDATION_MESSAGES(ctx);
        return r;
    };
    SECTION("non-finite and huge positions, found on the GPU") {
        for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 1e38f, 5e18f}) {
            CellScene s = scene;
            s.meshes[1].positions[s.meshes[1].indices[3 * 5 + 1]].y = bad;
            auto r = attempt(s, [](passes::CellStageInput&, UploadedScene&) {});
            INFO("value " << bad);
            REQUIRE_FALSE(r);
            CHECK(r.error().code() == ErrorCode::InvalidMesh);
            CHECK_THAT(r.error().message(), Catch::Contains("object 1, triangle"));
        }
    }
    SECTION("an index beyond the vertices") {
        CellScene s = scene;
        s.meshes[0].indices[3 * 7 + 2] = 100000;
        auto r = attempt(s, [](passes::CellStageInput&, UploadedScene&) {});
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(r.error().message(), Catch::Contains("object 0, triangle 7") && Catch::Contains("index"));
    }
    SECTION("a world coordinate of 2^62 or more") {
        auto r = attempt(scene, [](passes::CellStageInput&, UploadedScene& up) {
            // Entries below 2^62, but the sum reaches 8e18 > 2^62 at the sphere's +x pole.
            up.objects[1].model[0] = {4e18f, 0, 0, 4e18f};
        });
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(r.error().message(), Catch::Contains("object 1") && Catch::Contains("world"));
    }
    SECTION("host-side checks") {
        auto huge = attempt(scene, [](passes::CellStageInput& in, UploadedScene& up) {
            up.objects[0].model[2].w = 1e30f;
            in.objects = up.objects;
        });
        REQUIRE_FALSE(huge);
        CHECK(huge.error().code() == ErrorCode::InvalidArgument);
        auto projection = attempt(scene, [](passes::CellStageInput& in, UploadedScene&) {
            in.projection->row[1].y = std::numeric_limits<float>::quiet_NaN();
        });
        REQUIRE_FALSE(projection);
        CHECK(projection.error().code() == ErrorCode::InvalidArgument);
        auto resolution = attempt(scene, [](passes::CellStageInput& in, UploadedScene&) { in.resolution = 0; });
        REQUIRE_FALSE(resolution);
        CHECK(resolution.error().code() == ErrorCode::InvalidArgument);
        auto base = attempt(scene, [](passes::CellStageInput& in, UploadedScene& up) {
            up.objects[1].triangle_base += 1;
            in.objects = up.objects;
        });
        REQUIRE_FALSE(base);
        CHECK_THAT(base.error().message(), Catch::Contains("triangle_base"));
    }
    SECTION("the stage works again after an error") {
        CellRunOptions opt;
        opt.resolution = 16;
        requireAllFound(runCells(ctx, **stage, scene, opt), referencePairs(scene));
    }
}

TEST_CASE("cells: denormal coordinates are handled conservatively", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(10);
    CellScene scene;
    // Two soups a few times 1e-39 across (denormal floats, which a GPU may flush to zero),
    // and an ordinary object that sets the projection's scale.
    scene.meshes.push_back(soup(rng, 300, -3e-39f, 3e-39f, 2e-39f, "tiny-a"));
    scene.meshes.push_back(soup(rng, 300, -3e-39f, 3e-39f, 2e-39f, "tiny-b"));
    scene.meshes.push_back(generated(uvSphere(1.0f, 8, 4), "ordinary"));
    scene.transforms = {kIdentityTransform, kIdentityTransform, translation(3, 0, 0)};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 50);
    CellRunOptions opt;
    opt.resolution = 64;
    requireAllFound(runCells(ctx, **stage, scene, opt), reference);
}
