// Pathological scenes under the reliable method, the default: each ends in the
// exact pairs or a named error (LimitExceeded naming the count and
// DetectSettings::limits.max_candidate_pairs, or the extent), in bounded time, with the validation
// layer quiet, and the world goes on after the error. The same scenes under the peeling
// method: pathological_tests.cpp. docs/stability.md, "Pathological scenes", has the
// numbers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <optional>
#include <utility>
#include <string>

#include "cells/cells.h"
#include "stability_support.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// The case's scene with the automatic settings of the default method (the case's own
// settings are the peeling method's rays), or with `s`.
DetectSettings reliable(DetectSettings s = {}) {
    s.method = DetectMethod::Reliable;
    return s;
}

// A LimitExceeded that names the budget.
void checkBudgetError(const Result<DetectResult>& r, const std::string& count) {
    REQUIRE_FALSE(r);
    INFO(r.error().message());
    CHECK(r.error().code() == ErrorCode::LimitExceeded);
    CHECK(mentions(r.error(), "max_candidate_pairs"));
    CHECK(mentions(r.error(), count));
}

}  // namespace

// Copies of one triangle sharing its indices: every two are neighbours, and a huge cell's
// sort puts them in one run of copies that its sweep skips at once (before: every two
// compared, 65,545 copies refused as 8.6e10 comparisons). The crossing triangle still
// visits every copy, 2 x 65,545 loop iterations in one invocation: past what llvmpipe runs
// (it ends longer loops silently), so there the run fails naming that limit.
TEST_CASE("reliable: a stack of 65,545 copies of a triangle gives every pair (on llvmpipe a named loop limit), 1,100 copies give every pair",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    auto deep = repeatedTriangle(65545);
    auto sorted = repeatedTriangle(1100);  // deeper than kCellsDeepShared: a huge cell, sorted in global memory
    REQUIRE(deep);
    REQUIRE(sorted);
    const bool llvmpipe = ctx.device().info.loop_iteration_limit != 0;
    for (bool engine : {false, true}) {
        INFO((engine ? "engine buffers" : "host meshes"));
        // The automatic resolution for host meshes (8 cells here); a world of engine meshes
        // alone knows no extent before its first successful detection and takes 256,
        // where 1,100 copies are 1.9e10 comparisons: beyond the budget too.
        DetectSettings s = reliable();
        if (engine) s.resolution = 8;
        // On llvmpipe 2 cells: the error is the same, without sorting 64 cells of 65,546 first
        // (20 s there).
        if (llvmpipe) s.resolution = 2;
        std::vector<EngineMesh> keep;
        auto world = worldOf(ctx, *deep, engine ? &keep : nullptr);
        // Every copy in every cell it covers, with the crossing triangle: 65,546 deep.
        auto r = world->detect(s);
        if (llvmpipe) {
            REQUIRE_FALSE(r);
            INFO(r.error().message());
            CHECK(r.error().code() == ErrorCode::LimitExceeded);
            CHECK(mentions(r.error(), "loop iterations"));
            CHECK(mentions(r.error(), "65546 footprints in one cell"));
        } else {
            INFO((r ? std::string() : r.error().message()));
            REQUIRE(r);
            checkExact(r->pairs, *deep->reference);
            CHECK(r->stats.cells.huge_cells > 0);
        }
        CHECK(world->state() == WorldState::Ready);

        std::vector<EngineMesh> keep_sorted;
        auto fits = worldOf(ctx, *sorted, engine ? &keep_sorted : nullptr);
        auto found = fits->detect(s);
        INFO((found ? std::string() : found.error().message()));
        REQUIRE(found);
        checkExact(found->pairs, *sorted->reference);
        CHECK(found->stats.cells.max_cell >= 1100);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: after LimitExceeded the world detects again, with a larger budget the same pairs",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    auto c = repeatedTriangle(1100);
    REQUIRE(c);
    auto world = worldOf(ctx, *c);
    DetectSettings tight = reliable();
    tight.limits.max_candidate_pairs = 10000;
    for (int round = 0; round < 2; ++round) {
        INFO("round " << round);
        checkBudgetError(world->detect(tight), "max_candidate_pairs (10000)");
        CHECK(world->state() == WorldState::Ready);
        auto r = world->detect(reliable());
        REQUIRE(r);
        checkExact(r->pairs, *c->reference);
    }
    // submit()/collect() fail and recover the same way.
    REQUIRE(world->submit(tight));
    checkBudgetError(world->collect(), "max_candidate_pairs (10000)");
    REQUIRE(world->submit(reliable()));
    auto collected = world->collect();
    REQUIRE(collected);
    checkExact(collected->pairs, *c->reference);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// Each cell under the slabs holds about 8 footprints per slab. Cells of more than 1,024
// are sorted in global memory by (object, depth), so the sweep pairs each slab with the
// few that meet it in depth: linear in the slabs (before, every two footprints of a cell
// were compared: 1,000 slabs took 4 s on lavapipe, 32,768 were refused as 5.4e11
// comparisons). The slabs touch nothing: the pairs are the contact's, the same for any
// number of slabs (the reference is computed for 300). On lavapipe 32,768 slabs (7.7M
// footprints, cells of 262,148) take most of a minute; 4,096 (cells of 32,772) show the same.
TEST_CASE("reliable: a contact under 300, 1,000 and 4,096 slabs gives every pair, at the automatic grid",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    auto few = slabsOverContact(300);
    REQUIRE(few);
    REQUIRE_FALSE(few->reference->empty());
    for (std::uint32_t slabs : {300u, 1000u, 4096u}) {
        INFO(slabs << " slabs");
        auto c = slabsOverContact(slabs, false);
        REQUIRE(c);
        auto world = worldOf(ctx, *c);
        auto found = world->detect(reliable());
        INFO((found ? std::string() : found.error().message()));
        REQUIRE(found);
        checkExact(found->pairs, *few->reference);
        const CellStats& cells = found->stats.cells;
        INFO("deepest cell " << cells.max_cell << ", comparisons " << cells.comparisons << ", footprints " << cells.entries);
        CHECK(cells.max_cell > gpu::kCellsDeepShared);
        CHECK(cells.huge_cells > 0);
        // About log^2 per footprint (a huge cell's sort counts L (L + 1) / 4, L = ceil(log2 k):
        // 95 for 262,148 footprints), where comparing every two footprints of a cell counts
        // half the deepest cell per footprint: 1,202 for 300 slabs, 131,074 for 32,768.
        CHECK(cells.comparisons < 128 * cells.entries);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: a thousand objects give the exact reference's pairs", "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    auto c = manyObjects(1000);
    REQUIRE(c);
    REQUIRE_FALSE(c->reference->empty());
    auto world = worldOf(ctx, *c);
    for (std::optional<std::uint32_t> resolution : {std::optional<std::uint32_t>{}, std::optional<std::uint32_t>{256}}) {
        DetectSettings s = reliable();
        s.resolution = resolution;
        auto r = world->detect(s);
        REQUIRE(r);
        checkExact(r->pairs, *c->reference);
        CHECK(r->stats.objects == 1000);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: mutually crossing triangles: max_candidate_pairs and max_pairs name their counts",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    // 10,000: 50M intersecting pairs, every triangle in the cells along the z axis. A
    // budget of 2^22 bounds the sweep's comparisons at 2^28: refused before it runs.
    auto huge = crossingTriangles(10000);
    REQUIRE(huge);
    auto world = worldOf(ctx, *huge);
    DetectSettings s = reliable();
    s.limits.max_candidate_pairs = std::uint64_t{1} << 22;
    auto r = world->detect(s);
    checkBudgetError(r, "max_candidate_pairs (4194304)");
    CHECK(mentions(r.error(), "10000 footprints in one cell"));

    // 300: 44,850 pairs, found whole; a candidate budget below what the sweep forms names
    // that count; max_pairs keeps the first 20,000 and counts the rest.
    auto c = crossingTriangles(300);
    REQUIRE(c);
    const std::size_t all = std::size_t{300} * 299 / 2;
    REQUIRE(c->reference->size() == all);
    auto fits = worldOf(ctx, *c);
    auto full = fits->detect(reliable());
    REQUIRE(full);
    checkExact(full->pairs, *c->reference);
    // What the budget counts: the pairs the sweep wrote and the repeats it dropped.
    const std::uint64_t candidates = full->stats.cells.candidates + full->stats.cells.repeats;
    REQUIRE(candidates > 100000);
    DetectSettings tight = reliable();
    tight.limits.max_candidate_pairs = 100000;
    auto stopped = fits->detect(tight);
    checkBudgetError(stopped, std::to_string(candidates) + " candidate pairs");
    CHECK(fits->state() == WorldState::Ready);

    DetectSettings capped = reliable();
    capped.limits.max_pairs = 20000;
    std::vector<TrianglePair> kept_before;
    for (unsigned threads : {1u, 2u}) {
        INFO(threads << " threads");
        auto w = makeWorld(ctx, {.threads = threads});
        addScene(*w, c->scene);
        auto capped_run = w->detect(capped);
        REQUIRE(capped_run);
        CHECK(capped_run->pairs.size() == 20000);
        CHECK(capped_run->pairs_left_out == all - 20000);
        REQUIRE(capped_run->incomplete);
        CHECK(capped_run->incomplete->code() == ErrorCode::LimitExceeded);
        CHECK(mentions(*capped_run->incomplete, "max_pairs"));
        CHECK(std::includes(c->reference->begin(), c->reference->end(), capped_run->pairs.begin(), capped_run->pairs.end()));
        if (!kept_before.empty()) CHECK((capped_run->pairs == kept_before));
        kept_before = capped_run->pairs;
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

namespace {

// The crossing pair scaled by `scale` (pathological_scenes.hpp), detected by the reliable
// method in a world of its own: the result, the world's state after it, the exact pair.
struct ScaledDetection {
    Result<DetectResult> result;
    WorldState state;
    std::vector<TrianglePair> reference;
};
ScaledDetection detectScaled(ValidatedContext& ctx, float scale) {
    auto c = scaledCrossing(scale);
    REQUIRE(c);
    auto world = worldOf(ctx, *c);
    auto r = world->detect(reliable());
    return {std::move(r), world->state(), *c->reference};
}

}  // namespace

TEST_CASE("reliable: coordinates from subnormal to 2^62 give the pair or a named error", "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    // Inside the reliable method's range (below 2^62) and wider than the 1e-30 every method
    // needs: the pair. 1e-29 and 1e-25 put the fitted projection's rows above 2^62: the
    // stage scales them back (before: "a projection entry is not finite or not below 2^62").
    for (float scale : {1e-29f, 1e-25f, 1.0f, 1e18f}) {
        INFO("scale " << scale);
        const ScaledDetection d = detectScaled(ctx, scale);
        INFO((d.result ? std::string() : d.result.error().message()));
        REQUIRE(d.result);
        checkExact(d.result->pairs, d.reference);
    }
    // 2^62 and more (1e19, 1e29): the reliable method's limit, named with the object.
    for (float scale : {1e19f, 1e29f}) {
        INFO("scale " << scale);
        const ScaledDetection d = detectScaled(ctx, scale);
        REQUIRE_FALSE(d.result);
        CHECK(d.result.error().code() == ErrorCode::InvalidMesh);
        CHECK(mentions(d.result.error(), "'flat'"));
        CHECK(mentions(d.result.error(), "2^62"));
        CHECK(d.state == WorldState::Ready);
    }
    // Narrower than 1e-30 or subnormal: LimitExceeded, as for the peeling method.
    for (float scale : {1e-35f, 1e-40f}) {
        INFO("scale " << scale);
        const ScaledDetection d = detectScaled(ctx, scale);
        REQUIRE_FALSE(d.result);
        CHECK(d.result.error().code() == ErrorCode::LimitExceeded);
        CHECK(mentions(d.result.error(), "1e-30"));
    }
    // Flat scenes whose depth extent is tiny or subnormal (the fit's depth row is 1 / extent,
    // infinite for the subnormal one): the pair.
    for (float dz : {1e-20f, 1e-40f}) {
        INFO("depth extent " << dz);
        auto world = makeWorld(ctx);
        REQUIRE(world->addMesh(HostMesh{"a", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}}, {.name = "a"}));
        REQUIRE(world->addMesh(HostMesh{"b", {{0.2f, 0.2f, 0}, {1.2f, 0.2f, dz}, {0.2f, 1.2f, 0}}, {0, 1, 2}}, {.name = "b"}));
        auto r = world->detect(reliable());
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        CHECK(r->pairs.size() == 1);
    }
    // 1e38 in engine buffers: the GPU check leaves them out and names them.
    auto far = scaledCrossing(1e38f);
    auto near = scaledCrossing(1.0f);
    REQUIRE(far);
    REQUIRE(near);
    std::vector<EngineMesh> keep;
    auto world = worldOf(ctx, *far, &keep);
    auto none = world->detect(reliable());
    REQUIRE_FALSE(none);
    CHECK(none.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(none.error(), "no object left"));
    keep.push_back(engineCopy(ctx.device(), near->scene.objects[0].mesh));
    REQUIRE(world->addGpuMesh(keep.back().desc, {.name = "near"}));
    auto r = world->detect(reliable());
    REQUIRE(r);
    CHECK(r->pairs.empty());
    CHECK(r->excluded.size() == 2);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// Every cell a pile covers holds all of it, so each overlapping pair repeats in every cell
// its two footprints share: 2,200 copies wrote 96.7M candidates for 2.4M pairs (94.3M
// repeats dropped later by the pair pass), 52 s on lavapipe. Cells of kCellsSweepDedupe
// entries or more make the first part of the pair pass's canonical-cell check in the
// sweep (repeatsHere: the cell to the left or below keeps the pair), so each pair is
// written about once. 200 copies: shallow cells; 600: the deep sweep's sorted cells (where
// llvmpipe once got the whole check wrong); 1,100 and 3,000: huge cells, sorted in global
// memory, where the copies (the same three positions: neighbours) are one run the sweep
// skips, so only the crossing triangle's pairs are visited (before: 3,000 copies failed
// the default budget, 180M overlapping pairs).
TEST_CASE("reliable: a pile of copies writes each overlapping pair once, in its canonical cell, and gives every pair",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    for (std::uint32_t copies : {200u, 600u, 1100u, 3000u}) {
        INFO(copies << " copies");
        auto c = copiesWithOwnVertices(copies);
        REQUIRE(c);
        auto world = worldOf(ctx, *c);
        auto r = world->detect(reliable());
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        checkExact(r->pairs, *c->reference);
        const CellStats& cells = r->stats.cells;
        INFO("candidates " << cells.candidates << ", repeats " << cells.repeats << ", deepest cell " << cells.max_cell
                           << ", comparisons " << cells.comparisons);
        REQUIRE(cells.max_cell > copies);  // every copy and the crossing triangle in one cell
        if (copies > gpu::kCellsDeepShared) {
            // Only the crossing triangle's pairs: written once, repeated in the other cells.
            CHECK(cells.huge_cells > 0);
            CHECK(cells.candidates == copies);
            CHECK(cells.repeats < 64u * copies);
            CHECK(cells.comparisons < 128 * cells.entries);  // log^2 per footprint (every two: copies / 2)
            continue;
        }
        // Overlapping pairs: the copies' among themselves and each copy's with the crossing
        // triangle; each written once (before: once per shared cell, 30-40 times as many).
        const std::uint64_t overlapping = std::uint64_t(copies) * (copies - 1) / 2 + copies;
        CHECK(cells.candidates >= copies);
        CHECK(cells.candidates <= overlapping);
        CHECK(cells.repeats > 10 * overlapping);
        // The budget still counts every overlapping pair the sweep found, repeats included
        // (the count before the sweep dropped them), so a budget below it fails naming it:
        // all of them when the sweep was one chunk, else what the chunks counted until the
        // count passed the budget ("or more"; the chunks after it are not swept).
        if (copies == 600) {
            DetectSettings small = reliable();
            small.limits.max_candidate_pairs = 4 * overlapping;
            auto refused = world->detect(small);
            checkBudgetError(refused, "candidate pairs");
            const std::string text = refused.error().message(), prefix = "cell stage: ";
            REQUIRE(text.rfind(prefix, 0) == 0);
            const std::uint64_t counted = std::stoull(text.substr(prefix.size()));
            CHECK(counted > small.limits.max_candidate_pairs);
            if (mentions(refused.error(), "or more"))
                CHECK(counted <= cells.candidates + cells.repeats);
            else
                CHECK(counted == cells.candidates + cells.repeats);
            CHECK(world->state() == WorldState::Ready);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// One triangle with 5,000 partners: the GPU's pair sort puts them in order in one
// invocation (a heap sort, some 100,000 loop iterations). llvmpipe ends a shader
// invocation's loops past 65,535 iterations without an error, so there the sort fails by
// name (before: "out of order (internal error)" from the host's check, and device pairs
// silently out of order); Auto sorts on the host there. Elsewhere, the host's pairs.
TEST_CASE("reliable: a triangle with 5,000 partners sorts on the GPU as on the host, or on llvmpipe fails naming the loop limit",
          "[stability][gpu][limits][reliable]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        SUCCEED("no shaderFloat64: pairs are not sorted on the GPU");
        return;
    }
    auto pile = copiesWithOwnVertices(5000);
    REQUIRE(pile);
    // The crossing triangle first, so that it is the lower id of each of its pairs.
    std::swap(pile->scene.objects[0], pile->scene.objects[1]);
    auto world = worldOf(ctx, *pile);
    DetectSettings host = reliable();
    host.resolution = 2;
    host.reliable.pair_sort = PairSort::Cpu;
    auto expected = world->detect(host);
    REQUIRE(expected);
    REQUIRE(expected->pairs.size() == 5000);
    DetectSettings gpu = host;
    gpu.reliable.pair_sort = PairSort::Gpu;
    auto sorted = world->detect(gpu);
    if (ctx.device().info.loop_iteration_limit != 0) {
        REQUIRE_FALSE(sorted);
        INFO(sorted.error().message());
        CHECK(sorted.error().code() == ErrorCode::LimitExceeded);
        CHECK(mentions(sorted.error(), "sorts in one shader invocation"));
        CHECK(world->state() == WorldState::Ready);
        // Auto stays on the host there, even after a detection of 5,000 pairs.
        DetectSettings automatic = host;
        automatic.reliable.pair_sort = PairSort::Auto;
        auto again = world->detect(automatic);
        REQUIRE(again);
        CHECK_FALSE(again->stats.reliable.pairs_sorted_on_gpu);
        CHECK(again->pairs == expected->pairs);
    } else {
        INFO((sorted ? std::string() : sorted.error().message()));
        REQUIRE(sorted);
        CHECK(sorted->stats.reliable.pairs_sorted_on_gpu);
        CHECK(sorted->pairs == expected->pairs);
    }
    // Device responses with the crossing triangle last: its 5,000 partners are the bucket of
    // lower partners the responses' pass sorts. The same rule: named on llvmpipe, else the
    // host's responses to the bit.
    auto last = copiesWithOwnVertices(5000);
    REQUIRE(last);
    auto last_world = worldOf(ctx, *last);
    auto host_responses = last_world->detect(host);
    REQUIRE(host_responses);
    REQUIRE(host_responses->responses.size() == 5001);
    DetectSettings on_device = host;
    on_device.reliable.device_pairs = true;
    on_device.reliable.device_responses = true;
    auto responded = last_world->detect(on_device);
    if (ctx.device().info.loop_iteration_limit != 0) {
        REQUIRE_FALSE(responded);
        INFO(responded.error().message());
        CHECK(responded.error().code() == ErrorCode::LimitExceeded);
        CHECK(mentions(responded.error(), "device responses"));
        CHECK(mentions(responded.error(), "sorts in one shader invocation"));
    } else {
        INFO((responded ? std::string() : responded.error().message()));
        REQUIRE(responded);
        CHECK(responded->stats.reliable.device_responses_written == 5001);
        CHECK(responded->responses.size() == 5001);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
