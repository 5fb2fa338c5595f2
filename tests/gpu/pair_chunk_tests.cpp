// The reliable method's pair pass in chunks (BroadPhaseSettings::pair_chunk): each chunk is
// a submission of its own (the broad phase's Again), so that GPU work left running after a
// timeout is at most one chunk. The passes after the pair pass (the GPU sort, proximity)
// must see every chunk: the same sorted pairs and proximity records as one pass.
#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

#include "broad/broad_phase.hpp"
#include "broad/cells/reliable_method.hpp"
#include "mesh/mesh_upload.hpp"
#include "proximity/ownership.hpp"
#include "support/gpu_fixture.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

HostMesh sphereAt(Float3 t, float radius) {
    auto made = uvSphere(radius, 24, 12);
    REQUIRE(made);
    HostMesh m = std::move(*made);
    REQUIRE(transformMesh(m, Transform3x4{1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}));
    return m;
}

struct Outputs {
    std::vector<TrianglePair> pairs;
    std::vector<std::uint8_t> proximity;  // the records' bytes
    std::size_t records = 0;
    std::uint32_t pair_passes = 0;
};

Outputs run(BroadPhase& bp, std::span<const GpuMesh> meshes, BroadPhaseSettings s) {
    auto r = bp.run(meshes, s);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    REQUIRE(r->has_sorted_pairs);
    REQUIRE(r->has_proximity);
    Outputs out;
    out.pairs.assign(r->sorted_pairs.begin(), r->sorted_pairs.end());
    out.records = r->proximity.size();
    out.proximity.resize(r->proximity.size_bytes());
    if (!out.proximity.empty()) std::memcpy(out.proximity.data(), r->proximity.data(), out.proximity.size());
    for (const graph::PassTiming& p : r->passes) out.pair_passes += p.name == "cells-pairs" ? 1u : 0u;
    return out;
}

}  // namespace

TEST_CASE("reliable: the pair pass in chunks gives the sorted pairs and proximity records of one pass", "[gpu][cells][proximity]") {
    test::ValidatedContext ctx;
    REQUIRE(ctx.device().shader_float64);  // lavapipe and the GPUs we test on have it
    std::vector<HostMesh> meshes{sphereAt({-0.6f, 0.02f, 0.01f}, 1.0f), sphereAt({0.6f, -0.03f, 0.02f}, 1.0f),
                                 sphereAt({0.0f, 1.1f, 0.0f}, 0.7f)};
    auto up = uploadMeshes(ctx.device(), {&meshes[0], &meshes[1], &meshes[2]});
    REQUIRE(up);
    std::vector<std::vector<std::uint8_t>> owned;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        owned.push_back(proximity::ownedPrimitives(meshes[i].indices, static_cast<std::uint32_t>(meshes[i].positions.size())));
        up->meshes[i].proximity_owned = owned.back();
        up->meshes[i].tag = static_cast<std::uint32_t>(i);
        up->meshes[i].self_collision = i == 2;
    }
    auto bp = BroadPhase::create(ctx.device(), ReliableMethod::create);
    REQUIRE(bp);
    BroadPhaseSettings s;
    s.resolution = 48;
    s.direction = {0.1f, 0.2f, 1.0f};
    s.exact_on_gpu = true;
    s.sort_on_gpu = true;
    s.proximity_distance = 0.02;
    (void)run(**bp, up->meshes, s);  // the buffers grow to the scene: one run from now on
    const Outputs whole = run(**bp, up->meshes, s);
    REQUIRE(whole.pairs.size() > 50);
    REQUIRE(whole.records > 50);
    CHECK(whole.pair_passes == 1);
    for (std::uint32_t chunk : {157u, 1000u}) {
        INFO("chunks of " << chunk << " candidates");
        s.pair_chunk = chunk;
        const Outputs split = run(**bp, up->meshes, s);
        CHECK(split.pair_passes > 1);
        CHECK(split.pairs == whole.pairs);
        CHECK(split.records == whole.records);
        CHECK(split.proximity == whole.proximity);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
