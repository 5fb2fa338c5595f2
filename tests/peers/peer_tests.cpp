// The peers (tools/bench/peers) against the exact reference on small generated scenes.
// CGAL and Embree feed our exact test, so they must find exactly the reference pairs.
// FCL decides with its own floating-point triangle test and finds no pairs within one
// object: its pairs between objects are measured against the reference with
// self-collision off, and guarded at what was measured (docs/peers.md).
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "narrow/printers.hpp"
#include "peers.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {

HostMesh moved(Result<HostMesh> mesh, float dx, float dy, float dz) {
    REQUIRE(mesh);
    HostMesh m = std::move(*mesh);
    REQUIRE(transformMesh(m, Transform3x4{1, 0, 0, dx, 0, 1, 0, dy, 0, 0, 1, dz}));
    return m;
}

struct Scene {
    std::string name;
    std::vector<HostMesh> meshes;
};

// Two spheres that overlap in a lens.
Scene twoSpheres() {
    return {"two spheres", {moved(uvSphere(1.0f, 32, 16), 0, 0, 0), moved(uvSphere(0.8f, 24, 12), 1.3f, 0.21f, 0.13f)}};
}

// A torus whose tube passes through a box's side walls.
Scene torusThroughBox() {
    return {"torus through box",
            {moved(torus(1.0f, 0.25f, 48, 16), 0, 0, 0), moved(box({0.35f, 0.3f, 0.5f}, 3), 1.0f, 0, 0)}};
}

// One tube crossing itself near the origin: pairs within one object only.
Scene selfCrossingTube() {
    Result<HostMesh> tube = twistedTube(1.0f, 0.2f, 96, 12, 1.0f);
    REQUIRE(tube);
    return {"twisted tube", {std::move(*tube)}};
}

// Boxes whose faces lie in one plane (x = 0.5) and share edges: contacts that only touch.
// All coordinates are small dyadic fractions, exact in float.
Scene touchingBoxes() {
    return {"touching boxes",
            {moved(box({0.5f, 0.5f, 0.5f}, 2), 0, 0, 0), moved(box({0.5f, 0.25f, 0.25f}, 2), 1.0f, 0.25f, 0),
             moved(box({0.25f, 0.25f, 0.25f}, 1), 0, 0.75f, 0.25f)}};
}

std::vector<Scene> allScenes() { return {twoSpheres(), torusThroughBox(), selfCrossingTube(), touchingBoxes()}; }

std::vector<TrianglePair> reference(const std::vector<HostMesh>& meshes, bool self_collision) {
    std::vector<test::ReferenceObject> objects;
    for (const HostMesh& m : meshes) objects.push_back({&m, test::kIdentityTransform, self_collision});
    Result<std::vector<TrianglePair>> pairs = test::computeReferencePairs(objects);
    REQUIRE(pairs);
    return *pairs;
}

using PeerFactory = std::function<Result<std::unique_ptr<Peer>>(const PeerMode&)>;

struct NamedFactory {
    const char* name;
    PeerFactory create;
};

std::vector<NamedFactory> exactPeers() {
    return {
        {"cgal",
         [](const PeerMode& m) {
             return createCgalPeer({CgalTest::Exact, true}, m, 2);
         }},
        {"cgal-seqbox",
         [](const PeerMode& m) {
             return createCgalPeer({CgalTest::Exact, false}, m, 2);
         }},
        {"cgal-epick",
         [](const PeerMode& m) {
             return createCgalPeer({CgalTest::Epick, true}, m, 2);
         }},
        {"embree", [](const PeerMode& m) { return createEmbreePeer(EmbreeUpdate::Rebuild, m, 2); }},
        {"embree-refit", [](const PeerMode& m) { return createEmbreePeer(EmbreeUpdate::Refit, m, 2); }},
    };
}

// Moves every vertex by a smooth, frame-dependent displacement (a deforming frame).
std::vector<HostMesh> deformed(const std::vector<HostMesh>& meshes, int frame) {
    std::vector<HostMesh> out = meshes;
    const float t = 0.35f * static_cast<float>(frame);
    for (std::size_t o = 0; o < out.size(); ++o) {
        for (Float3& p : out[o].positions) {
            const float s = 0.06f * std::sin(3.0f * p.y + t + static_cast<float>(o));
            p = {p.x + s - 0.04f * static_cast<float>(frame) * (o == 0 ? -1.0f : 1.0f), p.y + 0.5f * s, p.z - s};
        }
    }
    return out;
}

}  // namespace

