// The grid exact reference (tests/support/exact_reference.cpp) against a brute-force test
// of every pair with the same rules, on random triangle soups that stress the grid: mixed
// sizes (from sub-cell needles to triangles spanning the scene), shared vertices, several
// objects with self-collision on and off, an object filter, and a thread count sweep.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "narrow/neighbours.hpp"
#include "narrow/triangle_intersection.hpp"
#include "support/exact_reference.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

HostMesh soup(std::mt19937& rng, std::size_t triangles, float scene_size) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    HostMesh m;
    m.name = "soup";
    for (std::size_t t = 0; t < triangles; ++t) {
        // Sizes spread over four decades, a few spanning most of the scene.
        const float size = scene_size * (unit(rng) < 0.01f ? 0.5f : 0.002f * std::pow(10.0f, 2.0f * unit(rng)));
        const Float3 c{scene_size * unit(rng), scene_size * unit(rng), scene_size * unit(rng)};
        const auto corner = [&] { return Float3{c.x + size * (unit(rng) - 0.5f), c.y + size * (unit(rng) - 0.5f), c.z + size * (unit(rng) - 0.5f)}; };
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        // A quarter of the triangles reuse a vertex of the previous one (neighbours).
        if (t > 0 && unit(rng) < 0.25f) {
            m.positions.push_back(corner());
            m.positions.push_back(corner());
            m.indices.insert(m.indices.end(), {base - 1, base, base + 1});
        } else {
            m.positions.insert(m.positions.end(), {corner(), corner(), corner()});
            m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
        }
    }
    return m;
}

std::vector<TrianglePair> bruteForce(const std::vector<ReferenceObject>& objects, bool (*may_collide)(std::uint32_t, std::uint32_t)) {
    struct Tri {
        std::uint32_t object, triangle, index[3];
        Float3 v[3];
    };
    std::vector<Tri> tris;
    for (std::uint32_t o = 0; o < objects.size(); ++o) {
        const std::vector<Float3> world = worldPositions(*objects[o].mesh, objects[o].transform);
        for (std::uint32_t t = 0; t < objects[o].mesh->triangleCount(); ++t) {
            Tri x{o, t, {}, {}};
            for (int k = 0; k < 3; ++k) {
                x.index[k] = objects[o].mesh->indices[3 * t + k];
                x.v[k] = world[x.index[k]];
            }
            tris.push_back(x);
        }
    }
    std::vector<TrianglePair> out;
    for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t j = i + 1; j < tris.size(); ++j) {
            const Tri &a = tris[i], &b = tris[j];
            if (a.object == b.object && (!objects[a.object].self_collision || narrow::areNeighbours(a.index, a.v, b.index, b.v))) continue;
            if (a.object != b.object && may_collide && !may_collide(a.object, b.object)) continue;
            if (narrow::trianglesIntersect(a.v, b.v)) out.push_back({a.object, a.triangle, b.object, b.triangle});
        }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("grid reference equals brute force on random soups of mixed sizes", "[scene][reference]") {
    std::mt19937 rng(12);
    for (int round = 0; round < 4; ++round) {
        const float scene_size = round == 3 ? 5000.0f : 1.0f;  // other units
        std::vector<HostMesh> meshes;
        for (int o = 0; o < 3; ++o) meshes.push_back(soup(rng, 300 + 200 * static_cast<std::size_t>(round), scene_size));
        std::vector<ReferenceObject> objects;
        for (std::size_t o = 0; o < meshes.size(); ++o) objects.push_back({&meshes[o], kIdentityTransform, o != 1});
        objects[2].transform = transformFrom3x4({0.8f, -0.6f, 0, 0.01f * scene_size, 0.6f, 0.8f, 0, 0, 0, 0, 1, 0.02f * scene_size});
        const auto filter = round == 2 ? +[](std::uint32_t a, std::uint32_t b) { return !(a == 0 && b == 2); } : nullptr;
        const std::vector<TrianglePair> expected = bruteForce(objects, filter);
        INFO("round " << round << ": " << expected.size() << " pairs");
        REQUIRE(expected.size() > 20);
        for (unsigned threads : {1u, 2u, 5u}) {
            ReferenceOptions options;
            options.threads = threads;
            if (filter) options.may_collide = filter;
            auto pairs = computeReferencePairs(objects, options);
            REQUIRE(pairs);
            CHECK(*pairs == expected);
        }
    }
}

TEST_CASE("grid reference: degenerate scenes (one point, a flat sheet) still work", "[scene][reference]") {
    HostMesh point;
    point.positions = {{1, 1, 1}};
    point.indices = {0, 0, 0, 0, 0, 0};
    std::vector<ReferenceObject> objects = {{&point}};
    auto pairs = computeReferencePairs(objects);
    REQUIRE(pairs);
    CHECK(pairs->empty());  // the two triangles share vertex 0: neighbours
    HostMesh flat;
    flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2f, 0.2f, 0}, {2, 0.2f, 0}, {0.2f, 2, 0}};
    flat.indices = {0, 1, 2, 3, 4, 5};
    objects = {{&flat}};
    pairs = computeReferencePairs(objects);
    REQUIRE(pairs);
    CHECK(pairs->size() == 1);  // coplanar overlap
}
