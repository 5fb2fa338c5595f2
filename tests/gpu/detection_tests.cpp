// passes::Detection without CollisionWorld: one or three directions, measured or predicted,
// engine meshes that fail the GPU check left out (or failing the detection), with the
// findings as data, and a follow-up stage (the contact stage) after it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "broad/projection.hpp"
#include "contacts/contact_stage.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "detect/detection.hpp"
#include "mesh/mesh_upload.hpp"
#include "support/gpu_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

HostMesh moved(Result<HostMesh> made, Float3 t, const char* name) {
    REQUIRE(made);
    HostMesh m = std::move(*made);
    REQUIRE(transformMesh(m, Transform3x4{1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}));
    m.name = name;
    return m;
}

// Three spheres in a row, each overlapping the next.
struct Row {
    std::vector<HostMesh> meshes;
    UploadedMeshes up;
};

Row makeRow(vk::Device& dev) {
    Row row;
    row.meshes.push_back(moved(uvSphere(1.0f, 20, 10), {-1.5f, 0.05f, 0.02f}, "a"));
    row.meshes.push_back(moved(uvSphere(1.0f, 20, 10), {0.0f, 0.0f, 0.0f}, "b"));
    row.meshes.push_back(moved(uvSphere(1.0f, 20, 10), {1.5f, -0.05f, 0.03f}, "c"));
    auto up = uploadMeshes(dev, {&row.meshes[0], &row.meshes[1], &row.meshes[2]});
    REQUIRE(up);
    row.up = std::move(*up);
    for (GpuMesh& m : row.up.meshes) m.check_on_gpu = true;  // as engine meshes are
    return row;
}

// The paper's method: its records are what these tests compare.
DetectionSettings settings(std::uint32_t axes) {
    DetectionSettings s;
    s.method = PeelingMethod::create;
    s.broad.resolution = 64;
    s.broad.direction = {0.15f, -0.2f, 1.0f};
    s.axes = axes;
    return s;
}

std::vector<TrianglePair> narrowPairs(const DetectionResult& r) {
    ThreadPool pool(1);
    auto n = runNarrowPhase(r.candidates(), {}, pool);
    REQUIRE(n);
    std::vector<TrianglePair> pairs = std::move(n->pairs);
    for (TrianglePair& p : pairs) p.object_a = r.objects[p.object_a], p.object_b = r.objects[p.object_b];
    return pairs;
}

// The paper's method, counting how often a broad phase is made with it.
int peeling_made = 0;
Result<std::unique_ptr<BroadPhaseMethod>> countingPeeling(vk::Device& device, BufferTable& table, const CoreBuffers& core) {
    ++peeling_made;
    return PeelingMethod::create(device, table, core);
}

}  // namespace

