// Bench scene kinds, part 2: two big subdivided meshes overlapping deeply (a large
// shared volume), and a deforming pair that approaches, penetrates and separates.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "bench_scenes.hpp"

namespace vkcollide::bench {
namespace {


// Subdivision levels that bring `base` triangles closest to `target` (at least 0).
std::uint32_t levelsFor(double base, double target, std::uint32_t most) {
    const double l = std::round(std::log(std::max(1.0, target / base)) / std::log(4.0));
    return static_cast<std::uint32_t>(std::clamp(l, 0.0, double(most)));
}

// An icosphere pushed in and out by smooth waves: a closed, curved, nowhere-symmetric
// surface. `phase` changes the waves (per object and per frame).
Result<HostMesh> blob(float radius, std::uint32_t levels, double phase, double amplitude) {
    Result<HostMesh> m = icosphere(radius, levels);
    if (!m) return m.error();
    for (Float3& p : m->positions) {
        const double x = p.x / radius, y = p.y / radius, z = p.z / radius;
        const double wave = std::sin(3 * x + 2 * y + phase) * std::cos(2 * z - y + 0.7 * phase) +
                            0.5 * std::sin(5 * y + 4 * z + 1.3 * phase) + 0.25 * std::sin(9 * x - 7 * z + 2.1 * phase);
        const double k = 1 + amplitude * wave / 1.75;
        p = {static_cast<float>(p.x * k), static_cast<float>(p.y * k), static_cast<float>(p.z * k)};
    }
    return m;
}

}  // namespace

std::vector<SceneSpec> deepOverlapScenes(const std::string& data, double scale) {
    const std::uint32_t blob_levels = levelsFor(20, 1.31e6 * scale, 8);
    const std::uint32_t cgal_levels = levelsFor(80000, 1.3e6 * scale, 2);
    const std::size_t blob_tris = 20ull << (2 * blob_levels);
    return {
        {"deep-blobs", Motion::Rigid, SceneSet::Tuning, 1,
         "two subdivided wavy icospheres of " + std::to_string(blob_tris) + " triangles each, centres 0.6 radius apart: a large shared volume",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> a = blob(1.0f, blob_levels, 0.0, 0.15), b = blob(1.0f, blob_levels, 2.0, 0.15);
             if (!a) return a.error();
             if (!b) return b.error();
             std::vector<BenchObject> out(2);
             out[0].mesh = std::move(*a);
             out[0].mesh.name = "blob-a";
             out[0].transform = rotationTranslation(0.2, 1, 0.4, 0.5, {-0.3f, 0, 0});
             out[1].mesh = std::move(*b);
             out[1].mesh.name = "blob-b";
             out[1].transform = rotationTranslation(1, -0.3, 0.5, 1.2, {0.3f, 0.1f, 0.05f});
             return out;
         }},
        {"deep-bunny-elephant", Motion::Rigid, SceneSet::HeldOut, 1,
         "held-out: bunny00.off and refined_elephant.off subdivided " + std::to_string(cgal_levels) +
             " times (16x: 1.21M and 1.42M at scale 1), the same size, overlapping by a third of it, tilted",
         [=](int) -> Result<std::vector<BenchObject>> {
             Result<HostMesh> bunny = loadMesh(data, "bunny00.off", 1.0f), elephant = loadMesh(data, "refined_elephant.off", 1.0f);
             if (!bunny) return bunny.error();
             if (!elephant) return elephant.error();
             Result<HostMesh> fine_bunny = subdivide(*bunny, cgal_levels), fine_elephant = subdivide(*elephant, cgal_levels);
             if (!fine_bunny) return fine_bunny.error();
             if (!fine_elephant) return fine_elephant.error();
             std::vector<BenchObject> out(2);
             out[0].mesh = std::move(*fine_bunny);
             out[0].transform = rotationTranslation(0.1, 1, 0.3, 2.0, {0, 0, 0});
             out[1].mesh = std::move(*fine_elephant);
             out[1].transform = rotationTranslation(0.7, 0.2, 1, -0.8, {0.2f, 0.12f, -0.1f});
             return out;
         }},
    };
}

