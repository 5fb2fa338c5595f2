// Bench scene kinds, part 1: a cloth folded over a hinge through itself, a draped cloth with
// a flap folded through itself, a bar bent and twisted into itself, README's ball pushed
// through a cloth, and mixed engine/host meshes. Each kind has a tuning scene and a held-out
// one that differs in kind or parameters (other shapes, scales, orientations, motions).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "bench_scenes.hpp"

namespace vkcollide::bench {
namespace {


std::string count(std::size_t n) {
    return n >= 1000000 ? std::to_string(n / 1000000) + "." + std::to_string(n / 100000 % 10) + "M" : std::to_string((n + 500) / 1000) + "K";
}

BenchObject object(HostMesh mesh, std::string name, Transform3x4 transform = kIdentity3x4) {
    BenchObject o;
    o.mesh = std::move(mesh);
    o.mesh.name = std::move(name);
    o.transform = transform;
    return o;
}

// A closed bar along X (elliptic section a x b, length 2 pi radius turns) twisted `twists`
// times and bent `turns` times round with `pitch` per turn, so its ends pass through its start.
Result<HostMesh> wrappedBar(float a, float b, float radius, float turns, float twists, float pitch, std::uint32_t around,
                            std::uint32_t along) {
    const float length = 2.0f * static_cast<float>(std::numbers::pi) * radius * turns;
    Result<HostMesh> bar = frustum(1.0f, 1.0f, length, around, along);
    if (!bar) return bar.error();
    for (Result<void> ok : {transformMesh(*bar, Transform3x4{a, 0, 0, 0, 0, b, 0, 0, 0, 0, 1, 0}),
                            twistMesh(*bar, 2.0f * static_cast<float>(std::numbers::pi) * twists / length),
                            transformMesh(*bar, Transform3x4{0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 0}), bendMesh(*bar, radius, pitch)})
        if (!ok) return ok.error();
    return bar;
}

// A square cloth (n x n quads, side 1) folded over a hinge through itself: the part s <= hinge
// (s across [0, 1]) lies flat, rippled along y as a sin(2 pi f0 y); past a half-cylinder of
// radius r it comes back above, rippled as a sin(2 pi f1 y + phase). Where the ripples differ
// by more than 2 r the flap passes through the part below, along lines across the overlap.
Result<HostMesh> foldedCloth(std::uint32_t n, double hinge, double r, double a, double f0, double f1, double phase) {
    Result<HostMesh> cloth = clothGrid(1.0f, 1.0f, n, n);
    if (!cloth) return cloth.error();
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double bend = std::numbers::pi * r;  // the hinge's arc length
    for (Float3& p : cloth->positions) {
        const double s = double(p.x) + 0.5, y = double(p.y) + 0.5;
        const double below = a * std::sin(kTwoPi * f0 * y), above = a * std::sin(kTwoPi * f1 * y + phase);
        double x = s, z = below;
        if (s > hinge + bend) {
            x = hinge - (s - hinge - bend), z = 2 * r + above;
        } else if (s > hinge) {
            const double t = (s - hinge) / r;  // the angle round the hinge, 0 .. pi
            x = hinge + r * std::sin(t), z = r - r * std::cos(t) + below + (above - below) * t / std::numbers::pi;
        }
        p = {float(x - 0.5), float(y - 0.5), float(z)};
    }
    return cloth;
}

}  // namespace

std::vector<SceneSpec> foldScenes(double scale) {
    const std::uint32_t n = scaledCount(300, scale, 2, 16), n_b = scaledCount(600, scale, 2, 16);
    return {
        {"cloth-fold", Motion::Rigid, SceneSet::Tuning, 1,
         "one open cloth (" + count(2ull * n * n) +
             ", self-colliding) folded over a hinge so that its rippled flap passes through "
             "the part below along lines",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> cloth = foldedCloth(n, 0.5, 0.02, 0.03, 5.0, 7.0, 0.5);
             if (!cloth) return cloth.error();
             BenchObject c = object(std::move(*cloth), "cloth");
             c.open = true;
             return std::vector<BenchObject>{std::move(c)};
         }},
        {"cloth-fold-720K", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: as the exact-on-GPU issue's folded cloth, one open cloth (" + count(2ull * n_b * n_b) +
             ", self-colliding) folded through itself, other ripples, a tighter hinge, in metres x 2, tilted",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> cloth = foldedCloth(n_b, 0.58, 0.012, 0.025, 7.0, 9.0, 1.0);
             if (!cloth) return cloth.error();
             Transform3x4 t = rotationTranslation(0.3, 1, 0.4, 0.7, {0.2f, -0.1f, 0.05f});
             for (int k : {0, 1, 2, 4, 5, 6, 8, 9, 10}) t[k] *= 2.0f;
             BenchObject c = object(std::move(*cloth), "cloth", t);
             c.open = true;
             return std::vector<BenchObject>{std::move(c)};
         }},
    };
}