TEST_CASE("a detection runs the method it is given on every direction", "[gpu][detection]") {
    test::ValidatedContext ctx;
    Row row = makeRow(ctx.device());
    auto det = Detection::create(ctx.device(), PeelingMethod::create);
    REQUIRE(det);
    REQUIRE((*det)->start(row.up.meshes, settings(1), true));
    auto plain = (*det)->collect();
    REQUIRE(plain);
    DetectionSettings s = settings(3);
    s.method = countingPeeling;
    peeling_made = 0;
    REQUIRE((*det)->start(row.up.meshes, s, true));
    auto counted = (*det)->collect();
    REQUIRE(counted);
    CHECK(peeling_made == 3);  // one broad phase per direction, made anew for the new method
    REQUIRE((*det)->start(row.up.meshes, s, false));
    REQUIRE((*det)->collect());
    CHECK(peeling_made == 3);  // and kept while the method stays
    CHECK(counted->axes[0].records.size() == plain->axes[0].records.size());
    // No default method: none given is refused by name.
    auto none = Detection::create(ctx.device(), nullptr);
    REQUIRE_FALSE(none);
    CHECK(none.error().code() == ErrorCode::InvalidArgument);
    DetectionSettings unnamed = settings(1);
    unnamed.method = nullptr;
    auto refused = (*det)->start(row.up.meshes, unnamed, true);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().message().find("DetectionSettings::method") != std::string::npos);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a detection runs one or three directions without a world", "[gpu][detection]") {
    test::ValidatedContext ctx;
    Row row = makeRow(ctx.device());
    auto det = Detection::create(ctx.device(), PeelingMethod::create);
    REQUIRE(det);
    Detection& d = **det;

    REQUIRE(d.start(row.up.meshes, settings(1), true));
    CHECK(d.pending());
    auto one = d.collect();
    REQUIRE(one);
    CHECK_FALSE(d.pending());
    REQUIRE(one->axes.size() == 1);
    CHECK(one->objects == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(one->excluded.empty());
    CHECK(one->candidates().size() == one->axes[0].records.size());
    const std::vector<TrianglePair> pairs_one = narrowPairs(*one);
    REQUIRE_FALSE(pairs_one.empty());

    // Predicted depth (one submission each): the same candidates as measured.
    REQUIRE(d.start(row.up.meshes, settings(1), false));
    auto predicted = d.collect();
    REQUIRE(predicted);
    CHECK(predicted->axes[0].depth_complexity == one->axes[0].depth_complexity);
    CHECK(narrowPairs(*predicted) == pairs_one);

    // Three directions: the first one's and its image axes; the union keeps every pair.
    REQUIRE(d.start(row.up.meshes, settings(3), true));
    auto three = d.collect();
    REQUIRE(three);
    REQUIRE(three->axes.size() == 3);
    const ProjectionBasis basis = projectionBasis(settings(1).broad.direction);
    CHECK(three->directions[1] == basis.u);
    CHECK(three->directions[2] == basis.v);
    CHECK(three->candidates().size() == three->united.size());
    const std::vector<TrianglePair> pairs_three = narrowPairs(*three);
    CHECK(std::includes(pairs_three.begin(), pairs_three.end(), pairs_one.begin(), pairs_one.end()));
    CHECK(d.memoryBytes() > 0);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a detection leaves out a mesh the GPU check refuses, or fails with the finding", "[gpu][detection]") {
    test::ValidatedContext ctx;
    Row row = makeRow(ctx.device());
    auto det = Detection::create(ctx.device(), PeelingMethod::create);
    REQUIRE(det);
    Detection& d = **det;
    REQUIRE(d.start(row.up.meshes, settings(1), true));
    auto clean = d.collect();
    REQUIRE(clean);

    // Object 1 ("b"): a NaN position; the others keep the pairs they have without it.
    auto* positions = static_cast<float*>(row.up.buffers[2].mapped());
    const std::uint32_t vertex = row.meshes[1].indices[3 * 5];
    positions[vertex * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
    row.up.buffers[2].flush();
    for (bool measure : {true, false}) {
        INFO("measured first: " << measure);
        REQUIRE(d.start(row.up.meshes, settings(1), measure));
        auto r = d.collect();
        REQUIRE(r);
        REQUIRE(r->excluded.size() == 1);
        CHECK(r->excluded[0].object == 1);
        CHECK(r->excluded[0].kind == ObjectFault::Kind::NonFinitePosition);
        CHECK(r->excluded[0].triangles_affected >= 1);
        CHECK(r->objects == std::vector<std::uint32_t>{0, 2});
        std::vector<TrianglePair> expected;
        for (const TrianglePair& p : narrowPairs(*clean))
            if (p.object_a != 1 && p.object_b != 1) expected.push_back(p);
        CHECK(narrowPairs(*r) == expected);
    }

    // BadObjectPolicy::Fail: the error, and the finding as data.
    DetectionSettings strict = settings(1);
    strict.bad_objects = BadObjectPolicy::Fail;
    auto failed = d.start(row.up.meshes, strict, true);
    REQUIRE_FALSE(failed);
    CHECK(failed.error().code() == ErrorCode::InvalidMesh);
    REQUIRE(d.failure().faults.size() == 1);
    CHECK(d.failure().faults[0].object == 1);
    CHECK_FALSE(d.failure().none_left);
    CHECK_FALSE(d.pending());

    // Only the bad mesh: nothing left to test.
    auto alone = d.start(std::span<const GpuMesh>(&row.up.meshes[1], 1), settings(1), true);
    REQUIRE_FALSE(alone);
    CHECK(d.failure().none_left);
    REQUIRE(d.failure().faults.size() == 1);
    CHECK(d.failure().faults[0].object == 0);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The contact stage is a follow-up of the first direction's broad phase: made once, its
// buffers rows of that broad phase's table (counted in memoryBytes), its submissions on
// that executor within the detection's deadline, and only after collect().
TEST_CASE("a follow-up stage runs on the detection's executor and table, within its deadline", "[gpu][detection]") {
    test::ValidatedContext ctx;
    Row row = makeRow(ctx.device());
    auto det = Detection::create(ctx.device(), PeelingMethod::create);
    REQUIRE(det);
    Detection& d = **det;
    REQUIRE(d.start(row.up.meshes, settings(1), true));
    auto made_early = d.followUp(ContactStage::create);
    REQUIRE(made_early);
    auto* contacts = static_cast<ContactStage*>(*made_early);
    contacts->setInput({.direction = {0.15f, -0.2f, 1.0f}, .resolution = 64});
    auto early = d.runFollowUp(*contacts);  // the detection is still in flight
    REQUIRE_FALSE(early);
    CHECK(early.error().code() == ErrorCode::InvalidArgument);
    REQUIRE(d.collect());

    const std::uint64_t before = d.memoryBytes();
    REQUIRE(d.runFollowUp(*contacts));
    const ContactStageResult& r = contacts->result();
    // a-b and b-c overlap (centres 1.5 apart, radius 1); a and c do not.
    REQUIRE(r.contacts.size() == 2);
    CHECK((r.contacts[0].a == 0 && r.contacts[0].b == 1));
    CHECK((r.contacts[1].a == 1 && r.contacts[1].b == 2));
    for (const StageContact& c : r.contacts) CHECK(c.volume > 0);
    CHECK(r.runs == 1);
    CHECK(d.memoryBytes() > before);  // its rows are the broad phase's
    auto again = d.followUp(ContactStage::create);
    REQUIRE(again);
    CHECK(*again == *made_early);

    // A deadline that has passed: nothing is submitted, the error is the detection's timeout
    // and names the stage it ran out at.
    d.setDeadline(std::chrono::steady_clock::now() - std::chrono::milliseconds(1));
    auto late = d.runFollowUp(*contacts);
    REQUIRE_FALSE(late);
    CHECK(late.error().code() == ErrorCode::Timeout);
    CHECK(late.error().message().find("timeout_ms") != std::string::npos);
    CHECK(late.error().message().find("it ran out at the contact stage") != std::string::npos);
    CHECK_FALSE(d.busy());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
