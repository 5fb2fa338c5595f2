#include "bench_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "vkcollide/io.hpp"

namespace vkcollide::bench {
namespace {


}  // namespace

Transform3x4 rotationTranslation(double axis_x, double axis_y, double axis_z, double angle, Float3 t) {
    const double n = std::sqrt(axis_x * axis_x + axis_y * axis_y + axis_z * axis_z);
    const double x = axis_x / n, y = axis_y / n, z = axis_z / n;
    const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    const auto f = [](double v) { return static_cast<float>(v); };
    return {f(c + x * x * k),     f(x * y * k - z * s), f(x * z * k + y * s), t.x,
            f(y * x * k + z * s), f(c + y * y * k),     f(y * z * k - x * s), t.y,
            f(z * x * k - y * s), f(z * y * k + x * s), f(c + z * z * k),     t.z};
}

double hash01(std::uint32_t i) {
    std::uint32_t h = i * 2654435761u;
    h ^= h >> 16;
    h *= 2246822519u;
    h ^= h >> 13;
    return static_cast<double>(h) / 4294967296.0;
}

Transform3x4 compose(const Transform3x4& a, const Transform3x4& b) {
    Transform3x4 out{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            double v = c == 3 ? a[4 * r + 3] : 0.0;
            for (int k = 0; k < 3; ++k) v += double{a[4 * r + k]} * b[4 * k + c];
            out[4 * r + c] = static_cast<float>(v);
        }
    return out;
}

std::uint32_t scaledCount(std::uint32_t n, double scale, int dims, std::uint32_t least) {
    const double v = std::round(n * std::pow(scale, 1.0 / dims));
    return std::max(least, static_cast<std::uint32_t>(std::min(v, 1e9)));
}

Result<HostMesh> loadMesh(const std::string& data, const std::string& file, float size) {
    Result<std::vector<HostMesh>> read = readMeshFile(data + "/" + file);
    if (!read) return Error(read.error().code(), read.error().message() + " (tools/fetch_cgal_data.sh " + data + ")");
    if (read->size() != 1) return Error(ErrorCode::InvalidArgument, file + ": expected one mesh");
    HostMesh m = std::move(read->front());
    Result<MeshStats> st = computeMeshStats(m);
    if (!st) return st.error();
    const Float3 lo = st->bounds_min, hi = st->bounds_max;
    const float k = size / std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    if (Result<void> ok = transformMesh(m, Transform3x4{k, 0, 0, -0.5f * k * (lo.x + hi.x), 0, k, 0, -0.5f * k * (lo.y + hi.y), 0, 0, k,
                                                        -0.5f * k * (lo.z + hi.z)});
        !ok)
        return ok.error();
    m.name = file.substr(0, file.find('.'));
    return m;
}

Result<std::vector<HostMesh>> worldMeshes(const std::vector<BenchObject>& objects) {
    std::vector<HostMesh> out;
    for (const BenchObject& o : objects) {
        HostMesh m = o.mesh;
        if (Result<void> ok = transformMesh(m, o.transform); !ok) return ok.error();
        out.push_back(std::move(m));
    }
    return out;
}

const char* motionName(Motion motion) {
    switch (motion) {
        case Motion::Rigid: return "rigid";
        case Motion::Deforming: return "deforming";
        case Motion::Moving: return "moving";
    }
    return "?";
}

const char* setName(SceneSet set) {
    switch (set) {
        case SceneSet::Tuning: return "tuning";
        case SceneSet::HeldOut: return "held-out";
        case SceneSet::User: return "user";
    }
    return "?";
}

namespace {

// `count` unit spheres on a grid whose spacing (< 2) makes neighbours overlap; each
// turned by its own rotation so seams do not line up.
Result<std::vector<HostMesh>> sphereGrid(std::uint32_t count, std::uint32_t segments, std::uint32_t rings,
                                         float spacing = 1.8f) {
    Result<HostMesh> base = uvSphere(1.0f, segments, rings);
    if (!base) return base.error();
    const auto side = static_cast<std::uint32_t>(std::ceil(std::cbrt(static_cast<double>(count))));
    std::vector<HostMesh> meshes;
    for (std::uint32_t i = 0; i < count; ++i) {
        HostMesh m = *base;
        m.name = "sphere" + std::to_string(i);
        const Float3 t{spacing * static_cast<float>(i % side), spacing * static_cast<float>((i / side) % side),
                       spacing * static_cast<float>(i / (side * side))};
        const Transform3x4 xf = rotationTranslation(hash01(3 * i) - 0.5, hash01(3 * i + 1) - 0.5,
                                                    hash01(3 * i + 2) + 0.1, 2 * std::numbers::pi * hash01(7 * i + 5), t);
        if (Result<void> ok = transformMesh(m, xf); !ok) return ok.error();
        meshes.push_back(std::move(m));
    }
    return meshes;
}

// `count` copies of a packaged mesh around a ring (each turned about the vertical axis),
// neighbours `step` times the mesh's size apart: 0.65 overlaps them by about a third.
Result<std::vector<HostMesh>> meshRing(const std::string& path, std::uint32_t count, double step_fraction = 0.65) {
    Result<std::vector<HostMesh>> read = readMeshFile(path);
    if (!read) return read.error();
    if (read->size() != 1) return Error(ErrorCode::InvalidArgument, path + ": expected one mesh");
    HostMesh base = std::move(read->front());
    Result<MeshStats> stats = computeMeshStats(base);
    if (!stats) return stats.error();
    const Float3 lo = stats->bounds_min, hi = stats->bounds_max;
    const float size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    // Centre on the origin first.
    if (Result<void> ok = transformMesh(base, Transform3x4{1, 0, 0, -0.5f * (lo.x + hi.x), 0, 1, 0,
                                                           -0.5f * (lo.y + hi.y), 0, 0, 1, -0.5f * (lo.z + hi.z)});
        !ok) {
        return ok.error();
    }
    std::vector<HostMesh> meshes;
    // Neighbours step apart on a circle of `count` copies (two copies: a segment).
    const double step = step_fraction * size;
    const double radius = count > 2 ? step / (2 * std::sin(std::numbers::pi / count)) : 0.5 * step;
    for (std::uint32_t i = 0; i < count; ++i) {
        const double a = 2 * std::numbers::pi * i / count;
        HostMesh m = base;
        m.name = base.name + std::to_string(i);
        const Float3 t{static_cast<float>(radius * std::cos(a)), 0.05f * size * static_cast<float>(i % 2),
                       static_cast<float>(radius * std::sin(a))};
        if (Result<void> ok = transformMesh(m, rotationTranslation(0.1, 1, 0.05, a + 0.5, t)); !ok) return ok.error();
        meshes.push_back(std::move(m));
    }
    return meshes;
}

// A packaged mesh and a copy of it turned by `angle` radians about a tilted axis through
// its centre: the two surfaces cross each other all over (a worst case for any method).
Result<std::vector<HostMesh>> meshTwin(const std::string& path, double angle) {
    Result<std::vector<HostMesh>> one = meshRing(path, 1, 0);
    if (!one) return one.error();
    HostMesh twin = one->front();
    twin.name += "_twin";
    if (Result<void> ok = transformMesh(twin, rotationTranslation(0.3, 1, 0.2, angle, {0, 0, 0})); !ok)
        return ok.error();
    one->push_back(std::move(twin));
    return one;
}

// Two unit spheres that overlap and wobble: every vertex moves every frame. The radius
// at direction d is 1 + 0.04 sin(7 theta + 0.4 f) sin(5 phi + 0.3 f + object), and the
// centres swing by +-0.05 along x, so the contact region changes from frame to frame.
Result<std::vector<HostMesh>> wobblingPair(std::uint32_t segments, std::uint32_t rings, int frame) {
    Result<HostMesh> base = uvSphere(1.0f, segments, rings);
    if (!base) return base.error();
    std::vector<HostMesh> meshes;
    for (std::uint32_t o = 0; o < 2; ++o) {
        HostMesh m = *base;
        m.name = "wobbling_sphere" + std::to_string(o);
        const double f = frame;
        const double cx = (o == 0 ? -0.85 : 0.85) + (o == 0 ? 1 : -1) * 0.05 * std::sin(0.5 * f);
        for (Float3& p : m.positions) {
            const double theta = std::acos(std::clamp(static_cast<double>(p.z), -1.0, 1.0));
            const double phi = std::atan2(static_cast<double>(p.y), static_cast<double>(p.x));
            const double r = 1 + 0.04 * std::sin(7 * theta + 0.4 * f) * std::sin(5 * phi + 0.3 * f + o);
            p = {static_cast<float>(cx + r * p.x), static_cast<float>(r * p.y), static_cast<float>(r * p.z)};
        }
        meshes.push_back(std::move(m));
    }
    return meshes;
}

}  // namespace

namespace {

// World-space meshes as bench objects (identity transforms, every one self-colliding).
Result<std::vector<BenchObject>> asObjects(Result<std::vector<HostMesh>> meshes) {
    if (!meshes) return meshes.error();
    std::vector<BenchObject> out;
    for (HostMesh& m : *meshes) out.push_back(BenchObject{.mesh = std::move(m)});
    return out;
}

// The first sweep's scenes (all in the tuning set: the defaults were chosen on them). The
// names give the triangle counts at scale 1.
std::vector<SceneSpec> issue7Scenes(const std::string& data, double scale) {
    const auto n = [scale](std::uint32_t count) { return scaledCount(count, scale, 2); };
    const std::string bunny = data + "/bunny00.off";
    const auto rigid = [](std::string name, std::string what, auto build) {
        return SceneSpec{std::move(name), Motion::Rigid, SceneSet::Tuning, 1, std::move(what),
                         [build](int) { return asObjects(build()); }};
    };
    const auto deforming = [n](std::string name, std::string what, std::uint32_t segments, std::uint32_t rings) {
        return SceneSpec{std::move(name), Motion::Deforming, SceneSet::Tuning, 6, std::move(what),
                         [segments = n(segments), rings = n(rings)](int f) { return asObjects(wobblingPair(segments, rings, f)); }};
    };
    return {
        rigid("spheres-8x10K", "8 overlapping spheres of 9,940 triangles", [n] { return sphereGrid(8, n(70), n(72)); }),
        rigid("bunnies-2x75K", "two overlapping bunny00.off (75,408 triangles each)", [bunny] { return meshRing(bunny, 2); }),
        rigid("bunnies-2x75K-deep", "two bunny00.off overlapping by 85% of their size", [bunny] { return meshRing(bunny, 2, 0.15); }),
        rigid("bunnies-2x75K-twin", "bunny00.off and a copy turned by 3 degrees: surfaces cross all over",
              [bunny] { return meshTwin(bunny, 3 * std::numbers::pi / 180); }),
        rigid("spheres-60x10K", "60 overlapping spheres of 9,940 triangles (596K)", [n] { return sphereGrid(60, n(70), n(72)); }),
        rigid("spheres-60x10K-dense", "60 spheres of 9,940 triangles, 1.25 apart (radius 1)", [n] { return sphereGrid(60, n(70), n(72), 1.25f); }),
        rigid("spheres-100x10K", "100 overlapping spheres of 9,940 triangles (994K)", [n] { return sphereGrid(100, n(70), n(72)); }),
        rigid("bunnies-14x75K", "14 bunny00.off in an overlapping ring (1.06M)", [bunny] { return meshRing(bunny, 14); }),
        rigid("spheres-2x640K", "two overlapping spheres of 640,000 triangles (1.28M)", [n] { return sphereGrid(2, n(640), n(501)); }),
        deforming("deform-pair-100K", "two wobbling spheres of 49,920 triangles, all vertices move", 160, 157),
        deforming("deform-pair-1M", "two wobbling spheres of 500,000 triangles, all vertices move", 500, 501),
    };
}

}  // namespace

std::vector<SceneSpec> allScenes(const std::string& data, double scale) {
    std::vector<SceneSpec> all = issue7Scenes(data, scale);
    for (auto part : {foldScenes(scale), drapeScenes(scale), twistedScenes(scale), pileScenes(data, scale), deepOverlapScenes(data, scale),
                      deformingPairScenes(data, scale), ballClothScenes(scale), mixedScenes(scale), touchingScenes(scale)})
        for (SceneSpec& s : part) all.push_back(std::move(s));
    return all;
}

}  // namespace vkcollide::bench