std::vector<SceneSpec> drapeScenes(double scale) {
    const std::uint32_t quads = scaledCount(100, scale, 2, 12), seg = scaledCount(64, scale, 2, 8);
    const std::uint32_t quads_b = scaledCount(130, scale, 2, 12);
    const std::uint32_t levels_b = static_cast<std::uint32_t>(std::clamp(std::lround(5 + std::log(scale) / std::log(4.0)), 1l, 5l));
    return {
        {"drape-flap", Motion::Rigid, SceneSet::Tuning, 1,
         "open cloth (" + count(2ull * quads * quads) + ") draped over a uv sphere, sunk in by 0.4 %, a corner flap folded through it",
         [=](int) -> Result<std::vector<BenchObject>> {
             DrapeOptions o;
             o.size = 3.2f;
             o.quads = quads;
             o.gap = -0.004f;
             Result<HostMesh> cloth = drapedCloth(o);
             Result<HostMesh> ball = uvSphere(1.0f, seg, seg / 2);
             if (!cloth) return cloth.error();
             if (!ball) return ball.error();
             BenchObject c = object(std::move(*cloth), "cloth");
             c.open = true;
             return std::vector<BenchObject>{std::move(c), object(std::move(*ball), "ball")};
         }},
        {"drape-flap-b", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: a larger, finer cloth (" + count(2ull * quads_b * quads_b) + ") over an icosphere of radius 40, tilted, "
         "narrower contact cap, more folds, a wider flap",
         [=](int) -> Result<std::vector<BenchObject>> {
             DrapeOptions o;
             o.radius = 40.0f;
             o.size = 150.0f;
             o.quads = quads_b;
             o.gap = -0.1f;
             o.contact_angle = 0.8f;
             o.folds = 9;
             o.fold_depth = 0.18f;
             o.flap = 0.2f;
             o.flap_lift = 0.12f;
             Result<HostMesh> cloth = drapedCloth(o);
             Result<HostMesh> ball = icosphere(40.0f, levels_b);
             if (!cloth) return cloth.error();
             if (!ball) return ball.error();
             const Transform3x4 tilt = rotationTranslation(0.4, 1, 0.2, 0.9, {10, -5, 3});
             BenchObject c = object(std::move(*cloth), "cloth", tilt);
             c.open = true;
             return std::vector<BenchObject>{std::move(c), object(std::move(*ball), "ball", tilt)};
         }},
    };
}

std::vector<SceneSpec> twistedScenes(double scale) {
    const std::uint32_t around = scaledCount(48, scale, 2, 8), along = scaledCount(500, scale, 2, 24);
    const std::uint32_t around_b = scaledCount(64, scale, 2, 8), along_b = scaledCount(470, scale, 2, 24);
    return {
        {"twisted-bar", Motion::Rigid, SceneSet::Tuning, 1,
         "one closed elliptic bar (" + count(2ull * around * along) + ") twisted twice and bent 1.15 turns into itself: self-intersections only",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> bar = wrappedBar(0.25f, 0.14f, 1.0f, 1.15f, 2.0f, 0.2f, around, along);
             if (!bar) return bar.error();
             std::vector<BenchObject> out;
             out.push_back(object(std::move(*bar), "bar", rotationTranslation(1, 0.3, 0.1, 0.35, {0, 0, 0})));
             return out;
         }},
        {"twisted-ribbon", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: a thin-walled ribbon (" + count(2ull * around_b * along_b) + ", 0.7 wide, 0.04 thick) twisted 5 times and bent 1.3 "
         "turns into itself, in centimetres (x 0.01), tilted",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> ribbon = wrappedBar(0.35f, 0.02f, 1.6f, 1.3f, 5.0f, 0.25f, around_b, along_b);
             if (!ribbon) return ribbon.error();
             Transform3x4 t = rotationTranslation(0.2, 1, 0.7, 1.1, {0.3f, 0.1f, -0.2f});
             for (float& v : t) v *= 0.01f;
             std::vector<BenchObject> out;
             out.push_back(object(std::move(*ribbon), "ribbon", t));
             return out;
         }},
    };
}