std::vector<SceneSpec> deformingPairScenes(const std::string& data, double scale) {
    const std::uint32_t levels = levelsFor(20, 81920 * scale, 7);
    const std::uint32_t around = scaledCount(256, scale, 2, 8), sides = scaledCount(100, scale, 2, 4);
    constexpr int kBlobFrames = 10, kToriFrames = 12, kCgalFrames = 8;
    return {
        {"deform-blobs", Motion::Deforming, SceneSet::Tuning, kBlobFrames,
         "two wavy icospheres of " + std::to_string(20ull << (2 * levels)) +
             " triangles whose waves move every frame, approaching along a diagonal, passing deep into each other and separating over 10 frames",
         [=](int f) -> Result<std::vector<BenchObject>> {
             const double t = static_cast<double>(f) / (kBlobFrames - 1);
             const double gap = 0.3 + 2.0 * std::fabs(std::cos(std::numbers::pi * t));  // centre distance in radii
             const double d[3] = {0.92, 0.32, 0.21};  // a unit diagonal
             std::vector<BenchObject> out(2);
             for (int o = 0; o < 2; ++o) {
                 Result<HostMesh> m = blob(1.0f, levels, 0.6 * f + 3.0 * o, 0.12);
                 if (!m) return m.error();
                 const double side = o == 0 ? -0.5 : 0.5;
                 const Transform3x4 at = rotationTranslation(o, 1, 0.3, 0.2 * f + o,
                                                             {static_cast<float>(side * gap * d[0]), static_cast<float>(side * gap * d[1]),
                                                              static_cast<float>(side * gap * d[2])});
                 // Deforming: the motion is baked into the vertices, the transform stays identity.
                 if (Result<void> ok = transformMesh(*m, at); !ok) return ok.error();
                 out[o].mesh = std::move(*m);
                 out[o].mesh.name = o == 0 ? "blob-a" : "blob-b";
             }
             return out;
         }},
        {"deform-tori", Motion::Deforming, SceneSet::HeldOut, kToriFrames,
         "held-out: two tori of " + std::to_string(2ull * around * sides) +
             " triangles at right angles, one sliding through the other's tube and out again over 12 frames while both twist and "
             "breathe, tilted, in millimetres (x 1000)",
         [=](int f) -> Result<std::vector<BenchObject>> {
             const double t = static_cast<double>(f) / (kToriFrames - 1);
             std::vector<BenchObject> out(2);
             for (int o = 0; o < 2; ++o) {
                 Result<HostMesh> m = torus(1.0f, 0.3f + 0.04f * static_cast<float>(std::sin(2 * std::numbers::pi * t + o)), around, sides);
                 if (!m) return m.error();
                 if (Result<void> ok = twistMesh(*m, static_cast<float>(0.4 * std::sin(std::numbers::pi * t) * (o ? -1 : 1))); !ok) return ok.error();
                 // Torus b stands in the XZ plane and slides along X from outside a's tube,
                 // through it, to its hole and back out the far side.
                 const Transform3x4 place = o == 0 ? kIdentity3x4
                                                   : rotationTranslation(1, 0, 0, std::numbers::pi / 2, {static_cast<float>(-2.6 + 3.2 * t), 0.0f, 0.05f});
                 Transform3x4 world = compose(rotationTranslation(0.3, 0.5, 1, 0.7, {0, 0, 0}), place);
                 for (float& v : world) v *= 1000.0f;
                 if (Result<void> ok = transformMesh(*m, world); !ok) return ok.error();
                 out[o].mesh = std::move(*m);
                 out[o].mesh.name = o == 0 ? "torus-a" : "torus-b";
             }
             return out;
         }},
        {"deform-armadillo-bunny", Motion::Deforming, SceneSet::HeldOut, kCgalFrames,
         "held-out: armadillo.off (52K) and bunny00.off (75K), each twisting back and forth, meeting head-on along a tilted line, "
         "passing through each other and apart over 8 frames",
         [=](int f) -> Result<std::vector<BenchObject>> {
             const double t = static_cast<double>(f) / (kCgalFrames - 1);
             std::vector<BenchObject> out(2);
             const char* files[2] = {"armadillo.off", "bunny00.off"};
             for (int o = 0; o < 2; ++o) {
                 Result<HostMesh> m = loadMesh(data, files[o], 1.0f);
                 if (!m) return m.error();
                 if (Result<void> ok = twistMesh(*m, static_cast<float>(0.8 * std::sin(2 * std::numbers::pi * t + o))); !ok) return ok.error();
                 // Centres 1.8 apart, through each other to 1.4 apart on the far sides, and back.
                 const double x = (o == 0 ? -1 : 1) * (0.9 - 1.6 * std::sin(std::numbers::pi * t));
                 Transform3x4 at = rotationTranslation(0.2, 1, 0.1, o ? 2.5 : 0.3, {static_cast<float>(x), 0, 0});
                 at = compose(rotationTranslation(0.1, 0.3, 1, 0.6, {0, 0, 0}), at);
                 if (Result<void> ok = transformMesh(*m, at); !ok) return ok.error();
                 out[o].mesh = std::move(*m);
             }
             return out;
         }},
    };
}

}  // namespace vkcollide::bench
