// Object-sampling benchmark: raster vs compute backend on generated scenes (grids of
// spheres or tori, several layers deep along the view) and packaged meshes, GPU
// timestamps per pass. Prints one Markdown table row per (scene, mode, backend) and checks
// that both backends give the same collision rays and records.
//
//   vkcollide_bench_sampling [--quick] [--reps R] [--mesh PATH] [--only NAME] [--sweep]
//
//   --quick   small scenes (for lavapipe)
//   --reps    timed runs per configuration after one warm-up (median reported; default 5);
//             the warm-up also sizes the compute backend's fragment lists (steady state)
//   --mesh    a packaged mesh (e.g. data/cgal/bunny00.off): alone and as a 4x4 grid
//   --only    run the scenes whose name contains NAME
//   --sweep   also time the compute backend's tuning (small_box, drawing per step, depth plane)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "broad/peeling/sampling/backend_choice.hpp"
#include "mesh/mesh_upload.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using passes::BroadPhaseResult;
using passes::BroadPhaseSettings;
using passes::SamplingBackend;

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "vkcollide_bench_sampling: %s\n", what.c_str());
    return 1;
}

struct SceneDesc {
    std::string name;
    std::uint32_t resolution = 1024;
    std::vector<HostMesh> meshes;  // one per layer of objects: few draws and dispatches
};

// `grid` x `grid` copies of `base` (unit-ish size, centred) per layer, `layers` layers
// along +z, each copy turned by a pseudo-random rotation when `tumble`.
SceneDesc gridScene(std::string name, const HostMesh& base, std::uint32_t grid, std::uint32_t layers, float spacing,
                    float layer_gap, bool tumble, std::uint32_t resolution) {
    SceneDesc s;
    s.name = std::move(name);
    s.resolution = resolution;
    std::uint32_t seed = 12345;
    auto rnd = [&] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / float(1u << 24);
    };
    for (std::uint32_t l = 0; l < layers; ++l) {
        HostMesh m;
        m.name = s.name + "-layer" + std::to_string(l);
        m.positions.reserve(base.positions.size() * grid * grid);
        m.indices.reserve(base.indices.size() * grid * grid);
        for (std::uint32_t gy = 0; gy < grid; ++gy)
            for (std::uint32_t gx = 0; gx < grid; ++gx) {
                float r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
                if (tumble) {
                    // Rotation from a random unit quaternion.
                    float q[4] = {rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f};
                    float n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
                    for (float& v : q) v /= n;
                    const float w = q[0], x = q[1], y = q[2], z = q[3];
                    float rr[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                                   2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                                   2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
                    std::copy(rr, rr + 9, r);
                }
                const Float3 t{(float(gx) - 0.5f * float(grid - 1)) * spacing + 0.013f * float(l),
                               (float(gy) - 0.5f * float(grid - 1)) * spacing + 0.007f * float(l), float(l) * layer_gap};
                const auto first = static_cast<std::uint32_t>(m.positions.size());
                for (const Float3& p : base.positions)
                    m.positions.push_back({r[0] * p.x + r[1] * p.y + r[2] * p.z + t.x, r[3] * p.x + r[4] * p.y + r[5] * p.z + t.y,
                                           r[6] * p.x + r[7] * p.y + r[8] * p.z + t.z});
                for (std::uint32_t i : base.indices) m.indices.push_back(first + i);
            }
        s.meshes.push_back(std::move(m));
    }
    return s;
}

// Centred and scaled to a unit bounding radius.
HostMesh normalised(HostMesh m) {
    Float3 lo = m.positions[0], hi = lo;
    for (const Float3& p : m.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Float3 c{0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), 0.5f * (lo.z + hi.z)};
    const float r = 0.5f * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    for (Float3& p : m.positions) p = {(p.x - c.x) / r, (p.y - c.y) / r, (p.z - c.z) / r};
    return m;
}

std::size_t triangleCount(const SceneDesc& s) {
    std::size_t t = 0;
    for (const auto& m : s.meshes) t += m.triangleCount();
    return t;
}

struct Timing {
    double setup = 0, count = 0, gather = 0, peel = 0, classify = 0, sampling = 0, wall = 0;
    std::vector<double> steps;  // count pass, then each peel pass
};

