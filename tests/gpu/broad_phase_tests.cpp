// GPU broad phase (paper passes 1-4, and depth-aware separation) on the device, validation
// on, against the CPU reference of the same four passes in tests/support.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <sstream>

#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "mesh/mesh_upload.hpp"
#include "support/broadphase_reference.hpp"
#include "support/gpu_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

// Rotation about an arbitrary axis, so pixel centres do not sit on edges by construction.
HostMesh placed(HostMesh m, float ax, float ay, float az, float angle, Float3 t, const std::string& name) {
    const float len = std::sqrt(ax * ax + ay * ay + az * az);
    ax /= len, ay /= len, az /= len;
    const float c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    Transform3x4 tr = {c + ax * ax * k,      ax * ay * k - az * s, ax * az * k + ay * s, t.x,
                       ay * ax * k + az * s, c + ay * ay * k,      ay * az * k - ax * s, t.y,
                       az * ax * k - ay * s, az * ay * k + ax * s, c + az * az * k,      t.z};
    REQUIRE(transformMesh(m, tr));
    m.name = name;
    return m;
}

HostMesh makeBox(float h, std::uint32_t sub = 2) {
    auto b = box({h, h, h}, sub);
    REQUIRE(b);
    return *b;
}

HostMesh makeSphere(float r, std::uint32_t seg = 16, std::uint32_t rings = 8) {
    auto s = uvSphere(r, seg, rings);
    REQUIRE(s);
    return *s;
}

HostMesh inverted(HostMesh m) {
    for (std::size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

struct Run {
    BroadPhaseResult gpu;
    test::ReferenceResult ref;
};

Run runBoth(test::ValidatedContext& ctx, BroadPhase& bp, const std::vector<const HostMesh*>& meshes,
            BroadPhaseSettings settings, const std::vector<bool>& open = {}, const std::vector<bool>& self = {}) {
    settings.keep_ray_image = true;
    if (!settings.region) settings.region = std::array<float, 6>{-2.5f, -2.5f, -2.5f, 2.5f, 2.5f, 2.5f};
    auto scene = uploadMeshes(ctx.device(), meshes, {.open = open});
    REQUIRE(scene);
    for (std::size_t i = 0; i < self.size(); ++i) scene->meshes[i].self_collision = self[i];
    auto gpu = bp.run(scene->meshes, settings);
    INFO((gpu ? std::string() : gpu.error().message()));
    REQUIRE(gpu);
    std::vector<test::BroadPhaseObject> objects;
    for (std::size_t i = 0; i < meshes.size(); ++i)
        objects.push_back({meshes[i], i < open.size() && open[i], i >= self.size() || self[i]});
    Run run{std::move(*gpu), {}};
    run.ref = test::referenceBroadPhase(objects, settings, run.gpu.layers);
    if (run.ref.ambiguousCount() > 0) {
        // Passes 2-4 are checked exactly from the GPU's rays (and depth intervals); pass 1 is
        // checked on every unambiguous ray by requireSameRays.
        auto ref2 = test::referenceBroadPhase(objects, settings, run.gpu.layers, {&run.gpu.ray_image, &run.gpu.ray_depth});
        run.ref.records = std::move(ref2.records);
    }
    return run;
}

// Rays equal wherever the reference is unambiguous; the scenes are built so none is.
void requireSameRays(const Run& r) {
    REQUIRE(r.gpu.ray_image.size() == r.ref.rays.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < r.ref.rays.size(); ++i)
        if (!r.ref.ambiguous[i] && r.gpu.ray_image[i] != r.ref.rays[i]) ++differ;
    CHECK(differ == 0);
    // Samples within 1e-3 px of an edge or 1e-6 of another fragment's depth (silhouettes,
    // intersection curves) may round either way; they must stay rare.
    INFO("ambiguous rays: " << r.ref.ambiguousCount());
    CHECK(r.ref.ambiguousCount() * 100 <= r.ref.rays.size());
    CHECK(r.gpu.depth_complexity == r.ref.depth_complexity);
    // Depth-aware: the same intervals on rays whose 3x3 neighbourhood is unambiguous (a
    // neighbour's collision decides whether a ray's near pairs count), up to float
    // rounding (relative to the interval: planes of steep triangles in pixel units).
    REQUIRE(r.gpu.ray_depth.size() == r.ref.ray_depth.size());
    const std::size_t n = static_cast<std::size_t>(std::sqrt(double(r.ref.rays.size())));
    std::size_t depth_differ = 0, compared = 0;
    std::ostringstream where;
    for (std::size_t i = 0; i < r.ref.ray_depth.size(); ++i) {
        const std::size_t x = i % n, y = i / n;
        bool clear = true;
        for (std::size_t j = y > 0 ? y - 1 : 0; j <= std::min(y + 1, n - 1); ++j)
            for (std::size_t k = x > 0 ? x - 1 : 0; k <= std::min(x + 1, n - 1); ++k) clear = clear && !r.ref.ambiguous[j * n + k];
        if (!clear) continue;
        const auto a = r.gpu.ray_depth[i], b = r.ref.ray_depth[i];
        const bool a_none = a[0] > a[1], b_none = b[0] > b[1];
        compared += !b_none;
        const float tolerance = 1e-5f * (1.0f + (b[1] - b[0]));
        if (a_none != b_none || (!a_none && (std::fabs(a[0] - b[0]) > tolerance || std::fabs(a[1] - b[1]) > tolerance))) {
            if (depth_differ < 5) where << " (" << x << "," << y << "): " << a[0] << ".." << a[1] << " vs " << b[0] << ".." << b[1];
            ++depth_differ;
        }
    }
    INFO("rays with a depth interval compared: " << compared << "; differing (GPU vs reference):" << where.str());
    CHECK(depth_differ == 0);
}

// Depth tolerance: 1e-6 for triangle ranges; depth-aware kept ranges may end at a window
// (slope times a pixel count), where the GPU's and the CPU's slopes differ in the last bits.
void requireSameRecords(const std::vector<CandidateTriangle>& a, const std::vector<CandidateTriangle>& b, float depth_tolerance = 1e-6f) {
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("record " << i);
        CHECK(a[i].object == b[i].object);
        CHECK(a[i].triangle == b[i].triangle);
        for (int c = 0; c < 3; ++c) CHECK(a[i].vertex_index[c] == b[i].vertex_index[c]);
        // Boxes and depths agree up to float rounding of the projection (FMA on the GPU).
        for (int c = 0; c < 4; ++c) CHECK(std::fabs(a[i].box[c] - b[i].box[c]) <= 1e-6f);
        CHECK(std::fabs(a[i].zmin - b[i].zmin) <= depth_tolerance);
        CHECK(std::fabs(a[i].zmax - b[i].zmax) <= depth_tolerance);
        CHECK(std::fabs(a[i].v[1].y - b[i].v[1].y) <= 1e-6f);
    }
}

void requireIdenticalRecords(const std::vector<CandidateTriangle>& a, const std::vector<CandidateTriangle>& b) {
    REQUIRE(a.size() == b.size());
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(CandidateTriangle)) == 0);
}

