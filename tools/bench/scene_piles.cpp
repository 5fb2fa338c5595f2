// Piles of rigid meshes, no physics engine: objects of several shapes, randomly turned and
// scaled, are dropped one by one at random places into a square box and stop at the lowest
// height where their sphere (between the volume-equivalent and the bounding one) overlaps
// the spheres below (or the floor) by a few percent of its radius. Real shapes bulge past that sphere in places and fall short
// in others, so some neighbours interpenetrate by a few percent of their size and some
// only nearly touch: a pile's contacts. A thin floor slab takes the bottom layer's contacts.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "bench_scenes.hpp"

namespace vkcollide::bench {
namespace {


struct PileOptions {
    std::uint32_t objects = 60;
    double box_width = 9.0;    // side of the square box the objects fall into
    double overlap = 0.04;     // of the equivalent radius
    double size_lo = 0.6, size_hi = 1.4;  // random uniform scale of each shape
    std::uint32_t seed = 1;
    float units = 1.0f;        // everything multiplied by this at the end
    Transform3x4 turn = kIdentity3x4;  // the whole pile, floor included
    std::uint32_t floor_subdivisions = 20;
};

// A uniformly random rotation (from a random unit quaternion).
Transform3x4 randomRotation(std::uint32_t key, float s, Float3 t) {
    const double u1 = hash01(key), u2 = hash01(key + 1), u3 = hash01(key + 2);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    const double x = a * std::sin(2 * std::numbers::pi * u2), y = a * std::cos(2 * std::numbers::pi * u2), z = b * std::sin(2 * std::numbers::pi * u3), w = b * std::cos(2 * std::numbers::pi * u3);
    const auto f = [s](double v) { return static_cast<float>(s * v); };
    return {f(1 - 2 * (y * y + z * z)), f(2 * (x * y - z * w)), f(2 * (x * z + y * w)), t.x,
            f(2 * (x * y + z * w)), f(1 - 2 * (x * x + z * z)), f(2 * (y * z - x * w)), t.y,
            f(2 * (x * z - y * w)), f(2 * (y * z + x * w)), f(1 - 2 * (x * x + y * y)), t.z};
}

Result<std::vector<BenchObject>> pile(const std::vector<HostMesh>& shapes, const PileOptions& o) {
    // Each shape's sphere: halfway between its volume-equivalent sphere and its bounding
    // sphere about the origin (the same for a ball; a thin shape does not sink into others).
    std::vector<double> radius;
    for (const HostMesh& m : shapes) {
        Result<MeshStats> st = computeMeshStats(m);
        if (!st) return st.error();
        double bound = 0;
        for (const Float3& p : m.positions) bound = std::max(bound, std::sqrt(double{p.x} * p.x + double{p.y} * p.y + double{p.z} * p.z));
        radius.push_back(0.5 * (bound + std::cbrt(3.0 * std::fabs(st->signed_volume) / (4.0 * std::numbers::pi))));
    }
    struct Placed {
        double x, y, z, r;
    };
    std::vector<Placed> placed;
    std::vector<BenchObject> out;
    for (std::uint32_t i = 0; i < o.objects; ++i) {
        const std::uint32_t key = o.seed * 7919u + 16u * i;
        const std::size_t shape = i % shapes.size();
        const double s = o.size_lo + (o.size_hi - o.size_lo) * hash01(key + 3);
        const double r = radius[shape] * s;
        // Settling: of kTries random drop points, the one where the object comes to rest
        // lowest (it rolls into a gap), instead of a porous tower of first contacts.
        constexpr std::uint32_t kTries = 12;
        double x = 0, y = 0, z = 0;
        for (std::uint32_t t = 0; t < kTries; ++t) {
            const double tx = r + (o.box_width - 2 * r) * hash01(key + 100 * t + 4), ty = r + (o.box_width - 2 * r) * hash01(key + 100 * t + 5);
            double tz = r * (1 - o.overlap);  // resting on the floor (z = 0), sunk in a little
            for (const Placed& p : placed) {
                const double reach = (r + p.r) * (1 - o.overlap), d2 = (tx - p.x) * (tx - p.x) + (ty - p.y) * (ty - p.y);
                if (d2 < reach * reach) tz = std::max(tz, p.z + std::sqrt(reach * reach - d2));
            }
            if (t == 0 || tz < z) x = tx, y = ty, z = tz;
        }
        placed.push_back({x, y, z, r});
        BenchObject b;
        b.mesh = shapes[shape];
        b.mesh.name = shapes[shape].name + "#" + std::to_string(i);
        b.transform = randomRotation(key, static_cast<float>(s), {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
        out.push_back(std::move(b));
    }
    // The floor: a slab 2 % of the mean radius thick whose top is z = 0.
    double mean_r = 0;
    for (const Placed& p : placed) mean_r += p.r / static_cast<double>(placed.size());
    const auto half = static_cast<float>(0.5 * o.box_width), thick = static_cast<float>(0.01 * mean_r);
    Result<HostMesh> slab = box({half, half, thick}, o.floor_subdivisions);
    if (!slab) return slab.error();
    BenchObject floor;
    floor.mesh = std::move(*slab);
    floor.mesh.name = "floor";
    floor.transform = Transform3x4{1, 0, 0, half, 0, 1, 0, half, 0, 0, 1, -thick};
    out.push_back(std::move(floor));
    const Transform3x4 world = [&] {
        Transform3x4 t = o.turn;
        for (int k = 0; k < 12; ++k) t[k] *= o.units;
        return t;
    }();
    for (BenchObject& b : out) b.transform = compose(world, b.transform);
    return out;
}

// Six generated shapes of about `n` triangles each (n >= 200).
Result<std::vector<HostMesh>> generatedShapes(std::uint32_t n) {
    const auto side = [](double t) { return static_cast<std::uint32_t>(std::max(3.0, std::round(std::sqrt(t)))); };
    std::vector<Result<HostMesh>> made = {
        uvSphere(0.9f, side(n), std::max(2u, side(n) / 2)),
        torus(0.8f, 0.28f, side(2.0 * n), std::max(3u, side(n / 2.0))),
        box({0.9f, 0.55f, 0.35f}, std::max(1u, side(n / 12.0))),
        frustum(0.45f, 0.45f, 1.8f, side(2.0 * n), std::max(1u, side(n / 8.0))),
        frustum(0.75f, 0.0f, 1.5f, side(2.0 * n), std::max(1u, side(n / 8.0))),
        icosphere(0.8f, static_cast<std::uint32_t>(std::clamp(std::lround(std::log(n / 20.0) / std::log(4.0)), 1l, 7l))),
    };
    const char* names[] = {"sphere", "torus", "box", "cylinder", "cone", "ellipsoid"};
    std::vector<HostMesh> out;
    for (std::size_t k = 0; k < made.size(); ++k) {
        if (!made[k]) return made[k].error();
        out.push_back(std::move(*made[k]));
        out.back().name = names[k];
    }
    // The icosphere becomes an ellipsoid: a shape whose contact normals are not radial.
    if (Result<void> ok = transformMesh(out.back(), Transform3x4{1.1f, 0, 0, 0, 0, 0.75f, 0, 0, 0, 0, 0.5f, 0}); !ok) return ok.error();
    return out;
}

}  // namespace

std::vector<SceneSpec> pileScenes(const std::string& data, double scale) {
    const std::uint32_t per_shape = std::max<std::uint32_t>(200, static_cast<std::uint32_t>(10000 * scale));
    const std::uint32_t per_small = std::max<std::uint32_t>(100, static_cast<std::uint32_t>(2100 * scale));
    const std::uint32_t per_deep = std::max<std::uint32_t>(200, static_cast<std::uint32_t>(8000 * scale));
    const std::uint32_t cgal_objects = static_cast<std::uint32_t>(std::clamp(std::lround(64 * std::sqrt(scale)), 12l, 64l));
    return {
        {"pile-shapes", Motion::Rigid, SceneSet::Tuning, 1,
         "60 rigid meshes of six generated shapes (~" + std::to_string(per_shape) + " triangles each) piled in a 9 x 9 box on a thin floor",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<std::vector<HostMesh>> shapes = generatedShapes(per_shape);
             if (!shapes) return shapes.error();
             return pile(*shapes, PileOptions{});
         }},
        {"pile-small", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: 240 smaller meshes of the six shapes (~" + std::to_string(per_small) + " triangles each), another seed, a "
         "deeper 11 x 11 pile, more overlap, in centimetres (x 100), tilted",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<std::vector<HostMesh>> shapes = generatedShapes(per_small);
             if (!shapes) return shapes.error();
             PileOptions o;
             o.objects = 240;
             o.box_width = 11.0;
             o.overlap = 0.07;
             o.size_lo = 0.4;
             o.size_hi = 1.1;
             o.seed = 29;
             o.units = 100.0f;
             o.turn = rotationTranslation(0.3, 1, 0.1, 0.4, {0, 0, 0});
             return pile(*shapes, o);
         }},
        {"pile-deep", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: 64 meshes of the six shapes (~" + std::to_string(per_deep) + " triangles each) sunk halfway into each other "
         "(the deep-overlap pile: large volumes overlapping), another seed, a 6 x 6 box, tilted",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<std::vector<HostMesh>> shapes = generatedShapes(per_deep);
             if (!shapes) return shapes.error();
             PileOptions o;
             o.objects = 64;
             o.box_width = 6.0;
             o.overlap = 0.5;
             o.seed = 17;
             o.turn = rotationTranslation(-0.5, 0.2, 1, 0.3, {0, 0, 0});
             return pile(*shapes, o);
         }},
        {"pile-cgal", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: " + std::to_string(cgal_objects) + " packaged meshes of eight kinds (man, camel, fandisk, knot1, cow, triceratops, "
         "elephant, eight) piled in a narrower 7 x 7 box, another seed",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<HostMesh> shapes;
             for (const char* f : {"man.off", "camel.off", "fandisk.off", "knot1.off", "cow.off", "triceratops.off", "elephant.off", "eight.off"}) {
                 Result<HostMesh> m = loadMesh(data, f, 2.0f);
                 if (!m) return m.error();
                 shapes.push_back(std::move(*m));
             }
             PileOptions o;
             o.objects = cgal_objects;
             o.box_width = 7.0;
             o.seed = 5;
             o.size_lo = 0.5;
             o.size_hi = 1.0;
             return pile(shapes, o);
         }},
    };
}

}  // namespace vkcollide::bench