std::vector<SceneSpec> ballClothScenes(double scale) {
    const std::uint32_t quads = scaledCount(100, scale, 2, 8), seg = scaledCount(64, scale, 2, 8);
    const std::uint32_t strip_x = scaledCount(150, scale, 2, 12), strip_y = scaledCount(45, scale, 2, 4);
    constexpr int kMovingFrames = 8;
    return {
        {"ball-cloth", Motion::Rigid, SceneSet::Tuning, 1,
         "README's example: a host ball (radius 0.5) pushed through a flat engine cloth (" + count(2ull * quads * quads) +
             ", 2 x 2, GPU mesh, open, self-colliding) whose size the world is not told",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> cloth = clothGrid(2.0f, 2.0f, quads, quads);
             Result<HostMesh> ball = uvSphere(0.5f, seg, seg / 2);
             if (!cloth) return cloth.error();
             if (!ball) return ball.error();
             BenchObject c = object(std::move(*cloth), "cloth");
             c.open = true;
             c.gpu = true;
             return std::vector<BenchObject>{object(std::move(*ball), "ball", rotationTranslation(0, 0, 1, 0, {0.1f, -0.05f, 0.2f})), std::move(c)};
         }},
        {"ball-cloth-moving", Motion::Moving, SceneSet::HeldOut, kMovingFrames,
         "held-out: a host cloth strip (" + count(2ull * strip_x * strip_y) + ", 3 x 0.9, tilted) and an icosphere ball (radius 0.5) "
         "moving through it over 8 frames, in metres x 10",
         [=](int f) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> cloth = clothGrid(30.0f, 9.0f, strip_x, strip_y);
             Result<HostMesh> ball = icosphere(5.0f, std::clamp<std::uint32_t>(seg / 16 + 1, 1, 4));
             if (!cloth) return cloth.error();
             if (!ball) return ball.error();
             const Transform3x4 tilt = rotationTranslation(1, 0.2, 0, 0.25, {0, 0, 0});
             BenchObject c = object(std::move(*cloth), "strip", tilt);
             c.open = true;
             // From 6 above the strip to 6 below it, along the strip's normal, drifting sideways.
             const double t = static_cast<double>(f) / (kMovingFrames - 1);
             const Transform3x4 ball_at = compose(tilt, rotationTranslation(0.3, 0.5, 1, 2 * t, {static_cast<float>(-4 + 8 * t), 0.5f,
                                                                                                  static_cast<float>(6 - 12 * t)}));
             return std::vector<BenchObject>{std::move(c), object(std::move(*ball), "ball", ball_at)};
         }},
    };
}

