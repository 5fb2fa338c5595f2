// The reliable method's sweep and pair pass in chunks (BroadPhaseSettings::sweep_work and
// pair_chunk): each chunk is a submission of its own (the broad phase's Again), so that GPU
// work left running after a timeout is at most one chunk. The passes after them (the GPU
// sort, proximity) must see every chunk: the same sorted pairs and proximity records as one
// pass, and the sweep's counts unchanged. The sorted pairs handed to the host in pieces while
// the GPU computes the responses (BroadPhaseSettings::on_sorted_pairs) are the final ones. The
// one pass of few pairs (BroadPhaseSettings::small_sort) ends every chunk's submission and
// gives the device pairs' sort and responses.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>
#include <thread>
#include <vector>

#include "broad/broad_phase.hpp"
#include "broad/cells/reliable_method.hpp"
#include "mesh/mesh_upload.hpp"
#include "proximity/ownership.hpp"
#include "support/device_copy.hpp"
#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

HostMesh sphereAt(Float3 t, float radius, std::uint32_t slices = 24, std::uint32_t stacks = 12) {
    auto made = uvSphere(radius, slices, stacks);
    REQUIRE(made);
    HostMesh m = std::move(*made);
    REQUIRE(transformMesh(m, Transform3x4{1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}));
    return m;
}