std::unique_ptr<BroadPhase> makeBroadPhase(test::ValidatedContext& ctx) {
    auto created = BroadPhase::create(ctx.device(), PeelingMethod::create);
    REQUIRE(created);
    return std::move(*created);
}

// Every test: a validated context and a broad phase on it.
struct BroadPhaseFixture {
    test::ValidatedContext ctx;
    std::unique_ptr<BroadPhase> owned = makeBroadPhase(ctx);
    BroadPhase& bp = *owned;
};

}  // namespace

TEST_CASE_METHOD(BroadPhaseFixture, "two overlapping boxes mark exactly the rays of their overlap footprint", "[gpu][broadphase]") {
    HostMesh a = placed(makeBox(1.0f), 0.3f, 1, 0.2f, 0.41f, {-0.45f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeBox(1.0f), 1, 0.2f, 0.5f, 0.73f, {0.55f, -0.11f, 0.09f}, "b");
    BroadPhaseSettings s;
    s.resolution = 64;
    Run r = runBoth(ctx, bp, {&a, &b}, s);
    requireSameRays(r);
    CHECK(r.gpu.collision_rays > 0);
    CHECK(r.gpu.collision_rays == r.ref.collision_rays);
    requireSameRecords(r.gpu.records, r.ref.records);
    CHECK_FALSE(r.gpu.records.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "separated meshes mark no ray and download nothing", "[gpu][broadphase]") {
    HostMesh a = placed(makeSphere(0.8f), 0.3f, 1, 0.2f, 0.41f, {-1.2f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeBox(0.6f), 1, 0.2f, 0.5f, 0.73f, {1.1f, -0.11f, 0.09f}, "b");
    for (bool dual : {false, true}) {
        BroadPhaseSettings s;
        s.resolution = 64;
        s.dual = dual;
        Run r = runBoth(ctx, bp, {&a, &b}, s);
        requireSameRays(r);
        CHECK(r.gpu.collision_rays == 0);
        CHECK(r.gpu.records.empty());
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "a mesh inside another is marked", "[gpu][broadphase]") {
    HostMesh outer = placed(makeSphere(2.0f, 24, 12), 0.3f, 1, 0.2f, 0.41f, {0.01f, 0.02f, 0.03f}, "outer");
    HostMesh inner = placed(makeBox(0.5f), 1, 0.2f, 0.5f, 0.73f, {0.1f, -0.11f, 0.09f}, "inner");
    BroadPhaseSettings s;
    s.resolution = 64;
    Run r = runBoth(ctx, bp, {&outer, &inner}, s);
    requireSameRays(r);
    CHECK(r.gpu.collision_rays > 0);
    // The inner object's triangles are all downloaded.
    std::size_t inner_records = 0;
    for (const auto& rec : r.gpu.records) inner_records += rec.object == 1;
    CHECK(inner_records == inner.triangleCount());
    requireSameRecords(r.gpu.records, r.ref.records);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "an inverted mesh is marked everywhere it covers", "[gpu][broadphase]") {
    HostMesh m = inverted(placed(makeBox(1.2f, 1), 0.3f, 1, 0.2f, 0.41f, {0.01f, 0.02f, 0.03f}, "inside-out"));
    BroadPhaseSettings s;
    s.resolution = 64;
    Run r = runBoth(ctx, bp, {&m}, s);
    requireSameRays(r);
    CHECK(r.gpu.collision_rays > 0);
    // Every triangle of a coarse inverted box covers rays, so every one survives.
    CHECK(r.gpu.records.size() == m.triangleCount());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "records equal the CPU reference: spheres and boxes, single and dual peeling", "[gpu][broadphase]") {
    HostMesh a = placed(makeSphere(1.0f, 20, 10), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeSphere(0.9f, 18, 9), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}, "b");
    HostMesh c = placed(makeBox(0.5f, 3), 0.2f, 0.4f, 1, 1.1f, {0.1f, 0.8f, -0.3f}, "c");
    for (std::uint32_t res : {64u, 128u})
        for (bool dual : {false, true}) {
            INFO("resolution " << res << (dual ? " dual" : " single"));
            BroadPhaseSettings s;
            s.resolution = res;
            s.dual = dual;
            s.direction = {0.2f, -0.3f, 1.0f};
            Run r = runBoth(ctx, bp, {&a, &b, &c}, s);
            requireSameRays(r);
            requireSameRecords(r.gpu.records, r.ref.records);
            CHECK(r.gpu.peel_steps == (dual ? (r.gpu.layers + 1) / 2 : r.gpu.layers));
        }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "a layer cap marks deeper rays as colliding", "[gpu][broadphase]") {
    // Four separated boxes in a row along the view: depth complexity 8, no collision.
    std::vector<HostMesh> boxes;
    for (int i = 0; i < 4; ++i)
        boxes.push_back(placed(makeBox(0.35f), 0.3f, 1, 0.2f, 0.1f * float(i) + 0.2f, {0.03f, 0.02f, -1.8f + 1.2f * float(i)}, "b" + std::to_string(i)));
    std::vector<const HostMesh*> ptrs;
    for (auto& b : boxes) ptrs.push_back(&b);
    BroadPhaseSettings s;
    s.resolution = 64;
    Run full = runBoth(ctx, bp, ptrs, s);
    requireSameRays(full);
    CHECK(full.gpu.depth_complexity == 8);
    CHECK(full.gpu.collision_rays == 0);
    s.layer_cap = 4;
    Run capped = runBoth(ctx, bp, ptrs, s);
    requireSameRays(capped);
    CHECK(capped.gpu.layers == 4);
    CHECK(capped.gpu.collision_rays > 0);  // rays through more than four surfaces
    requireSameRecords(capped.gpu.records, capped.ref.records);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "open surfaces collide by depth proximity", "[gpu][broadphase]") {
    auto cloth = clothGrid(3.0f, 3.0f, 12, 12);
    REQUIRE(cloth);
    HostMesh sheet = placed(*cloth, 1, 0.1f, 0.2f, 1.3f, {0.02f, 0.03f, 0.01f}, "cloth");
    HostMesh ball = placed(makeSphere(0.8f), 0.3f, 1, 0.2f, 0.41f, {0.1f, 0.05f, 0.2f}, "ball");
    BroadPhaseSettings s;
    s.resolution = 64;
    s.open_epsilon = 0.05f;
    for (bool dual : {false, true}) {
        s.dual = dual;
        Run r = runBoth(ctx, bp, {&sheet, &ball}, s, {true, false});
        requireSameRays(r);
        CHECK(r.gpu.collision_rays > 0);
        requireSameRecords(r.gpu.records, r.ref.records);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "both packing methods give identical records", "[gpu][broadphase]") {
    HostMesh a = placed(makeSphere(1.0f, 24, 12), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeBox(0.7f, 4), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}, "b");
    HostMesh far_a = placed(makeSphere(0.5f), 0, 0, 1, 0.1f, {-1.5f, 0, 0}, "far-a");
    HostMesh far_b = placed(makeSphere(0.5f), 0, 0, 1, 0.1f, {1.5f, 0, 0}, "far-b");
    HostMesh inv = inverted(placed(makeBox(1.2f, 1), 0.3f, 1, 0.2f, 0.41f, {0.01f, 0.02f, 0.03f}, "inv"));
    auto scene = [&](std::vector<const HostMesh*> meshes, PackingMethod m) {
        BroadPhaseSettings s;
        s.resolution = 128;
        s.packing = m;
        s.region = std::array<float, 6>{-2.5f, -2.5f, -2.5f, 2.5f, 2.5f, 2.5f};
        auto up = uploadMeshes(ctx.device(), meshes);
        REQUIRE(up);
        auto r = bp.run(up->meshes, s);
        REQUIRE(r);
        return std::move(*r);
    };
    SECTION("some survive") {
        auto paper = scene({&a, &b}, PackingMethod::Paper), scan = scene({&a, &b}, PackingMethod::Scan);
        CHECK_FALSE(paper.records.empty());
        requireIdenticalRecords(paper.records, scan.records);
    }
    SECTION("empty result") {
        auto paper = scene({&far_a, &far_b}, PackingMethod::Paper), scan = scene({&far_a, &far_b}, PackingMethod::Scan);
        CHECK(paper.records.empty());
        CHECK(scan.records.empty());
    }
    SECTION("every triangle survives") {
        auto paper = scene({&inv}, PackingMethod::Paper), scan = scene({&inv}, PackingMethod::Scan);
        CHECK(paper.records.size() == inv.triangleCount());
        requireIdenticalRecords(paper.records, scan.records);
    }
    SECTION("more than one packing row and block") {
        HostMesh big = placed(makeSphere(1.0f, 64, 40), 0.3f, 1, 0.2f, 0.41f, {-0.3f, 0.07f, 0.03f}, "big");
        HostMesh big2 = placed(makeSphere(1.0f, 48, 30), 1, 0.2f, 0.5f, 0.73f, {0.4f, -0.11f, 0.29f}, "big2");
        auto paper = scene({&big, &big2}, PackingMethod::Paper), scan = scene({&big, &big2}, PackingMethod::Scan);
        CHECK(paper.records.size() > 256);
        requireIdenticalRecords(paper.records, scan.records);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "16-bit indices, strided vertices and an automatic fit", "[gpu][broadphase]") {
    HostMesh a = placed(makeSphere(1.0f), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeBox(0.7f), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}, "b");
    auto plain = uploadMeshes(ctx.device(), {&a, &b});
    auto packed = uploadMeshes(ctx.device(), {&a, &b}, {.index16 = true, .vertex_stride = 28});
    REQUIRE(plain);
    REQUIRE(packed);
    BroadPhaseSettings s;
    s.resolution = 64;
    auto r1 = bp.run(plain->meshes, s);
    auto r2 = bp.run(packed->meshes, s);
    REQUIRE(r1);
    REQUIRE(r2);
    CHECK(r1->collision_rays > 0);
    requireIdenticalRecords(r1->records, r2->records);
    // The fit covers the scene: records carry boxes inside [0,1].
    for (const auto& rec : r1->records) {
        CHECK(rec.box[0] >= 0.0f);
        CHECK(rec.box[2] <= 1.0f);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "per-pass GPU times and the Table 1 counts are reported", "[gpu][broadphase]") {
    HostMesh a = placed(makeSphere(1.0f), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeBox(0.7f), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}, "b");
    BroadPhaseSettings s;
    s.resolution = 64;
    Run r = runBoth(ctx, bp, {&a, &b}, s);
    std::size_t rays = 0;
    for (auto x : r.gpu.ray_image) rays += x;
    CHECK(r.gpu.collision_rays == rays);
    CHECK(r.gpu.triangles == a.triangleCount() + b.triangleCount());
    std::vector<std::string> names;
    for (const auto& p : r.gpu.passes) names.push_back(p.name);
    for (const char* expected : {"depth-complexity", "reduce-max", "peel[0]", "classify[0]", "merge", "separate", "pack-scan"})
        CHECK(std::find(names.begin(), names.end(), expected) != names.end());
    CHECK(r.gpu.sampling_ms > 0);
    CHECK(r.gpu.packing_ms > 0);
    // Every pass declares its stage; the stage times are the sums of their passes' times.
    BroadPhaseResult summed;
    for (const auto& p : r.gpu.passes) {
        INFO(p.name << ": " << toString(static_cast<Stage>(p.stage)));
        CHECK(static_cast<Stage>(p.stage) != Stage::None);
        if (p.name == "merge") CHECK(static_cast<Stage>(p.stage) == Stage::Merging);
        if (p.name == "separate") CHECK(static_cast<Stage>(p.stage) == Stage::Separation);
        if (p.name.rfind("pack", 0) == 0) CHECK(static_cast<Stage>(p.stage) == Stage::Packing);
        if (p.name == "fit" || p.name == "clear") CHECK(static_cast<Stage>(p.stage) == Stage::Prepare);
        addStageTime(summed, p);
    }
    CHECK(summed.sampling_ms == Approx(r.gpu.sampling_ms));
    CHECK(summed.merging_ms == Approx(r.gpu.merging_ms));
    CHECK(summed.separation_ms == Approx(r.gpu.separation_ms));
    CHECK(summed.packing_ms == Approx(r.gpu.packing_ms));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "per-object transforms are applied on the GPU", "[gpu][broadphase]") {
    HostMesh a = makeSphere(1.0f);
    HostMesh b = makeBox(0.7f);
    const Transform3x4 ta = {1, 0, 0, -0.5f, 0, 0, -1, 0.07f, 0, 1, 0, 0.03f};  // rotation about x + move
    const Transform3x4 tb = {0, -1, 0, 0.6f, 1, 0, 0, -0.11f, 0, 0, 1, 0.29f};   // rotation about z + move
    HostMesh a_world = a, b_world = b;
    REQUIRE(transformMesh(a_world, ta));
    REQUIRE(transformMesh(b_world, tb));
    auto local = uploadMeshes(ctx.device(), {&a, &b});
    auto world = uploadMeshes(ctx.device(), {&a_world, &b_world});
    REQUIRE(local);
    REQUIRE(world);
    std::copy(ta.begin(), ta.end(), local->meshes[0].transform.begin());
    std::copy(tb.begin(), tb.end(), local->meshes[1].transform.begin());
    BroadPhaseSettings s;
    s.resolution = 64;
    auto r1 = bp.run(local->meshes, s);
    auto r2 = bp.run(world->meshes, s);
    REQUIRE(r1);
    REQUIRE(r2);
    CHECK(r1->collision_rays > 0);
    CHECK(r1->collision_rays == r2->collision_rays);
    requireSameRecords(r1->records, r2->records);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// ---- Depth-aware separation --------------------------------------------------------------

namespace {

// Pairs the narrow phase finds among `records` (every object self-colliding).
std::vector<TrianglePair> pairsOf(const std::vector<CandidateTriangle>& records) {
    ThreadPool pool(2);
    auto r = runNarrowPhase(records, {}, pool);
    REQUIRE(r);
    return r->pairs;
}

// Every pair of the scene: all triangles as candidates with their world boxes (the
// narrow phase only compares boxes with each other, so any common space works).
std::vector<TrianglePair> exactPairs(const std::vector<const HostMesh*>& meshes) {
    std::vector<CandidateTriangle> all;
    for (std::uint32_t o = 0; o < meshes.size(); ++o)
        for (std::uint32_t t = 0; t < meshes[o]->triangleCount(); ++t) {
            CandidateTriangle c{};
            c.object = o;
            c.triangle = t;
            c.box[0] = c.box[1] = c.zmin = 3e38f;
            c.box[2] = c.box[3] = c.zmax = -3e38f;
            for (int k = 0; k < 3; ++k) {
                c.vertex_index[k] = meshes[o]->indices[t * 3 + k];
                const Float3 p = meshes[o]->positions[c.vertex_index[k]];
                c.v[k] = p;
                c.box[0] = std::min(c.box[0], p.x), c.box[1] = std::min(c.box[1], p.y), c.zmin = std::min(c.zmin, p.z);
                c.box[2] = std::max(c.box[2], p.x), c.box[3] = std::max(c.box[3], p.y), c.zmax = std::max(c.zmax, p.z);
            }
            all.push_back(c);
        }
    return pairsOf(all);
}

// How many of `expected` are not in `found` (both sorted).
std::size_t missing(const std::vector<TrianglePair>& found, const std::vector<TrianglePair>& expected) {
    std::vector<TrianglePair> missed;
    std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(), std::back_inserter(missed));
    return missed.size();
}

}  // namespace

TEST_CASE_METHOD(BroadPhaseFixture, "depth-aware records and ray intervals equal the CPU reference: spheres and boxes, single and dual", "[gpu][broadphase][depth]") {
    HostMesh a = placed(makeSphere(1.0f, 20, 10), 0.3f, 1, 0.2f, 0.41f, {-0.5f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeSphere(0.9f, 18, 9), 1, 0.2f, 0.5f, 0.73f, {0.6f, -0.11f, 0.29f}, "b");
    HostMesh c = placed(makeBox(0.5f, 3), 0.2f, 0.4f, 1, 1.1f, {0.1f, 0.8f, -0.3f}, "c");
    for (std::uint32_t res : {64u, 128u})
        for (bool dual : {false, true}) {
            INFO("resolution " << res << (dual ? " dual" : " single"));
            BroadPhaseSettings s;
            s.resolution = res;
            s.dual = dual;
            s.direction = {0.2f, -0.3f, 1.0f};
            s.depth_aware = true;
            Run r = runBoth(ctx, bp, {&a, &b, &c}, s);
            requireSameRays(r);
            CHECK(r.gpu.collision_rays > 0);
            CHECK_FALSE(r.gpu.records.empty());
            requireSameRecords(r.gpu.records, r.ref.records, 1e-5f);
            // The same collision rays as the paper's separation (Table 1's column keeps its
            // meaning); how many triangles each keeps is the deep-overlap test's business.
            s.depth_aware = false;
            Run paper = runBoth(ctx, bp, {&a, &b, &c}, s);
            CHECK(paper.gpu.collision_rays == r.gpu.collision_rays);
            CHECK(paper.gpu.ray_image == r.gpu.ray_image);
        }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "depth-aware: rays beyond the layer cap keep every depth, open surfaces use their near pairs", "[gpu][broadphase][depth]") {
    std::vector<HostMesh> boxes;
    for (int i = 0; i < 4; ++i)
        boxes.push_back(placed(makeBox(0.35f), 0.3f, 1, 0.2f, 0.1f * float(i) + 0.2f, {0.03f, 0.02f, -1.8f + 1.2f * float(i)}, "b" + std::to_string(i)));
    std::vector<const HostMesh*> ptrs;
    for (auto& b : boxes) ptrs.push_back(&b);
    BroadPhaseSettings s;
    s.resolution = 64;
    s.depth_aware = true;
    s.layer_cap = 4;
    Run capped = runBoth(ctx, bp, ptrs, s);
    requireSameRays(capped);
    REQUIRE(capped.gpu.collision_rays > 0);
    std::size_t every_depth = 0;
    for (std::size_t i = 0; i < capped.gpu.ray_image.size(); ++i)
        if (capped.gpu.ray_image[i]) {
            // No collision but the cap's: no fragment information, every depth.
            CHECK(capped.gpu.ray_depth[i][0] <= -3e38f);
            CHECK(capped.gpu.ray_depth[i][1] >= 3e38f);
            ++every_depth;
        }
    CHECK(every_depth == capped.gpu.collision_rays);
    requireSameRecords(capped.gpu.records, capped.ref.records, 1e-5f);

    auto cloth = clothGrid(3.0f, 3.0f, 12, 12);
    REQUIRE(cloth);
    HostMesh sheet = placed(*cloth, 1, 0.1f, 0.2f, 1.3f, {0.02f, 0.03f, 0.01f}, "cloth");
    HostMesh ball = placed(makeSphere(0.8f), 0.3f, 1, 0.2f, 0.41f, {0.1f, 0.05f, 0.2f}, "ball");
    s = {};
    s.resolution = 64;
    s.open_epsilon = 0.05f;
    s.depth_aware = true;
    for (bool dual : {false, true}) {
        s.dual = dual;
        Run r = runBoth(ctx, bp, {&sheet, &ball}, s, {true, false});
        requireSameRays(r);
        CHECK_FALSE(r.gpu.records.empty());
        requireSameRecords(r.gpu.records, r.ref.records, 1e-5f);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "depth-aware: an object's own triangles are near pairs only when it self-collides", "[gpu][broadphase][depth]") {
    auto tube = twistedTube(1.0f, 0.2f, 96, 12, 1.5f);
    REQUIRE(tube);
    HostMesh t = placed(*tube, 0.2f, 0.3f, 1, 0.2f, {0.02f, 0.03f, 0.01f}, "tube");
    BroadPhaseSettings s;
    s.resolution = 128;
    s.depth_aware = true;
    Run off = runBoth(ctx, bp, {&t}, s, {}, {false});
    requireSameRays(off);
    CHECK(off.gpu.collision_rays > 0);  // the paper's rules see the self-intersection
    CHECK(off.gpu.records.empty());     // but no pair of the object may collide
    Run on = runBoth(ctx, bp, {&t}, s, {}, {true});
    requireSameRays(on);
    requireSameRecords(on.gpu.records, on.ref.records, 1e-5f);
    const auto expected = exactPairs({&t});
    REQUIRE_FALSE(expected.empty());
    const auto found = pairsOf(on.gpu.records);
    CHECK(missing(found, expected) == 0);
    CHECK(found.size() == expected.size());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "depth-aware: a deep overlap downloads a fraction of the paper's triangles and loses no pair it finds", "[gpu][broadphase][depth]") {
    // Two fine spheres, centres 0.6 radius apart: every ray through the shared volume is a
    // collision ray, so the paper keeps both spheres' triangles there.
    HostMesh a = placed(makeSphere(1.0f, 96, 48), 0.3f, 1, 0.2f, 0.41f, {-0.3f, 0.02f, 0.03f}, "a");
    HostMesh b = placed(makeSphere(1.0f, 96, 48), 1, 0.2f, 0.5f, 0.73f, {0.3f, -0.04f, 0.05f}, "b");
    BroadPhaseSettings s;
    s.resolution = 256;
    s.direction = {0.31f, -0.07f, 1.0f};
    Run paper = runBoth(ctx, bp, {&a, &b}, s);
    s.depth_aware = true;
    Run depth = runBoth(ctx, bp, {&a, &b}, s);
    requireSameRays(depth);
    requireSameRecords(depth.gpu.records, depth.ref.records, 1e-5f);
    INFO("paper " << paper.gpu.records.size() << ", depth-aware " << depth.gpu.records.size());
    CHECK(depth.gpu.records.size() * 3 < paper.gpu.records.size());
    const auto expected = exactPairs({&a, &b});
    const auto found = pairsOf(depth.gpu.records), found_paper = pairsOf(paper.gpu.records);
    INFO("pairs " << expected.size() << ", found " << found.size() << ", by the paper's separation " << found_paper.size());
    CHECK(missing(found, found_paper) == 0);
    CHECK(missing(found, expected) * 50 <= expected.size());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE_METHOD(BroadPhaseFixture, "depth-aware: a box sunk into another, its sides seen edge-on, keeps every crossing pair", "[gpu][broadphase][depth]") {
    // Axis-aligned boxes seen along z: the small box's sides have no area in the image, so no
    // ray samples them, yet they are what crosses the big box's top face. Their depth
    // ranges reach the windows of the faces that share their vertices (edge-on neighbours).
    auto big = box({0.8f, 0.8f, 0.5f}, 2);
    auto small = box({0.2f, 0.2f, 0.2f}, 1);
    REQUIRE(big);
    REQUIRE(small);
    // Turned about z (sides stay parallel to the view), so no edge runs through pixel centres.
    HostMesh a = placed(*big, 0, 0, 1, 0.31f, {0.01f, 0.02f, 0}, "big");
    HostMesh b = placed(*small, 0, 0, 1, 0.53f, {0.13f, -0.07f, 0.61f}, "sunk");  // 0.09 below the top
    BroadPhaseSettings s;
    s.resolution = 64;
    s.direction = {0, 0, 1};
    Run paper = runBoth(ctx, bp, {&a, &b}, s);
    s.depth_aware = true;
    Run depth = runBoth(ctx, bp, {&a, &b}, s);
    requireSameRays(depth);
    requireSameRecords(depth.gpu.records, depth.ref.records, 1e-5f);
    const auto expected = exactPairs({&a, &b});
    const auto found = pairsOf(depth.gpu.records);
    INFO("pairs " << expected.size() << ", found " << found.size() << ", by the paper's separation " << pairsOf(paper.gpu.records).size());
    REQUIRE_FALSE(expected.empty());
    CHECK(missing(found, expected) == 0);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The peeling steps in chunks (BroadPhaseSettings::peel_chunk): each chunk is a submission
// of the broad phase's Again, so that the GPU work a timeout leaves running is at most one
// chunk. The per-ray state crosses submissions in the table's buffers: the records, rays
// and depth intervals must be those of one submission, bit for bit, whatever the chunk,
// on both backends, single and dual, depth-aware or not, measured (run) or predicted
// (submit).
TEST_CASE_METHOD(BroadPhaseFixture, "peeling in chunks of steps gives the records, rays and depth intervals of one submission", "[gpu][broadphase]") {
    // Nested and crossing closed meshes: 3 or more peeling steps along the direction.
    HostMesh a = placed(makeSphere(1.0f, 20, 10), 0.3f, 1, 0.2f, 0.41f, {-0.3f, 0.07f, 0.03f}, "a");
    HostMesh b = placed(makeSphere(0.6f, 18, 9), 1, 0.2f, 0.5f, 0.73f, {-0.2f, -0.11f, 0.09f}, "b");
    HostMesh c = placed(makeBox(0.5f, 3), 0.2f, 0.4f, 1, 1.1f, {0.3f, 0.2f, -0.3f}, "c");
    HostMesh d = placed(inverted(makeSphere(0.3f)), 0.5f, 0.1f, 1, 0.3f, {0.9f, 0.5f, 0.2f}, "d");
    auto scene = uploadMeshes(ctx.device(), {&a, &b, &c, &d});
    REQUIRE(scene);
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute})
        for (bool dual : {false, true})
            for (bool depth_aware : {false, true}) {
                INFO(toString(backend) << (dual ? " dual" : " single") << (depth_aware ? " depth-aware" : ""));
                BroadPhaseSettings s;
                s.resolution = 64;
                s.dual = dual;
                s.depth_aware = depth_aware;
                s.backend = backend;
                s.keep_ray_image = true;
                s.direction = {0.2f, -0.3f, 1.0f};
                s.peel_chunk = 1u << 20;  // every step in one submission
                auto whole = bp.run(scene->meshes, s);
                INFO((whole ? std::string() : whole.error().message()));
                REQUIRE(whole);
                REQUIRE(whole->peel_steps >= 3);
                CHECK(whole->peel_submissions == 1);
                CHECK_FALSE(whole->records.empty());
                for (std::uint32_t chunk : {1u, 2u}) {
                    INFO(chunk << " steps per submission");
                    s.peel_chunk = chunk;
                    for (bool predicted : {false, true}) {
                        INFO((predicted ? "submit() with the depth predicted" : "run()"));
                        auto r = [&]() -> Result<BroadPhaseResult> {
                            if (!predicted) return bp.run(scene->meshes, s);
                            if (auto ok = bp.submit(scene->meshes, s, whole->layers); !ok) return ok.error();
                            return bp.collect();
                        }();
                        INFO((r ? std::string() : r.error().message()));
                        REQUIRE(r);
                        CHECK(r->peel_steps == whole->peel_steps);
                        CHECK(r->peel_submissions == (whole->peel_steps + chunk - 1) / chunk);
                        CHECK(r->collision_rays == whole->collision_rays);
                        CHECK(r->ray_image == whole->ray_image);
                        CHECK(r->ray_depth == whole->ray_depth);
                        requireIdenticalRecords(r->records, whole->records);
                        // Every step's passes ran once, in order, across the submissions.
                        std::vector<std::string> classify;
                        for (const auto& p : r->passes)
                            if (p.name.rfind("classify[", 0) == 0) classify.push_back(p.name);
                        REQUIRE(classify.size() == r->peel_steps);
                        for (std::uint32_t i = 0; i < r->peel_steps; ++i) CHECK(classify[i] == "classify[" + std::to_string(i) + "]");
                    }
                }
            }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
