// Closed host meshes that are not closed surfaces facing outwards are named in
// DetectStats::mesh_warnings (api/mesh_checks): inside out (negative volume, mirroring
// transforms counted; measured by addMesh) and holed (boundary edges); nothing for a
// good closed mesh or an open one.
#include <catch2/catch.hpp>

#include <algorithm>

#include "api/mesh_checks.hpp"
#include "support/gpu_fixture.hpp"
#include "support/world_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

HostMesh ball(float x) {
    auto m = icosphere(1.0f, 2);
    REQUIRE(m);
    for (Float3& p : m->positions) p.x += x;
    return *m;
}

HostMesh flipped(HostMesh m) {
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

// One triangle fewer: a hole of three boundary edges.
HostMesh holed(HostMesh m) {
    m.indices.resize(m.indices.size() - 3);
    return m;
}

const MeshWarning* warningFor(const DetectResult& r, ObjectId id) {
    for (const MeshWarning& w : r.stats.mesh_warnings)
        if (w.object == id) return &w;
    return nullptr;
}

}  // namespace

TEST_CASE("mesh checks: boundary edges and the signed volume of closed and broken meshes", "[api]") {
    ThreadPool pool(2);
    const HostMesh good = ball(0);
    CHECK(mesh_checks::boundaryEdges(good.indices) == 0);
    CHECK(mesh_checks::boundaryEdges(holed(good).indices) == 3);  // one triangle removed: its three edges
    // A unit sphere of 320 triangles: a little under 4/3 pi.
    const double v6 = mesh_checks::signedVolume6(pool, good.positions, good.indices);
    CHECK(v6 / 6 == Approx(4.0 / 3.0 * 3.14159265).epsilon(0.1));
    CHECK(mesh_checks::signedVolume6(pool, good.positions, flipped(good).indices) == Approx(-v6));
    CHECK(mesh_checks::determinant(kIdentity3x4) == 1);
    CHECK(mesh_checks::determinant({-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}) == -1);
}

TEST_CASE("detect() warns of closed meshes that are inside out or holed, not of good or open ones", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto good = world->addMesh(ball(0), {.name = "good"});
    auto inside_out = world->addMesh(flipped(ball(1.2f)), {.name = "flipped"});
    auto hole = world->addMesh(holed(ball(-1.2f)), {.name = "holed"});
    auto cloth = world->addMesh(holed(ball(0.0f)), {.name = "cloth", .open = true});
    REQUIRE((good && inside_out && hole && cloth));
    auto r = world->detect();
    REQUIRE(r);
    CHECK(r->stats.mesh_warnings.size() == 2);
    CHECK(warningFor(*r, *good) == nullptr);
    CHECK(warningFor(*r, *cloth) == nullptr);
    const MeshWarning* w = warningFor(*r, *inside_out);
    REQUIRE(w);
    CHECK(w->inside_out);
    CHECK(w->boundary_edges == 0);
    CHECK(w->message.find("object 1 ('flipped'): declared closed but inside out") == 0);
    w = warningFor(*r, *hole);
    REQUIRE(w);
    CHECK_FALSE(w->inside_out);
    CHECK(w->boundary_edges == 3);
    CHECK(w->message.find("object 2 ('holed'): declared closed but has 3 boundary edges") == 0);

    // A mirroring transform turns the good ball inside out, and the flipped one right again.
    const Transform3x4 mirror{-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    REQUIRE(world->setTransform(*good, mirror));
    REQUIRE(world->setTransform(*inside_out, {-1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0}));
    r = world->detect();
    REQUIRE(r);
    CHECK(warningFor(*r, *good) != nullptr);
    CHECK(warningFor(*r, *inside_out) == nullptr);
    REQUIRE(world->setTransform(*good, kIdentity3x4));
    r = world->detect();
    REQUIRE(r);
    CHECK(warningFor(*r, *good) == nullptr);

}