// `copies` copies of one small triangle, each with its own vertices, at `t`.
HostMesh pileAt(Float3 t, std::uint32_t copies) {
    HostMesh m{"pile", {}, {}};
    for (std::uint32_t k = 0; k < copies; ++k) {
        m.positions.insert(m.positions.end(), {{t.x - 0.1f, t.y - 0.1f, t.z}, {t.x + 0.1f, t.y - 0.1f, t.z}, {t.x, t.y + 0.1f, t.z + 0.05f}});
        m.indices.insert(m.indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    return m;
}

struct Outputs {
    std::vector<std::uint64_t> pairs;  // the sorted pairs' global ids, a << 32 | b
    std::vector<std::uint8_t> proximity;  // the records' bytes
    std::size_t records = 0;
    std::uint32_t pair_passes = 0, sweeps = 0;
    CellStageStats cells;
};

Outputs run(BroadPhase& bp, std::span<const GpuMesh> meshes, BroadPhaseSettings s) {
    auto r = bp.run(meshes, s);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    REQUIRE(r->has_sorted_pairs);
    REQUIRE(r->has_proximity);
    Outputs out;
    for (const CandidatePair& p : r->sorted_pairs) out.pairs.push_back(std::uint64_t{p.a} << 32 | p.b);
    out.records = r->proximity.size();
    out.proximity.resize(r->proximity.size_bytes());
    if (!out.proximity.empty()) std::memcpy(out.proximity.data(), r->proximity.data(), out.proximity.size());
    for (const graph::PassTiming& p : r->passes) {
        out.pair_passes += p.name == std::string_view(kPairPassName) ? 1u : 0u;
        out.sweeps += p.name == std::string_view(kSweepPassName) ? 1u : 0u;
    }
    out.cells = r->cells;
    return out;
}

// `meshes` uploaded for the reliable method with proximity: each owns its primitives, is
// tagged with its index, and only mesh `self` tests itself.
struct Uploaded {
    std::vector<HostMesh> meshes;
    std::vector<std::vector<std::uint8_t>> owned;  // what the uploaded meshes' proximity_owned views
    UploadedMeshes up;
};

std::unique_ptr<Uploaded> upload(vk::Device& device, std::vector<HostMesh> meshes, std::size_t self) {
    auto u = std::make_unique<Uploaded>();
    u->meshes = std::move(meshes);
    std::vector<const HostMesh*> ptrs;
    for (const HostMesh& m : u->meshes) ptrs.push_back(&m);
    auto up = uploadMeshes(device, ptrs);
    REQUIRE(up);
    u->up = std::move(*up);
    for (std::size_t i = 0; i < u->meshes.size(); ++i) {
        const HostMesh& m = u->meshes[i];
        u->owned.push_back(proximity::ownedPrimitives(m.indices, static_cast<std::uint32_t>(m.positions.size())));
        u->up.meshes[i].proximity_owned = u->owned.back();
        u->up.meshes[i].tag = static_cast<std::uint32_t>(i);
        u->up.meshes[i].self_collision = i == self;
    }
    return u;
}

// The exact decision and the sort on the GPU, with proximity within `distance`.
BroadPhaseSettings exactWithProximity(std::uint32_t resolution, double distance) {
    BroadPhaseSettings s;
    s.resolution = resolution;
    s.direction = {0.1f, 0.2f, 1.0f};
    s.exact_on_gpu = true;
    s.sort_on_gpu = true;
    s.proximity_distance = distance;
    return s;
}

}  // namespace

TEST_CASE("reliable: the pair pass in chunks gives the sorted pairs and proximity records of one pass", "[gpu][cells][proximity]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);  // lavapipe and the GPUs we test on have it
    const auto up = upload(ctx.device(),
                           {sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), sphereAt({0.6f, -0.03f, 0.02f}, 1.0f), sphereAt({0.0f, 1.1f, 0.0f}, 0.7f)}, 2);
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    BroadPhaseSettings s = exactWithProximity(48, 0.02);
    // One chunk of each, whatever the machine's load (the automatic sizes split a run that
    // would take over ~200 ms: a loaded runner under the sanitizers).
    s.pair_chunk = ~0u;
    s.sweep_work = ~0u;
    (void)run(**bp, up->up.meshes, s);  // the buffers grow to the scene: one run from now on
    const Outputs whole = run(**bp, up->up.meshes, s);
    REQUIRE(whole.pairs.size() > 50);
    REQUIRE(whole.records > 50);
    INFO("one pass: " << whole.cells.candidates << " candidates, " << whole.cells.exact_tests << " exact tests, exact pass "
                      << (whole.cells.exact_queued ? "queued" : "inline"));
    CHECK(whole.pair_passes == 1);
    for (std::uint32_t chunk : {157u, 1000u}) {
        INFO("chunks of " << chunk << " candidates");
        s.pair_chunk = chunk;
        const Outputs split = run(**bp, up->up.meshes, s);
        CHECK(split.pair_passes > 1);
        CHECK(split.cells.pair_chunks == split.pair_passes);
        CHECK(split.cells.sweep_chunks == 1);  // the pair pass's chunks swept nothing
        CHECK(split.pairs == whole.pairs);
        CHECK(split.records == whole.records);
        CHECK(split.proximity == whole.proximity);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: the sweep in chunks, or with repeats checked only in deep chunks, gives the sorted pairs, proximity records and counts of one sweep", "[gpu][cells][proximity]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);
    // Shallow cells (the spheres), sorted deep cells (300 copies, self-colliding: their
    // repeats are dropped in the sweep) and deep cells in chunks (1,100 copies).
    const auto up = upload(ctx.device(),
                           {sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), sphereAt({0.6f, -0.03f, 0.02f}, 1.0f),
                            pileAt({0.1f, 0.2f, 0.9f}, 300), pileAt({2.5f, 0.0f, 0.0f}, 1100)},
                           2);
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    BroadPhaseSettings s = exactWithProximity(40, 0.01);
    s.sweep_work = ~0u;  // one chunk
    s.pair_chunk = ~0u;  // and one pair pass, whatever the load
    (void)run(**bp, up->up.meshes, s);  // the buffers grow to the scene: one run from now on
    const Outputs whole = run(**bp, up->up.meshes, s);
    REQUIRE(whole.pairs.size() > 50);
    REQUIRE(whole.cells.repeats > 0);  // the sorted deep cells dropped repeats
    REQUIRE(whole.cells.deep_cells > 0);
    REQUIRE(whole.cells.max_cell > 1024);  // and some cells came in chunks of entries
    CHECK(whole.sweeps == 1);
    CHECK(whole.cells.sweep_chunks == 1);
    for (std::uint32_t work : {1u, 20000u, 300000u}) {
        INFO("sweep chunks of " << work << " comparisons");
        s.sweep_work = work;
        const Outputs split = run(**bp, up->up.meshes, s);
        CHECK(split.sweeps > 1);
        CHECK(split.cells.sweep_chunks == split.sweeps);
        CHECK(split.pairs == whole.pairs);
        CHECK(split.records == whole.records);
        CHECK(split.proximity == whole.proximity);
        CHECK(split.cells.candidates == whole.cells.candidates);
        CHECK(split.cells.repeats == whole.cells.repeats);
        CHECK(split.cells.neighbours == whole.cells.neighbours);
        CHECK(split.cells.candidate_cells == whole.cells.candidate_cells);
        CHECK(split.cells.survivors == whole.cells.survivors);
        CHECK(split.cells.runs == 1);
    }
    // A GPU's choice (CellStageSettings::RepeatChecks::DeepChunksOnly): the shallow sweep
    // compiled without the repeat checks, the sorted deep cells without them too; the pair
    // pass drops those repeats instead. Same pairs and records, more candidates.
    s.repeat_checks = 2;
    for (std::uint32_t work : {~0u, 20000u}) {
        INFO("repeats checked only in the deep cells' chunks, sweep chunks of " << work);
        s.sweep_work = work;
        const Outputs plain = run(**bp, up->up.meshes, s);
        CHECK(plain.pairs == whole.pairs);
        CHECK(plain.proximity == whole.proximity);
        CHECK(plain.cells.repeats < whole.cells.repeats);
        CHECK(plain.cells.candidates > whole.cells.candidates);
        CHECK(plain.cells.candidates + plain.cells.repeats == whole.cells.candidates + whole.cells.repeats);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

namespace {

// Device pairs' and proximity's headers as an engine reads them at the signal of a run's
// first submission: submitted, finished (polled: collect() has not run the chunks after it),
// then copied as test::copyToHost copies.
struct FirstHeaders {
    gpu::DevicePairsHeader pairs;
    DeviceProximityHeader proximity;
};

FirstHeaders firstSubmission(vk::Device& device, BroadPhase& bp, std::span<const GpuMesh> meshes, const BroadPhaseSettings& s,
                             const DeviceProximity& proximity) {
    REQUIRE(bp.submit(meshes, s, 1));
    for (;;) {
        auto done = bp.poll();
        REQUIRE(done);
        if (*done == vk::Completion::Done) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    const auto view = bp.devicePairs();
    REQUIRE(view);
    const test::BufferRead reads[2] = {{view->header, sizeof(gpu::DevicePairsHeader)}, {proximity.header, sizeof(DeviceProximityHeader)}};
    const auto bytes = test::copyToHost(device, reads);
    FirstHeaders h{};
    std::memcpy(&h.pairs, bytes[0].data(), sizeof h.pairs);
    std::memcpy(&h.proximity, bytes[1].data(), sizeof h.proximity);
    return h;
}

}  // namespace

// detect_result.hpp, "Results on the GPU": an engine reads the pairs at the world's signal, which is the
// end of the run's first submission; where the sweep or the pair pass goes on in later
// submissions, what it reads there must say Incomplete (count 0), never a part of the pairs
// as complete. Here the first sweep chunks hold only a far sphere's cells (it collides with
// nothing, and two of them on opposite corners put one first whichever way the projection
// turns), so they found no candidate at all: the case the device pairs once took for done.
TEST_CASE(
    "reliable: a run whose sweep or pair pass goes on in later submissions leaves its device pairs and proximity incomplete at the first",
    "[gpu][cells][proximity]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);
    const auto up = upload(ctx.device(),
                           {sphereAt({-6.0f, -6.0f, 0.0f}, 1.0f, 64, 32), sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f),
                            sphereAt({0.6f, -0.03f, 0.02f}, 1.0f), sphereAt({6.0f, 6.0f, 0.0f}, 1.0f, 64, 32)},
                           std::size_t(-1));
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    BroadPhaseSettings s = exactWithProximity(40, 0.03);
    s.sort_on_gpu = false;
    s.device_pairs = true;
    s.host_pairs = false;  // the engine's case: nothing read back but the header
    s.sweep_work = ~0u;
    s.pair_chunk = ~0u;
    auto whole = (*bp)->run(up->up.meshes, s);  // the buffers grow to the scene: one run from now on
    REQUIRE(whole);
    whole = (*bp)->run(up->up.meshes, s);
    REQUIRE(whole);
    REQUIRE(whole->device_header);
    const std::uint32_t pairs = whole->device_header->count;
    REQUIRE(pairs > 50);
    REQUIRE(whole->device_header->flags == 0);
    REQUIRE(whole->cells.sweep_chunks == 1);
    const DeviceProximity proximity = whole->proximity_device;
    const std::size_t records = whole->proximity.size();
    REQUIRE(records > 50);

    struct Split {
        const char* what;
        std::uint32_t sweep_work, pair_chunk;
    };
    for (const Split& split : {Split{"the sweep in chunks", 1u, ~0u}, Split{"the pair pass in chunks", ~0u, 157u}}) {
        INFO(split.what);
        s.sweep_work = split.sweep_work;
        s.pair_chunk = split.pair_chunk;
        const FirstHeaders first = firstSubmission(ctx.device(), **bp, up->up.meshes, s, proximity);
        CHECK(first.pairs.flags == kDevicePairsIncomplete);
        CHECK(first.pairs.count == 0);
        CHECK(first.proximity.flags == kDeviceProximityIncomplete);
        CHECK(first.proximity.count == 0);
        auto r = (*bp)->collect();  // the later chunks, then the sort and proximity once more
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        CHECK((r->cells.sweep_chunks > 1 || r->cells.pair_chunks > 1));
        REQUIRE(r->device_header);
        CHECK(r->device_header->flags == 0);
        CHECK(r->device_header->count == pairs);
        CHECK(r->proximity.size() == records);
        CHECK(r->proximity_device.header == proximity.header);  // the buffers read above
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("reliable: the sorted pairs handed over piece by piece while the GPU computes the responses are the final ones, in order",
          "[gpu][cells]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);
    // Two spheres and a fan of 100 coplanar triangles, self-colliding: 4,950 pairs in the fan,
    // more than three of the four pieces of the smallest copy (4,096 pairs) hold.
    const auto up = upload(ctx.device(), {sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), sphereAt({0.6f, -0.03f, 0.02f}, 1.0f), test::coplanarFan(100)}, 2);
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    BroadPhaseSettings s = exactWithProximity(48, 0.0);
    s.responses_on_gpu = true;
    s.pair_chunk = ~0u;
    s.sweep_work = ~0u;
    std::vector<std::pair<std::size_t, std::size_t>> pieces;  // [begin, end) of each call
    std::vector<std::uint64_t> taken;
    bool refuse_later = false;
    s.on_sorted_pairs = [&](std::span<const CandidatePair> all, std::size_t begin, std::size_t end) {
        pieces.emplace_back(begin, end);
        if (refuse_later && begin > 0) return false;
        if (begin == 0) taken.clear();
        for (std::size_t k = begin; k < end; ++k) taken.push_back(std::uint64_t{all[k].a} << 32 | all[k].b);
        return true;
    };
    const auto detect = [&] {
        pieces.clear();
        auto r = bp->get()->run(up->up.meshes, s);
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        REQUIRE(r->has_sorted_pairs);
        REQUIRE(r->has_sorted_responses);
        std::vector<std::uint64_t> final_pairs;
        for (const CandidatePair& p : r->sorted_pairs) final_pairs.push_back(std::uint64_t{p.a} << 32 | p.b);
        return std::make_pair(r->sorted_pairs_seen, final_pairs);
    };
    (void)detect();  // the buffers and the copy's capacity grow to the scene
    for (std::uint32_t piece : {0u, 50u, 1u << 30}) {
        INFO("pieces of at least " << piece << " pairs (0: automatic)");
        s.early_piece_pairs = piece;
        const auto [seen, final_pairs] = detect();
        REQUIRE(final_pairs.size() > 3 * 1024);
        CHECK(seen);
        CHECK(taken == final_pairs);
        REQUIRE_FALSE(pieces.empty());
        CHECK(pieces.front().first == 0);
        CHECK(pieces.back().second == final_pairs.size());
        for (std::size_t k = 1; k < pieces.size(); ++k) CHECK(pieces[k].first == pieces[k - 1].second);
        for (const auto& [begin, end] : pieces) CHECK(begin < end);
        CHECK(pieces.size() == (piece == 50 ? DevicePairStage::kMaxEarlyChunks : 1u));
    }
    // A refused piece ends the calls for that sort, and the result says it was not all taken.
    s.early_piece_pairs = 50;
    refuse_later = true;
    const auto [seen, final_pairs] = detect();
    CHECK_FALSE(seen);
    CHECK(pieces.size() == 2);
    // Without the GPU's responses nothing is handed over early.
    refuse_later = false;
    s.responses_on_gpu = false;
    pieces.clear();
    auto r = bp->get()->run(up->up.meshes, s);
    REQUIRE(r);
    CHECK(r->has_sorted_pairs);
    CHECK_FALSE(r->sorted_pairs_seen);
    CHECK(pieces.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The one pass of few pairs against the device-pairs passes (proved equal to the CPU's
// result in tests/api/exact_decision_tests.cpp): the same pairs and responses to the bit,
// whether the stage ran in one submission or in chunks; too many survivors are left to the
// host's path.
TEST_CASE("reliable: few pairs sorted in one pass give the device pairs' sort and responses, after chunks too, and leave too many to the host",
          "[gpu][cells]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    struct Sorted {
        std::vector<CandidatePair> pairs;
        std::vector<TriangleResponse> responses;
        std::size_t survivors = 0;
        bool one_pass = false;
        CellStageStats cells;
    };
    const auto detect = [&](std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
        auto r = bp->get()->run(meshes, s);
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        Sorted out;
        out.survivors = r->pairs.size();
        out.one_pass = r->sorted_in_one_pass;
        out.cells = r->cells;
        if (!r->has_sorted_pairs) return out;
        REQUIRE(r->has_sorted_responses);
        out.pairs.assign(r->sorted_pairs.begin(), r->sorted_pairs.end());
        out.responses.assign(r->sorted_responses.begin(), r->sorted_responses.end());
        return out;
    };
    const auto same = [](const Sorted& a, const Sorted& b) {
        REQUIRE(a.pairs.size() == b.pairs.size());
        REQUIRE(a.responses.size() == b.responses.size());
        CHECK(std::memcmp(a.pairs.data(), b.pairs.data(), a.pairs.size() * sizeof(CandidatePair)) == 0);
        CHECK(std::memcmp(a.responses.data(), b.responses.data(), a.responses.size() * sizeof(TriangleResponse)) == 0);
    };
    // Spheres crossing, a sphere resting on them and a self-colliding coplanar fan (every
    // triangle with many partners in one plane): 780 pairs in the fan.
    const auto up = upload(ctx.device(),
                           {sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), sphereAt({0.6f, -0.03f, 0.02f}, 1.0f), sphereAt({0.0f, 1.1f, 0.0f}, 0.7f),
                            test::coplanarFan(40)},
                           3);
    BroadPhaseSettings device_sort = exactWithProximity(48, 0.0);
    device_sort.responses_on_gpu = true;
    device_sort.pair_chunk = ~0u;
    device_sort.sweep_work = ~0u;
    (void)detect(up->up.meshes, device_sort);  // the copies grow to the scene
    const Sorted expected = detect(up->up.meshes, device_sort);
    REQUIRE(expected.pairs.size() > 780);
    CHECK_FALSE(expected.one_pass);
    BroadPhaseSettings small = device_sort;
    small.sort_on_gpu = small.responses_on_gpu = false;
    small.small_sort = true;
    for (std::uint32_t chunk : {~0u, 157u}) {
        INFO("pair pass chunks of " << chunk << " candidates");
        small.pair_chunk = chunk;
        const Sorted first = detect(up->up.meshes, small);  // copies sized for 1,024: too few responses here
        CHECK(first.survivors >= expected.pairs.size());  // the host's path is still there
        const Sorted one = detect(up->up.meshes, small);
        CHECK(one.one_pass);
        if (chunk != ~0u) CHECK(one.cells.pair_chunks > 1);
        same(one, expected);
    }
    // A fan of 100: 4,950 pairs, more survivors than the pass holds: the host sorts them.
    const auto many = upload(ctx.device(), {sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), test::coplanarFan(100)}, 1);
    small.pair_chunk = ~0u;
    const Sorted left = detect(many->up.meshes, small);
    CHECK_FALSE(left.one_pass);
    CHECK(left.pairs.empty());
    CHECK(left.survivors >= 4950);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