std::vector<SceneSpec> mixedScenes(double scale) {
    const std::uint32_t n = scaledCount(64, scale, 2, 8), quads = scaledCount(90, scale, 2, 8);
    return {
        {"mixed-gpu", Motion::Rigid, SceneSet::Tuning, 1,
         "3 x 3 overlapping spheres, tori and boxes, every other one an engine GPU mesh (typical edge given), plus an engine cloth "
         "draped over a host ball",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<BenchObject> out;
             for (int i = 0; i < 9; ++i) {
                 Result<HostMesh> m = i % 3 == 0 ? uvSphere(0.6f, n, n / 2) : i % 3 == 1 ? torus(0.55f, 0.2f, n, n / 2) : box({0.45f, 0.35f, 0.3f}, n / 6 + 1);
                 if (!m) return m.error();
                 BenchObject o = object(std::move(*m), "object" + std::to_string(i),
                                        rotationTranslation(hash01(5 * i) - 0.5, hash01(5 * i + 1) - 0.5, 1, 6 * hash01(5 * i + 2),
                                                            {1.0f * static_cast<float>(i % 3), 1.0f * static_cast<float>(i / 3), 0.1f * static_cast<float>(i % 2)}));
                 o.gpu = i % 2 == 1;
                 o.typical_edge_length = o.gpu ? 0.6f * 2.0f * static_cast<float>(std::numbers::pi) / static_cast<float>(n) : 0.0f;
                 out.push_back(std::move(o));
             }
             DrapeOptions d;
             d.radius = 0.5f;
             d.size = 1.6f;
             d.quads = quads;
             d.flap = 0.0f;
             d.gap = -0.003f;
             Result<HostMesh> cloth = drapedCloth(d);
             Result<HostMesh> ball = uvSphere(0.5f, n, n / 2);
             if (!cloth) return cloth.error();
             if (!ball) return ball.error();
             BenchObject c = object(std::move(*cloth), "cloth", rotationTranslation(0, 0, 1, 0, {1, 3, 0}));
             c.gpu = c.open = true;
             c.typical_edge_length = d.size / static_cast<float>(quads);
             out.push_back(std::move(c));
             out.push_back(object(std::move(*ball), "ball", rotationTranslation(0, 0, 1, 0, {1, 3, 0})));
             return out;
         }},
        {"mixed-gpu-b", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: 12 cones, cylinders and icospheres in a tilted ring at scale 0.1, GPU ones with 16-byte vertices and 16-bit "
         "indices, half of them with no typical edge given",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<BenchObject> out;
             const std::uint32_t seg = std::min<std::uint32_t>(n, 120);
             for (int i = 0; i < 12; ++i) {
                 Result<HostMesh> m = i % 3 == 0   ? frustum(0.05f, 0.0f, 0.12f, seg, seg / 3)
                                      : i % 3 == 1 ? frustum(0.035f, 0.035f, 0.14f, seg, seg / 3)
                                                   : icosphere(0.05f, std::clamp<std::uint32_t>(seg / 16, 1, 5));
                 if (!m) return m.error();
                 const double a = 2 * std::numbers::pi * i / 12;
                 const Transform3x4 place = rotationTranslation(hash01(9 * i), 1, hash01(9 * i + 1), 6 * hash01(9 * i + 2),
                                                                {static_cast<float>(0.16 * std::cos(a)), static_cast<float>(0.16 * std::sin(a)), 0});
                 BenchObject o = object(std::move(*m), "part" + std::to_string(i), compose(rotationTranslation(1, 1, 0, 0.6, {0, 0, 0}), place));
                 o.gpu = i % 2 == 0;
                 o.gpu_stride = 16;
                 o.gpu_index16 = o.mesh.positions.size() < 65536;
                 o.typical_edge_length = o.gpu && i % 4 == 0 ? 0.3f / static_cast<float>(seg) : 0.0f;
                 out.push_back(std::move(o));
             }
             return out;
         }},
    };
}