TEST_CASE("Peers: CGAL and Embree find exactly the reference pairs", "[peers]") {
    for (const Scene& scene : allScenes()) {
        for (const bool self : {true, false}) {
            const std::vector<TrianglePair> expected = reference(scene.meshes, self);
            for (const NamedFactory& factory : exactPeers()) {
                INFO(scene.name << ", " << factory.name << ", self-collision " << self);
                auto peer = factory.create({self, Motion::Rigid});
                REQUIRE(peer);
                Result<PeerFrame> frame = (*peer)->frame(scene.meshes);
                REQUIRE(frame);
                CHECK(frame->pairs == expected);
                CHECK(frame->timings.total_ms == frame->timings.build_ms + frame->timings.query_ms);
                CHECK(frame->timings.candidates >= expected.size());
            }
        }
    }
}

TEST_CASE("Peers: the test scenes have the contacts they are meant to have", "[peers]") {
    CHECK(reference(twoSpheres().meshes, false).size() > 50);
    CHECK(reference(torusThroughBox().meshes, false).size() > 50);
    const Scene tube = selfCrossingTube();
    CHECK(reference(tube.meshes, false).empty());
    CHECK(reference(tube.meshes, true).size() > 20);
    CHECK(reference(touchingBoxes().meshes, false).size() > 10);
}

TEST_CASE("Peers: deforming frames refit or rebuild and stay exact", "[peers]") {
    const Scene scene = twoSpheres();
    for (const NamedFactory& factory : exactPeers()) {
        INFO(factory.name);
        auto peer = factory.create({true, Motion::Deforming});
        REQUIRE(peer);
        for (int f = 0; f < 4; ++f) {
            INFO("frame " << f);
            const std::vector<HostMesh> meshes = deformed(scene.meshes, f);
            Result<PeerFrame> frame = (*peer)->frame(meshes);
            REQUIRE(frame);
            CHECK(frame->pairs == reference(meshes, true));
        }
    }
}

TEST_CASE("Peers: FCL's pairs between objects, measured against the reference", "[peers][fcl]") {
    struct Guard {
        const char* scene;
        double min_recall, min_precision;
    };
    // Measured with Debian's libfcl 0.7.0 (docs/peers.md); a drop means FCL or our use of it changed.
    const std::vector<Guard> guards = {{"two spheres", 1.0, 1.0},
                                       {"torus through box", 1.0, 1.0},
                                       {"twisted tube", 1.0, 1.0},
                                       {"touching boxes", 1.0, 1.0}};
    std::vector<Scene> scenes = allScenes();
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const Scene& scene = scenes[s];
        const std::vector<TrianglePair> expected = reference(scene.meshes, false);
        for (const FclVolume volume : {FclVolume::Aabb, FclVolume::Obbrss}) {
            for (const Motion motion : {Motion::Rigid, Motion::Deforming}) {
                auto peer = createFclPeer(volume, {false, motion}, 2);
                REQUIRE(peer);
                INFO(scene.name << ", " << (*peer)->name() << (motion == Motion::Rigid ? " rigid" : " deforming"));
                for (int f = 0; f < (motion == Motion::Rigid ? 1 : 3); ++f) {
                    const std::vector<HostMesh> meshes =
                        motion == Motion::Rigid ? scene.meshes : deformed(scene.meshes, f);
                    const std::vector<TrianglePair> truth =
                        motion == Motion::Rigid ? expected : reference(meshes, false);
                    Result<PeerFrame> frame = (*peer)->frame(meshes);
                    REQUIRE(frame);
                    const test::PairComparison c = test::comparePairs(frame->pairs, truth);
                    UNSCOPED_INFO("frame " << f << ": reference " << truth.size() << ", found " << frame->pairs.size()
                                           << ", recall " << c.recall << ", precision " << c.precision);
                    CHECK(c.recall >= guards[s].min_recall);
                    CHECK(c.precision >= guards[s].min_precision);
                }
            }
        }
    }
}