Timing timingOf(const BroadPhaseResult& r) {
    Timing t;
    t.sampling = r.sampling_ms;
    for (const auto& p : r.passes) {
        if (p.name == "csample-setup") t.setup += p.gpu_ms;
        else if (p.name == "csample-gather") t.gather += p.gpu_ms;
        else if (p.name == "depth-complexity") t.count += p.gpu_ms, t.steps.insert(t.steps.begin(), p.gpu_ms);
        else if (p.name.rfind("peel[", 0) == 0) t.peel += p.gpu_ms, t.steps.push_back(p.gpu_ms);
        else if (p.name.rfind("classify[", 0) == 0) t.classify += p.gpu_ms;
    }
    return t;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

struct Measured {
    BroadPhaseResult last;
    Timing median;
};

Result<Measured> measure(passes::BroadPhase& bp, const std::vector<passes::GpuMesh>& meshes, const BroadPhaseSettings& s,
                         int reps) {
    auto warm = bp.run(meshes, s);
    if (!warm) return warm.error();
    std::vector<Timing> runs;
    Measured m;
    for (int i = 0; i < reps; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        auto r = bp.run(meshes, s);
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (!r) return r.error();
        runs.push_back(timingOf(*r));
        runs.back().wall = wall;
        if (i + 1 == reps) m.last = std::move(*r);
    }
    auto pick = [&](double Timing::*field) {
        std::vector<double> v;
        for (const auto& t : runs) v.push_back(t.*field);
        return median(v);
    };
    m.median.setup = pick(&Timing::setup);
    m.median.count = pick(&Timing::count);
    m.median.gather = pick(&Timing::gather);
    m.median.peel = pick(&Timing::peel);
    m.median.classify = pick(&Timing::classify);
    m.median.sampling = pick(&Timing::sampling);
    m.median.wall = pick(&Timing::wall);
    for (std::size_t k = 0; k < runs[0].steps.size(); ++k) {
        std::vector<double> v;
        for (const auto& t : runs) v.push_back(k < t.steps.size() ? t.steps[k] : 0.0);
        m.median.steps.push_back(median(v));
    }
    return m;
}

std::string stepsText(const std::vector<double>& steps) {
    std::string out;
    char buf[32];
    for (std::size_t i = 0; i < steps.size(); ++i) {
        std::snprintf(buf, sizeof(buf), "%s%.3f", i ? " " : "", steps[i]);
        out += buf;
    }
    return out;
}

void printRow(const SceneDesc& scene, std::size_t tris, const BroadPhaseSettings& s, const Measured& m, const char* label,
              const std::string& same) {
    const auto& r = m.last;
    const double fpt = double(r.fragments) / double(std::max<std::size_t>(tris, 1));
    std::printf("| %s | %zu | %u | %.1f | %u | %s | %s | %.3f | %.3f | %.3f | %.3f | %.3f | **%.3f** | %s | %.1f | %s |\n",
                scene.name.c_str(), tris, s.resolution, fpt, r.depth_complexity, s.dual ? "dual" : "single", label, m.median.setup,
                m.median.count, m.median.gather, m.median.peel, m.median.classify, m.median.sampling, stepsText(m.median.steps).c_str(),
                m.median.wall, same.c_str());
    std::fflush(stdout);
}

std::string compareResults(const BroadPhaseResult& a, const BroadPhaseResult& b) {
    std::size_t differ = 0;
    for (std::size_t i = 0; i < std::min(a.ray_image.size(), b.ray_image.size()); ++i) differ += a.ray_image[i] != b.ray_image[i];
    const bool records = a.records.size() == b.records.size() &&
                         std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(CandidateTriangle)) == 0;
    char buf[96];
    if (differ == 0 && records && a.fragments == b.fragments) return "yes";
    std::snprintf(buf, sizeof(buf), "NO: %zu rays, records %s, fragments %s", differ, records ? "same" : "differ",
                  a.fragments == b.fragments ? "same" : "differ");
    return buf;
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false, sweep = false;
    int reps = 5;
    std::string mesh_path, only;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--quick") quick = true;
        else if (a == "--sweep") sweep = true;
        else if (a == "--reps" && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--mesh" && i + 1 < argc) mesh_path = argv[++i];
        else if (a == "--only" && i + 1 < argc) only = argv[++i];
        else return fail("unknown argument " + a);
    }
    auto ctx = Context::create();
    if (!ctx) return fail(ctx.error().message());
    vk::Device& dev = ContextAccess::device(**ctx);
    std::printf("device: %s (%s), %s; sub-pixel bits %u\n\n", dev.info.name.c_str(), toString(dev.info.type), dev.info.driver.c_str(),
                dev.properties.limits.subPixelPrecisionBits);

    // Spheres: 2 * seg * (rings - 1) triangles each; grids of 16 x 16 x 4 layers give depth
    // complexity 8 and triangles from ~1.5 to ~250 px at 1024^2.
    struct Spec {
        const char* name;
        std::uint32_t seg, rings, grid, layers, resolution;
    };
    std::vector<SceneDesc> scenes;
    auto sphere = [](std::uint32_t seg, std::uint32_t rings) { return *uvSphere(1.0f, seg, rings); };
    if (quick) {
        for (Spec sp : {Spec{"spheres-4x4x4", 16, 8, 4, 4, 256}, Spec{"spheres-big", 6, 3, 4, 4, 256}})
            scenes.push_back(gridScene(sp.name, sphere(sp.seg, sp.rings), sp.grid, sp.layers, 2.1f, 2.5f, false, sp.resolution));
        scenes.push_back(gridScene("tori-4x4x2", *torus(1.0f, 0.35f, 24, 10), 4, 2, 2.7f, 2.5f, true, 256));
        scenes.push_back(gridScene("boxes-2x2x2", *box({0.7f, 0.7f, 0.7f}, 1), 2, 2, 2.1f, 2.5f, true, 256));
    } else {
        for (Spec sp : {Spec{"spheres-1M", 32, 16, 16, 4, 1024}, Spec{"spheres-4M", 64, 32, 16, 4, 1024},
                        Spec{"spheres-230K", 16, 8, 16, 4, 1024}, Spec{"spheres-100K", 10, 6, 16, 4, 1024},
                        Spec{"spheres-25K", 6, 3, 16, 4, 1024}, Spec{"spheres-4M@2048", 64, 32, 16, 4, 2048},
                        Spec{"spheres-1M@4096", 32, 16, 16, 4, 4096}})
            scenes.push_back(gridScene(sp.name, sphere(sp.seg, sp.rings), sp.grid, sp.layers, 2.1f, 2.5f, false, sp.resolution));
        scenes.push_back(gridScene("tori-1M", *torus(1.0f, 0.35f, 50, 20), 16, 2, 2.7f, 2.5f, true, 1024));
        // Few huge triangles: 12-triangle boxes, thousands of pixels each.
        scenes.push_back(gridScene("boxes-3K", *box({0.7f, 0.7f, 0.7f}, 1), 8, 4, 2.1f, 2.5f, true, 1024));
    }
    if (!mesh_path.empty()) {
        auto read = readMeshFile(mesh_path);
        if (!read) return fail(read.error().message());
        HostMesh base = normalised(std::move((*read)[0]));
        std::string stem = mesh_path.substr(mesh_path.find_last_of('/') + 1);
        scenes.push_back(gridScene(stem, base, 1, 1, 2.1f, 2.5f, false, 1024));
        scenes.push_back(gridScene(stem + "-4x4", base, 4, 1, 2.1f, 2.5f, true, 1024));
    }

    auto bp = passes::BroadPhase::create(dev, passes::PeelingMethod::create);
    if (!bp) return fail(bp.error().message());
    std::vector<std::string> details;
    std::printf("| scene | triangles | N | px/tri | depth cx | mode | backend | setup ms | count ms | gather ms | peel ms | classify ms | sampling ms | per pass: count, peel[i] (ms) | run wall ms | same rays + records |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const SceneDesc& scene : scenes) {
        if (!only.empty() && scene.name.find(only) == std::string::npos) continue;
        std::vector<const HostMesh*> ptrs;
        for (const auto& m : scene.meshes) ptrs.push_back(&m);
        auto up = passes::uploadMeshes(dev, ptrs);
        if (!up) return fail(up.error().message());
        const std::size_t tris = triangleCount(scene);
        for (bool dual : {false, true}) {
            BroadPhaseSettings s;
            s.resolution = scene.resolution;
            s.dual = dual;
            s.keep_ray_image = true;
            s.backend = SamplingBackend::Raster;
            auto raster = measure(**bp, up->meshes, s, reps);
            if (!raster) return fail(scene.name + ": " + raster.error().message());
            printRow(scene, tris, s, *raster, "raster", "");
            s.backend = SamplingBackend::Compute;
            auto compute = measure(**bp, up->meshes, s, reps);
            if (!compute) return fail(scene.name + ": " + compute.error().message());
            printRow(scene, tris, s, *compute, "compute", compareResults(raster->last, compute->last));
            if (details.size() < 4)  // every pass of the first scene's last runs, for the record
                for (const auto* m : {&*raster, &*compute}) {
                    std::string line = scene.name + (dual ? " dual " : " single ") + toString(m->last.backend) + ":";
                    char buf[64];
                    for (const auto& p : m->last.passes) {
                        std::snprintf(buf, sizeof(buf), " %s %.3f;", p.name.c_str(), p.gpu_ms);
                        line += buf;
                    }
                    details.push_back(line);
                }
            if (!sweep || !dual) continue;
            struct Variant {
                const char* label;
                passes::ComputeSamplingTuning tuning;
            };
            using Plane = passes::ComputeSamplingTuning::DepthPlane;
            std::vector<Variant> variants = {{"compute box 64", {.small_box = 64}}, {"compute box 1024", {.small_box = 1024}},
                                             {"compute draw/step", {.list_budget_bytes = 0}},
                                             {"compute draw/step unfused", {.list_budget_bytes = 0, .fuse_first_step = false}},
                                             {"compute z snapped", {.depth_plane = Plane::Snapped}},
                                             {"compute z unsnapped", {.depth_plane = Plane::Unsnapped}}};
            for (const Variant& v : variants) {
                s.compute = v.tuning;
                auto t = measure(**bp, up->meshes, s, reps);
                if (!t) return fail(t.error().message());
                printRow(scene, tris, s, *t, v.label, compareResults(raster->last, t->last));
            }
        }
    }
    std::printf("\nPer pass (ms), last run:\n");
    for (const auto& d : details) std::printf("- %s\n", d.c_str());
    {
        // What Auto picks here, for the record.
        const auto choice = passes::chooseSamplingBackend(dev.properties, passes::computeSamplingSupported(dev), SamplingBackend::Auto, 1024, 1'000'000, 6.0);
        std::printf("\nAuto on this device (1M triangles of 6 px at 1024^2): %s (%s)\n", toString(choice.backend), choice.reason.c_str());
    }
    return 0;
}