std::vector<SceneSpec> touchingScenes(double scale) {
    const std::uint32_t n = scaledCount(24, scale, 2, 2), seg = scaledCount(64, scale, 2, 8), mating = scaledCount(9, scale, 2, 2);
    // Every coordinate below is a multiple of a power of two: the contacts are exact in
    // float (coplanar faces, a vertex on a face), not just close.
    const auto boxAt = [](float hx, float hy, float hz, std::uint32_t subdivisions, Float3 at, std::string name) -> Result<BenchObject> {
        Result<HostMesh> m = box({hx, hy, hz}, subdivisions);
        if (!m) return m.error();
        return object(std::move(*m), std::move(name), Transform3x4{1, 0, 0, at.x, 0, 1, 0, at.y, 0, 0, 1, at.z});
    };
    return {
        {"stack-touching", Motion::Rigid, SceneSet::Tuning, 1,
         "3 x 3 x 2 unit boxes stacked face to face (exactly coplanar contacts), 4 spheres resting on the top with a pole vertex, a small box "
         "sunk 0.107 into the stack",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<BenchObject> out;
             for (int k = 0; k < 18; ++k) {
                 auto b = boxAt(0.5f, 0.5f, 0.5f, n, {float(k % 3), float(k / 3 % 3), float(k / 9)}, "box" + std::to_string(k));
                 if (!b) return b.error();
                 out.push_back(std::move(*b));
             }
             for (int k = 0; k < 4; ++k) {
                 Result<HostMesh> ball = uvSphere(0.25f, seg, seg / 2);
                 if (!ball) return ball.error();
                 out.push_back(object(std::move(*ball), "ball" + std::to_string(k),
                                      Transform3x4{1, 0, 0, 0.5f + float(k % 2), 0, 1, 0, 0.5f + float(k / 2), 0, 0, 1, 1.75f}));
             }
             // Sunk by 0.1069 and off the lattice in x and y, so no vertex of either box lies on
             // the other's face planes: its side faces cross the top (crossing pairs).
             auto sunk = boxAt(0.25f, 0.25f, 0.25f, n, {2.0431f, 1.9687f, 1.6431f}, "sunk");
             if (!sunk) return sunk.error();
             out.push_back(std::move(*sunk));
             return out;
         }},
        {"stack-mating", Motion::Rigid, SceneSet::Tuning, 1,
         "6 x 6 x 6 unit boxes of " + count(12ull * mating * mating) + " triangles each, stacked face to face (every neighbour's faces exactly "
         "coplanar and overlapping: a clash-detection scene where almost every pair touches)",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<BenchObject> out;
             for (int k = 0; k < 216; ++k) {
                 auto b = boxAt(0.5f, 0.5f, 0.5f, mating, {float(k % 6), float(k / 6 % 6), float(k / 36)}, "box" + std::to_string(k));
                 if (!b) return b.error();
                 out.push_back(std::move(*b));
             }
             return out;
         }},
        {"cad-mating", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: 5 x 4 x 4 plates (1 x 0.5 x 0.25) resting face to face, the whole stack turned about (1, 2, 3) so no face is "
         "axis-aligned and rounded world vertices leave mating faces only nearly coplanar",
         [=](int) -> Result<std::vector<BenchObject>> {
             const double angle = 0.41, nx = 1 / std::sqrt(14.0), ny = 2 / std::sqrt(14.0), nz = 3 / std::sqrt(14.0);
             const double c = std::cos(angle), sn = std::sin(angle), t = 1 - c;
             const double r[3][3] = {{t * nx * nx + c, t * nx * ny - sn * nz, t * nx * nz + sn * ny},
                                     {t * nx * ny + sn * nz, t * ny * ny + c, t * ny * nz - sn * nx},
                                     {t * nx * nz - sn * ny, t * ny * nz + sn * nx, t * nz * nz + c}};
             std::vector<BenchObject> out;
             for (int k = 0; k < 80; ++k) {
                 Result<HostMesh> plate = box({0.5f, 0.25f, 0.125f}, mating);
                 if (!plate) return plate.error();
                 const double at[3] = {1.0 * (k % 5), 0.5 * (k / 5 % 4), 0.25 * (k / 20)};
                 Transform3x4 x{};
                 for (int row = 0; row < 3; ++row) {
                     for (int col = 0; col < 3; ++col) x[4 * row + col] = static_cast<float>(r[row][col]);
                     x[4 * row + 3] = static_cast<float>(r[row][0] * at[0] + r[row][1] * at[1] + r[row][2] * at[2]);
                 }
                 out.push_back(object(std::move(*plate), "plate" + std::to_string(k), x));
             }
             return out;
         }},
        {"wall-touching", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: a running-bond wall of 4 x 5 bricks (half a brick offset per row, 0.5 x 0.25 x 0.125) touching face to face, a ball "
         "on top touching with a pole vertex, a thin plate standing on the wall's top face",
         [=](int) -> Result<std::vector<BenchObject>> {
             std::vector<BenchObject> out;
             for (int row = 0; row < 4; ++row)
                 for (int k = 0; k < 5; ++k) {
                     const float x = 0.5f * float(k) + (row % 2 ? 0.25f : 0.0f);
                     auto b = boxAt(0.25f, 0.125f, 0.0625f, n, {x, 0.0f, 0.125f * float(row)}, "brick" + std::to_string(row * 5 + k));
                     if (!b) return b.error();
                     out.push_back(std::move(*b));
                 }
             Result<HostMesh> ball = uvSphere(0.125f, seg, seg / 2);
             if (!ball) return ball.error();
             out.push_back(object(std::move(*ball), "ball", Transform3x4{1, 0, 0, 0.25f, 0, 1, 0, 0, 0, 0, 1, 0.5625f}));
             // A thin upright plate whose bottom face lies on the wall's top face.
             Result<HostMesh> plate = box({0.5f, 0.03125f, 0.25f}, n);
             if (!plate) return plate.error();
             out.push_back(object(std::move(*plate), "plate", Transform3x4{1, 0, 0, 1.0f, 0, 1, 0, 0.0625f, 0, 0, 1, 0.6875f}));
             return out;
         }},
    };
}

}  // namespace vkcollide::bench