TEST_CASE("Peers: touching triangle pairs, worked by hand", "[peers]") {
    const auto triangle = [](Float3 a, Float3 b, Float3 c) {
        HostMesh m;
        m.name = "triangle";
        m.positions = {a, b, c};
        m.indices = {0, 1, 2};
        return m;
    };
    const HostMesh floor = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    const float above = std::nextafter(0.0f, 1.0f);
    struct Case {
        const char* what;
        HostMesh other;
        bool touches;
    };
    const std::vector<Case> cases = {
        {"a vertex on the face", triangle({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {1, 1, 1}), true},
        {"a vertex one float above the face", triangle({0.25f, 0.25f, above}, {0.25f, 0.25f, 1}, {1, 1, 1}), false},
        {"an edge crossing an edge at one point", triangle({0.5f, 0, -1}, {0.5f, 0, 1}, {0.5f, -1, 0}), true},
        {"coplanar, sharing the long edge", triangle({1, 0, 0}, {1, 1, 0}, {0, 1, 0}), true},
        {"coplanar, overlapping", triangle({0.25f, 0.25f, 0}, {1, 0.25f, 0}, {0.25f, 1, 0}), true},
        {"coplanar, apart", triangle({0.75f, 0.75f, 0}, {1, 0.75f, 0}, {0.75f, 1, 0}), false},
        {"one shared corner", triangle({1, 0, 0}, {2, 0, 1}, {2, 1, 0}), true},
    };
    for (const Case& c : cases) {
        const std::vector<HostMesh> meshes = {floor, c.other};
        const std::vector<TrianglePair> expected =
            c.touches ? std::vector<TrianglePair>{{0, 0, 1, 0}} : std::vector<TrianglePair>{};
        INFO(c.what);
        REQUIRE(reference(meshes, true) == expected);
        for (const NamedFactory& factory : exactPeers()) {
            INFO(factory.name);
            auto peer = factory.create({true, Motion::Rigid});
            REQUIRE(peer);
            Result<PeerFrame> frame = (*peer)->frame(meshes);
            REQUIRE(frame);
            CHECK(frame->pairs == expected);
        }
        for (const FclVolume volume : {FclVolume::Aabb, FclVolume::Obbrss}) {
            auto peer = createFclPeer(volume, {false, Motion::Rigid}, 1);
            REQUIRE(peer);
            INFO((*peer)->name());
            Result<PeerFrame> frame = (*peer)->frame(meshes);
            REQUIRE(frame);
            CHECK(frame->pairs == expected);
        }
    }
}

TEST_CASE("Peers: FCL refuses self-collision", "[peers][fcl]") {
    for (const FclVolume volume : {FclVolume::Aabb, FclVolume::Obbrss}) {
        auto peer = createFclPeer(volume, {true, Motion::Rigid});
        REQUIRE_FALSE(peer);
        CHECK(peer.error().code() == ErrorCode::InvalidArgument);
        CHECK(peer.error().message().find("fcl#333") != std::string::npos);
    }
}

TEST_CASE("Peers: a deforming frame must keep the topology", "[peers]") {
    const Scene scene = twoSpheres();
    std::vector<HostMesh> changed = scene.meshes;
    changed[1].indices.resize(changed[1].indices.size() - 3);
    const std::vector<std::vector<HostMesh>> bad_frames = {changed, {scene.meshes[0]}};
    auto cgal = createCgalPeer({}, {true, Motion::Deforming}, 2);
    auto embree = createEmbreePeer(EmbreeUpdate::Refit, {true, Motion::Deforming}, 2);
    auto fcl = createFclPeer(FclVolume::Aabb, {false, Motion::Deforming}, 2);
    for (Peer* peer : {cgal->get(), embree->get(), fcl->get()}) {
        INFO(peer->name());
        REQUIRE(peer->frame(scene.meshes));
        for (const std::vector<HostMesh>& bad : bad_frames) {
            Result<PeerFrame> frame = peer->frame(bad);
            REQUIRE_FALSE(frame);
            CHECK(frame.error().code() == ErrorCode::InvalidArgument);
        }
    }
}

TEST_CASE("Peers: an invalid mesh is refused by name", "[peers]") {
    HostMesh broken = twoSpheres().meshes[0];
    broken.name = "broken";
    broken.indices.back() = static_cast<std::uint32_t>(broken.positions.size());
    const std::vector<HostMesh> meshes = {broken};
    auto cgal = createCgalPeer({}, {}, 2);
    auto embree = createEmbreePeer(EmbreeUpdate::Rebuild, {}, 2);
    auto fcl = createFclPeer(FclVolume::Obbrss, {false, Motion::Rigid}, 2);
    for (Peer* peer : {cgal->get(), embree->get(), fcl->get()}) {
        Result<PeerFrame> frame = peer->frame(meshes);
        REQUIRE_FALSE(frame);
        CHECK(frame.error().code() == ErrorCode::InvalidMesh);
        CHECK(frame.error().message().find("broken") != std::string::npos);
    }
}
