// DetectSettings::contacts.geometry through a world: one contact per pair whose end points lie
// on both triangles, per-object-pair sums that add up, the pairs unchanged, the same under
// either method and any thread count. Validation layer on.
#include <catch2/catch.hpp>

#include <cstring>
#include <map>

#include "contact_checks.hpp"
#include "narrow/slots.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scene_world.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// The world triangles of a scene, as the narrow phase sees them.
struct WorldTriangles {
    std::vector<std::vector<Float3>> positions;
    std::vector<const HostMesh*> meshes;
    std::array<Float3, 3> operator()(std::uint32_t object, std::uint32_t triangle) const {
        const HostMesh& m = *meshes[object];
        const std::vector<Float3>& p = positions[object];
        return {p[m.indices[3 * triangle]], p[m.indices[3 * triangle + 1]], p[m.indices[3 * triangle + 2]]};
    }
};

WorldTriangles worldTriangles(const TestScene& scene) {
    WorldTriangles w;
    for (const SceneObject& o : scene.objects) {
        std::vector<Float3> world;
        for (const Float3& p : o.mesh.positions) world.push_back(narrow::toWorld(o.options.transform, p));
        w.positions.push_back(std::move(world));
        w.meshes.push_back(&o.mesh);
    }
    return w;
}

void requireContacts(const DetectResult& r, const WorldTriangles& tri, const std::string& what) {
    INFO(what << ": " << r.pairs.size() << " pairs");
    REQUIRE(r.pair_contacts.size() == r.pairs.size());
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> per_objects;
    for (std::size_t k = 0; k < r.pairs.size(); ++k) {
        const TrianglePair& p = r.pairs[k];
        const PairContact& c = r.pair_contacts[k];
        const auto a = tri(p.object_a, p.triangle_a), b = tri(p.object_b, p.triangle_b);
        // Within float rounding of coordinates of about 1: on both triangles.
        for (const Float3& q : {c.start, c.end}) {
            CHECK(distanceToTriangle(q, a) < 1e-5);
            CHECK(distanceToTriangle(q, b) < 1e-5);
        }
        CHECK((c.shape == ContactShape::Coplanar) == (c.area > 0));
        ++per_objects[{p.object_a, p.object_b}];
    }
    REQUIRE(r.pair_contact_totals.size() == per_objects.size());
    std::size_t t = 0;
    for (const auto& [objects, count] : per_objects) {
        const ObjectPairContact& total = r.pair_contact_totals[t++];
        CHECK(total.object_a == objects.first);
        CHECK(total.object_b == objects.second);
        CHECK(total.pairs == count);
        CHECK(total.length >= 0);
    }
}

}  // namespace

TEST_CASE("contact geometry: every pair of the test scenes gets a contact on both triangles", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto scenes = allTestScenes(0.5f);
    REQUIRE(scenes);
    DetectSettings on;
    on.contacts.geometry = true;
    for (const TestScene& scene : *scenes) {
        const WorldTriangles tri = worldTriangles(scene);
        DetectResult first;
        for (unsigned threads : {1u, 3u}) {
            auto world = sceneWorld(ctx, scene, threads);
            auto plain = world->detect();
            auto r = world->detect(on);
            REQUIRE(plain);
            REQUIRE(r);
            CHECK(r->pairs == plain->pairs);
            CHECK(plain->pair_contacts.empty());
            CHECK(plain->pair_contact_totals.empty());
            CHECK(r->stats.contacts.geometry_ms >= 0);
            requireContacts(*r, tri, scene.name);
            if (threads == 1) {
                first = std::move(*r);
                continue;
            }
            // The same bits on any thread count.
            REQUIRE(r->pair_contacts.size() == first.pair_contacts.size());
            CHECK(std::memcmp(static_cast<const void*>(r->pair_contacts.data()), static_cast<const void*>(first.pair_contacts.data()),
                              r->pair_contacts.size() * sizeof(PairContact)) == 0);
            REQUIRE(r->pair_contact_totals.size() == first.pair_contact_totals.size());
            for (std::size_t k = 0; k < first.pair_contact_totals.size(); ++k) {
                CHECK(r->pair_contact_totals[k].length == first.pair_contact_totals[k].length);
                CHECK(r->pair_contact_totals[k].normal.x == first.pair_contact_totals[k].normal.x);
            }
        }
    }
    // The peeling method's pairs get theirs too.
    const TestScene& scene = scenes->front();
    auto world = sceneWorld(ctx, scene);
    DetectSettings peeling = on;
    peeling.method = DetectMethod::Peeling;
    auto r = world->detect(peeling);
    REQUIRE(r);
    requireContacts(*r, worldTriangles(scene), scene.name + ", peeling");
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contact geometry: resting boxes touch along segments and coplanar faces", "[contacts][gpu]") {
    ValidatedContext ctx;
    TestScene s{"two resting boxes", {}};
    for (int k = 0; k < 2; ++k) {
        auto b = box({0.5f, 0.5f, 0.5f}, 2);
        REQUIRE(b);
        s.objects.push_back({std::move(*b), {.name = "box" + std::to_string(k), .transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, float(k)}}});
    }
    auto world = sceneWorld(ctx, s);
    DetectSettings on;
    on.contacts.geometry = true;
    auto r = world->detect(on);
    REQUIRE(r);
    requireContacts(*r, worldTriangles(s), s.name);
    // The top face of box 0 lies on the bottom face of box 1: their overlap is the whole
    // 1 x 1 face, counted once per overlapping triangle pair; the normals point down (+z of
    // box 0's top against -z of box 1's bottom pushes box 0's triangles down).
    double coplanar_area = 0;
    for (const PairContact& c : r->pair_contacts)
        if (c.shape == ContactShape::Coplanar) {
            coplanar_area += c.area;
            CHECK(c.normal.z == -1);
        }
    CHECK(coplanar_area == Approx(1.0).epsilon(1e-5));
    REQUIRE(r->pair_contact_totals.size() == 1);
    CHECK(r->pair_contact_totals[0].area == Approx(1.0).epsilon(1e-5));
    CHECK(r->pair_contact_totals[0].pairs == r->pairs.size());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
