#include "support/pathological_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vkcollide::test {
namespace {

ObjectOptions named(std::string name, bool self_collision = false) {
    ObjectOptions o;
    o.name = std::move(name);
    o.self_collision = self_collision;
    return o;
}

Result<PathologicalCase> withReference(PathologicalCase c) {
    auto objects = c.scene.reference();
    auto ref = computeReferencePairs(objects);
    if (!ref) return ref.error();
    c.reference = std::move(*ref);
    return c;
}

// A closed box, outward winding.
void addBox(HostMesh& m, Float3 lo, Float3 hi) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 8; ++k)
        m.positions.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    static constexpr std::uint32_t kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : kQuads)
        for (std::uint32_t i : {q[0], q[1], q[2], q[0], q[2], q[3]}) m.indices.push_back(base + i);
}

// A tetrahedron wound outwards whatever order its corners come in.
HostMesh tetrahedron(std::string name, Float3 a, Float3 b, Float3 c, Float3 d) {
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
    const double det = (uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz;
    if (det > 0) std::swap(b, c);
    return HostMesh{std::move(name), {a, b, c, d}, {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2}};
}

}  // namespace

Result<PathologicalCase> repeatedTriangle(std::uint32_t copies) {
    PathologicalCase c{"one triangle x " + std::to_string(copies), {"repeated triangle", {}}, {.method = DetectMethod::Peeling}, {}};
    HostMesh stack{"stack", {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {}};
    stack.indices.reserve(std::size_t{copies} * 3);
    for (std::uint32_t k = 0; k < copies; ++k) stack.indices.insert(stack.indices.end(), {0u, 1u, 2u});
    // A triangle standing across the stack's plane, through its interior.
    HostMesh cross{"cross", {{-0.3f, -0.2f, -0.5f}, {0.3f, -0.2f, -0.5f}, {0.0f, 0.1f, 0.5f}}, {0, 1, 2}};
    c.scene.objects.push_back({std::move(stack), named("stack", true)});
    c.scene.objects.push_back({std::move(cross), named("cross")});
    c.settings.resolution = 32;
    c.settings.direction = std::array<float, 3>{0.2f, 0.3f, 1.0f};
    std::vector<TrianglePair> ref;
    ref.reserve(copies);
    for (std::uint32_t k = 0; k < copies; ++k) ref.push_back({0, k, 1, 0});
    c.reference = std::move(ref);
    return c;
}

Result<PathologicalCase> copiesWithOwnVertices(std::uint32_t copies) {
    PathologicalCase c{std::to_string(copies) + " copies with their own vertices", {"copies", {}}, {.method = DetectMethod::Reliable}, {}};
    HostMesh pile{"pile", {}, {}};
    pile.positions.reserve(std::size_t{copies} * 3);
    pile.indices.reserve(std::size_t{copies} * 3);
    for (std::uint32_t k = 0; k < copies; ++k) {
        pile.positions.insert(pile.positions.end(), {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}});
        pile.indices.insert(pile.indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    HostMesh cross{"cross", {{-0.3f, -0.2f, -0.5f}, {0.3f, -0.2f, -0.5f}, {0.0f, 0.1f, 0.5f}}, {0, 1, 2}};
    c.scene.objects.push_back({std::move(pile), named("pile", true)});
    c.scene.objects.push_back({std::move(cross), named("cross")});
    std::vector<TrianglePair> ref;
    ref.reserve(copies);
    for (std::uint32_t k = 0; k < copies; ++k) ref.push_back({0, k, 1, 0});
    c.reference = std::move(ref);
    return c;
}

std::string repeatedCornerFace(std::uint32_t corners) {
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
    obj.reserve(obj.size() + std::size_t{corners} * 2 + 2);
    for (std::uint32_t k = 0; k < corners; ++k) {
        obj += ' ';
        obj += static_cast<char>('1' + k % 3);
    }
    obj += '\n';
    return obj;
}

Result<PathologicalCase> slabsOverContact(std::uint32_t slabs, bool with_reference) {
    PathologicalCase c{std::to_string(slabs) + " slabs over a contact", {"slabs", {}}, {.method = DetectMethod::Peeling}, {}};
    c.scene.objects.push_back({tetrahedron("a", {-0.8f, -0.8f, 0.0f}, {0.6f, -0.8f, 0.0f}, {-0.8f, 0.6f, 0.0f}, {-0.8f, -0.8f, 0.9f}),
                               named("tetrahedron a")});
    c.scene.objects.push_back({tetrahedron("b", {-0.5f, -0.5f, 0.1f}, {0.8f, -0.5f, 0.1f}, {-0.5f, 0.8f, 0.1f}, {-0.5f, -0.5f, 1.0f}),
                               named("tetrahedron b")});
    HostMesh stack{"slabs", {}, {}};
    stack.positions.reserve(std::size_t{slabs} * 8);
    stack.indices.reserve(std::size_t{slabs} * 36);
    // 1 mm slabs 1 mm apart above the contact, wider than it: every ray through the
    // tetrahedra crosses every slab twice.
    const float pitch = 0.002f, thickness = 0.001f;
    for (std::uint32_t k = 0; k < slabs; ++k) {
        const float z = 1.2f + pitch * static_cast<float>(k);
        addBox(stack, {-0.95f, -0.95f, z}, {0.95f, 0.95f, z + thickness});
    }
    const float top = 1.2f + pitch * static_cast<float>(slabs) + 0.1f;
    c.scene.objects.push_back({std::move(stack), named("slabs")});
    c.settings.resolution = 16;
    c.settings.direction = std::array<float, 3>{0, 0, 1};
    c.settings.region = std::array<float, 6>{-1, -1, -0.5f, 1, 1, top};
    if (!with_reference) return c;
    return withReference(std::move(c));
}

Result<PathologicalCase> crossingTriangles(std::uint32_t count) {
    PathologicalCase c{std::to_string(count) + " mutually crossing triangles", {"crossing", {}}, {.method = DetectMethod::Peeling}, {}};
    HostMesh fan{"crossing", {}, {}};
    const double pi = std::acos(-1.0);
    for (std::uint32_t k = 0; k < count; ++k) {
        // Base through the origin (its midpoint, exactly: the ends are negatives), apex on
        // the z axis: each triangle holds the axis from 0 to its apex, so any two meet.
        const double angle = pi * double(k) / double(count);
        const auto x = static_cast<float>(std::cos(angle)), y = static_cast<float>(std::sin(angle));
        const float apex = 1.0f + static_cast<float>(k) / static_cast<float>(count);
        const auto base = static_cast<std::uint32_t>(fan.positions.size());
        fan.positions.insert(fan.positions.end(), {{x, y, 0.0f}, {-x, -y, 0.0f}, {0.0f, 0.0f, apex}});
        fan.indices.insert(fan.indices.end(), {base, base + 1, base + 2});
    }
    c.scene.objects.push_back({std::move(fan), named("crossing", true)});
    c.settings.resolution = 64;
    c.settings.direction = std::array<float, 3>{1.0f, 0.31f, 0.17f};
    if (count > 2000) return c;
    std::vector<TrianglePair> ref;
    for (std::uint32_t a = 0; a < count; ++a)
        for (std::uint32_t b = a + 1; b < count; ++b) ref.push_back({0, a, 0, b});
    c.reference = std::move(ref);
    return c;
}

Result<PathologicalCase> manyObjects(std::uint32_t count) {
    PathologicalCase c{std::to_string(count) + " objects", {"many objects", {}}, {.method = DetectMethod::Peeling}, {}};
    const auto side = static_cast<std::uint32_t>(std::ceil(std::cbrt(double(count))));
    for (std::uint32_t i = 0; i < count; ++i) {
        // Odd ones shifted a little, so neighbours cross instead of sharing face planes.
        const float shift = (i % 2) ? 0.15f : 0.0f;
        const float x = 0.5f * static_cast<float>(i % side), y = 1.0f * static_cast<float>((i / side) % side) + shift;
        const float z = 1.0f * static_cast<float>(i / (side * side)) + shift;
        // 0.7 wide at a pitch of 0.5 along x: each overlaps its +x neighbour.
        c.scene.objects.push_back({tetrahedron("t", {x, y, z}, {x + 0.7f, y, z}, {x, y + 0.7f, z}, {x + 0.1f, y + 0.1f, z + 0.7f}),
                                   named("tetrahedron " + std::to_string(i))});
    }
    c.settings.resolution = 256;
    c.settings.direction = std::array<float, 3>{0.2f, 0.3f, 1.0f};
    c.settings.peeling.coverage = Coverage::Dilate;  // grazing contacts between neighbours are thin
    return withReference(std::move(c));
}

Result<PathologicalCase> scaledCrossing(float scale) {
    char label[64];
    std::snprintf(label, sizeof label, "crossing triangles at scale %g", double(scale));
    PathologicalCase c{label, {"scaled", {}}, {.method = DetectMethod::Peeling}, {}};
    auto scaled = [scale](Float3 p) { return Float3{p.x * scale, p.y * scale, p.z * scale}; };
    HostMesh flat{"flat", {scaled({-1, -1, 0}), scaled({1, -1, 0}), scaled({0, 1, 0})}, {0, 1, 2}};
    HostMesh standing{"standing", {scaled({0, -0.5f, -1}), scaled({0.05f, 0.5f, 1}), scaled({0, 0.5f, -1})}, {0, 1, 2}};
    c.scene.objects.push_back({std::move(flat), named("flat")});
    c.scene.objects.push_back({std::move(standing), named("standing")});
    c.settings.resolution = 64;
    c.settings.direction = std::array<float, 3>{0.3f, 0.2f, 1.0f};
    c.reference = std::vector<TrianglePair>{{0, 0, 1, 0}};
    return c;
}

}  // namespace vkcollide::test
