#include "support/test_scenes.hpp"

#include <algorithm>
#include <cmath>

namespace vkcollide::test {
namespace {

std::uint32_t scaled(std::uint32_t n, float detail) { return std::max<std::uint32_t>(3, static_cast<std::uint32_t>(std::lround(static_cast<float>(n) * detail))); }

ObjectOptions placed(const char* name, Transform3x4 t, bool self = false, bool open = false) {
    ObjectOptions o;
    o.name = name;
    o.transform = t;
    o.self_collision = self;
    o.open = open;
    return o;
}

}  // namespace

Transform3x4 rotationY(float angle, Float3 t) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c, 0, s, t.x, 0, 1, 0, t.y, -s, 0, c, t.z};
}

std::vector<ReferenceObject> TestScene::reference() const {
    std::vector<ReferenceObject> out;
    for (const SceneObject& o : objects) out.push_back({&o.mesh, transformFrom3x4(o.options.transform), o.options.self_collision});
    return out;
}

Result<TestScene> overlappingSpheres(float d) {
    TestScene s{"overlapping spheres", {}};
    for (auto r : {addObject(s, uvSphere(1.0f, scaled(48, d), scaled(24, d)), placed("sphere-a", rotationY(0.3f, {-0.6f, 0.05f, 0.0f}))),
                   addObject(s, uvSphere(0.9f, scaled(40, d), scaled(20, d)), placed("sphere-b", rotationY(0.7f, {0.55f, -0.1f, 0.2f}))),
                   addObject(s, uvSphere(0.5f, scaled(32, d), scaled(16, d)), placed("sphere-c", rotationY(0.1f, {0.1f, 0.9f, 0.3f}))),
                   addObject(s, uvSphere(0.4f, scaled(24, d), scaled(12, d)), placed("sphere-far", rotationY(0.0f, {-2.5f, -1.5f, 0.0f})))})
        if (!r) return r.error();
    return s;
}

Result<TestScene> torusThroughBox(float d) {
    TestScene s{"torus through box", {}};
    for (auto r : {addObject(s, torus(0.9f, 0.25f, scaled(64, d), scaled(16, d)), placed("torus", rotationY(0.2f, {0, 0, 0}))),
                   addObject(s, box({0.3f, 0.3f, 1.4f}, scaled(6, d)), placed("bar", rotationY(0.1f, {0.9f, 0, 0})))})
        if (!r) return r.error();
    return s;
}

Result<TestScene> selfIntersectingTube(float d) {
    TestScene s{"self-intersecting tube", {}};
    if (auto r = addObject(s, twistedTube(1.0f, 0.2f, scaled(96, d), scaled(16, d), 1.0f), placed("tube", rotationY(0.4f, {0, 0, 0}), true)); !r)
        return r.error();
    return s;
}

Result<TestScene> clothThroughSphere(float d) {
    TestScene s{"cloth through sphere", {}};
    ClothOptions folded;
    folded.sag = 0.3f;
    for (auto r : {addObject(s, clothGrid(3.0f, 3.0f, scaled(40, d), scaled(40, d), folded), placed("cloth", rotationY(0.05f, {0, 0, 0.2f}), true, true)),
                   addObject(s, uvSphere(0.8f, scaled(48, d), scaled(24, d)), placed("ball", rotationY(0.0f, {0.1f, 0.2f, 0.0f})))})
        if (!r) return r.error();
    return s;
}

Result<TestScene> coincidentGrids(std::uint32_t cells) {
    TestScene s{"coincident grids", {}};
    for (int k = 0; k < 3; ++k) {
        auto g = clothGrid(1.0f, 1.0f, cells, cells);
        if (!g) return g.error();
        s.objects.push_back({std::move(*g), {.name = "grid" + std::to_string(k), .open = true}});
    }
    return s;
}

HostMesh coplanarFan(std::uint32_t n) {
    HostMesh fan{"fan", {}, {}};
    for (std::uint32_t k = 0; k < n; ++k) {
        for (int v = 0; v < 3; ++v) {
            const double a = 0.011 * k + 2.0943951023931953 * v;
            fan.positions.push_back({float(2.5 + 0.1 * std::cos(a)), float(0.1 * std::sin(a)), 0.0f});
        }
        fan.indices.insert(fan.indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    return fan;
}

TestScene combScene(std::uint32_t teeth) {
    TestScene s{"comb of " + std::to_string(teeth), {}};
    s.objects.push_back({HostMesh{"plate", {{-40, -40, 0}, {40, -40, 0}, {0, 40, 0}}, {0, 1, 2}}, placed("plate", kIdentity3x4, false, true)});
    HostMesh comb{"teeth", {}, {}};
    const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(teeth))));
    for (std::uint32_t k = 0; k < teeth; ++k) {
        const float x = -4.0f + 8.0f * float(k % side) / float(side), y = -4.0f + 8.0f * float(k / side) / float(side);
        comb.positions.insert(comb.positions.end(), {{x, y, -0.1f}, {x + 0.01f, y, 0.1f}, {x, y + 0.01f, 0.1f}});
        comb.indices.insert(comb.indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    s.objects.push_back({std::move(comb), placed("teeth", kIdentity3x4, false, true)});
    return s;
}

Result<std::vector<TestScene>> allTestScenes(float d) {
    std::vector<TestScene> out;
    for (auto make : {overlappingSpheres, torusThroughBox, selfIntersectingTube, clothThroughSphere}) {
        auto s = make(d);
        if (!s) return s.error();
        out.push_back(std::move(*s));
    }
    return out;
}

Result<void> addObject(TestScene& s, Result<HostMesh> mesh, ObjectOptions options) {
    if (!mesh) return mesh.error();
    s.objects.push_back({std::move(*mesh), std::move(options)});
    return {};
}

}  // namespace vkcollide::test
