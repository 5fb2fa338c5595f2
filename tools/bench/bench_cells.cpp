// vkcollide_bench_cells: the cell stage (src/broad/cells) alone on generated scenes
// of the bench set's kinds. Not a test: a program that prints one table.
//
//   vkcollide_bench_cells [--scenes a,b,...] [--scale S] [--factors 0.5,1,2] [--repeat K]
//                         [--frames F] [--no-reference] [--list]
//
// For each scene and each resolution factor f (cells per side = f * projected extent /
// mean edge length: f = 1 is about one cell per typical edge) it runs one warm-up (buffers
// grow to what the scene needs) and K timed runs, and prints: entries per triangle, the
// deepest cell and the cells deeper than kCellsSmallCell, the pairs of footprints sharing
// a cell (what the sweep compares), candidates, the overlapping
// pairs the sweep left out as neighbours, the percentages of candidates the pair pass
// dropped as duplicates and as proved disjoint, survivors, the exact pairs and the recall against them
// (tests/support/exact_reference.cpp), candidates per true pair, the median GPU time (first
// pass start to last pass end, from the graph's timestamps), the median wall time of
// CellStage::run (parameters, graph, submission, wait, readback, sorting: all host work of
// a detection) and the mean time of each pass. Meshes live in device-local memory;
// deforming scenes get new positions every frame (uploaded untimed, one run per frame;
// counts are per frame).
// The projection direction is the axis with the largest projected triangle area.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "broad/cells/cell_stage.hpp"
#include "support/exact_reference.hpp"
#include "vk/device.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;

namespace {

using Clock = std::chrono::steady_clock;

struct Scene {
    std::vector<HostMesh> meshes;  // world space
    std::vector<std::uint8_t> self;
};

struct SceneSpec {
    std::string name, what;
    bool deforming = false;
    std::function<Result<Scene>(double scale, int frame)> build;
};

double hash01(std::uint32_t i) {
    std::uint32_t h = i * 2654435761u;
    h ^= h >> 16;
    h *= 2246822519u;
    h ^= h >> 13;
    return double(h) / 4294967296.0;
}

Transform3x4 rotation(double ax, double ay, double az, double angle, Float3 t) {
    const double n = std::sqrt(ax * ax + ay * ay + az * az);
    const double x = ax / n, y = ay / n, z = az / n, c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    const auto f = [](double v) { return float(v); };
    return {f(c + x * x * k), f(x * y * k - z * s), f(x * z * k + y * s), t.x, f(y * x * k + z * s), f(c + y * y * k),
            f(y * z * k - x * s), t.y, f(z * x * k - y * s), f(z * y * k + x * s), f(c + z * z * k), t.z};
}

// A sphere of about `triangles` triangles (segments = 4 * rings).
Result<HostMesh> sphereOf(double triangles, float radius) {
    const auto rings = std::max<std::uint32_t>(3, std::uint32_t(std::sqrt(triangles / 8.0)));
    return uvSphere(radius, 4 * rings, rings + 1);
}

Result<Scene> deepOverlap(double scale, int) {
    Scene s;
    for (int o = 0; o < 2; ++o) {
        auto m = sphereOf(1.28e6 * scale, 1.0f);
        if (!m) return m.error();
        if (o == 1)
            if (auto ok = transformMesh(*m, rotation(0.3, 1, 0.2, 0.4, {0.5f, 0.2f, 0.1f})); !ok) return ok.error();
        s.meshes.push_back(std::move(*m));
        s.self.push_back(0);
    }
    return s;
}

// 60 rigid meshes of six shapes, about 9.9K triangles each at scale 1, dropped into a
// 4 x 4 x 2 box so that neighbours overlap.
Result<Scene> pile(double scale, int) {
    Scene s;
    const double per = 9.9e3 * scale;
    const auto ring = std::max<std::uint32_t>(3, std::uint32_t(std::sqrt(per / 2.0)));
    for (std::uint32_t i = 0; i < 60; ++i) {
        Result<HostMesh> m = Error(ErrorCode::InvalidArgument, "shape");
        switch (i % 6) {
            case 0: m = sphereOf(per, 0.5f); break;
            case 1: m = torus(0.5f, 0.18f, 2 * ring, ring / 2 + 3); break;
            case 2: m = box({0.4f, 0.3f, 0.25f}, std::max<std::uint32_t>(1, std::uint32_t(std::sqrt(per / 12.0)))); break;
            case 3: m = twistedTube(0.8f, 0.12f, 2 * ring, ring / 2 + 3, 1.0f); break;
            case 4: m = sphereOf(per, 0.35f); break;
            default: m = torus(0.35f, 0.12f, 2 * ring, ring / 2 + 3); break;
        }
        if (!m) return m.error();
        const Float3 t{float(4 * hash01(3 * i)), float(4 * hash01(3 * i + 1)), float(2 * hash01(3 * i + 2))};
        if (auto ok = transformMesh(*m, rotation(hash01(5 * i) - 0.5, hash01(5 * i + 1) - 0.5, hash01(5 * i + 2), 2 * std::numbers::pi * hash01(5 * i + 3), t)); !ok)
            return ok.error();
        s.meshes.push_back(std::move(*m));
        s.self.push_back(0);
    }
    return s;
}

// Two 50K-triangle spheres (at scale 1) that wobble, approach, penetrate and separate.
Result<Scene> deformingPair(double scale, int frame) {
    Scene s;
    const double f = frame;
    for (int o = 0; o < 2; ++o) {
        auto m = sphereOf(5e4 * scale, 1.0f);
        if (!m) return m.error();
        const double cx = (o == 0 ? -1 : 1) * (1.1 - 0.3 * std::sin(0.2 * f));
        for (Float3& p : m->positions) {
            const double theta = std::acos(std::clamp(double(p.z), -1.0, 1.0)), phi = std::atan2(double(p.y), double(p.x));
            const double r = 1 + 0.04 * std::sin(7 * theta + 0.4 * f) * std::sin(5 * phi + 0.3 * f + o);
            p = {float(cx + r * p.x), float(r * p.y), float(r * p.z)};
        }
        s.meshes.push_back(std::move(*m));
        s.self.push_back(0);
    }
    return s;
}

Result<Scene> twisted(double scale, int) {
    const auto segs = std::max<std::uint32_t>(8, std::uint32_t(std::sqrt(52e3 * scale / 2 * 4)));
    auto m = twistedTube(1.0f, 0.2f, segs, std::max<std::uint32_t>(3, segs / 4), 1.5f);
    if (!m) return m.error();
    return Scene{{std::move(*m)}, {1}};
}

Result<Scene> clothFold(double scale, int) {
    const auto n = std::max<std::uint32_t>(2, std::uint32_t(std::sqrt(24e3 * scale / 2)));
    ClothOptions options;
    options.sag = 0.2f;
    options.fold_angle = 3.3f;  // past flat: the flap passes through the other half
    auto m = clothGrid(2.0f, 2.0f, n, n, options);
    if (!m) return m.error();
    return Scene{{std::move(*m)}, {1}};
}

std::vector<SceneSpec> allScenes() {
    return {{"deep-overlap", "two 1.28M-triangle spheres overlapping deeply", false, deepOverlap},
            {"pile-60", "60 rigid meshes of six shapes, about 593K triangles", false, pile},
            {"deforming-100k", "two wobbling 50K spheres, approaching and penetrating", true, deformingPair},
            {"twisted-52k", "a tube through itself, self-collision", false, twisted},
            {"cloth-fold-24k", "a cloth folded through itself, self-collision", false, clothFold}};
}

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

// Device-local copies of the meshes (positions, indices), written through a staging copy.
struct GpuScene {
    std::vector<vk::Buffer> buffers;
    std::vector<gpu::ObjectGpu> objects;
    std::size_t triangles = 0;
};

Result<void> copyToDevice(vk::Device& device, graph::Executor& executor, const void* data, VkDeviceSize bytes, vk::Buffer& dst) {
    auto staging = vk::Buffer::create(device, bytes, 0, vk::MemoryKind::Upload, "bench-staging");
    if (!staging) return staging.error();
    std::memcpy(staging->mapped(), data, bytes);
    staging->flush();
    graph::Graph g;
    const auto s = g.importBuffer("staging", *staging), d = g.importBuffer("dst", dst);
    const VkBuffer from = staging->handle(), to = dst.handle();
    g.addPass("upload", graph::PassKind::Transfer).use(s, graph::Use::TransferSrc).use(d, graph::Use::TransferDst).record(
        [from, to, bytes](graph::PassContext& pc) {
            VkBufferCopy copy{0, 0, bytes};
            pc.fns().vkCmdCopyBuffer(pc.cmd, from, to, 1, &copy);
        });
    auto ran = executor.run(g);
    if (!ran) return ran.error();
    return {};
}

Result<GpuScene> upload(vk::Device& device, graph::Executor& executor, const Scene& scene, GpuScene* reuse) {
    GpuScene out;
    std::uint32_t base = 0;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const HostMesh& m = scene.meshes[i];
        vk::Buffer vb, ib;
        if (reuse) {
            vb = std::move(reuse->buffers[2 * i]);  // same topology every frame: new positions only
            ib = std::move(reuse->buffers[2 * i + 1]);
        } else {
            auto v = vk::Buffer::create(device, m.positions.size() * 12, 0, vk::MemoryKind::DeviceLocal, "bench-vertices");
            auto x = vk::Buffer::create(device, m.indices.size() * 4, 0, vk::MemoryKind::DeviceLocal, "bench-indices");
            if (!v) return v.error();
            if (!x) return x.error();
            vb = std::move(*v);
            ib = std::move(*x);
            if (auto ok = copyToDevice(device, executor, m.indices.data(), m.indices.size() * 4, ib); !ok) return ok.error();
        }
        if (auto ok = copyToDevice(device, executor, m.positions.data(), m.positions.size() * 12, vb); !ok) return ok.error();
        gpu::ObjectGpu o{};
        o.vertices = vb.address();
        o.indices = ib.address();
        o.vertex_stride = 12;
        o.vertex_count = std::uint32_t(m.positions.size());
        o.triangle_count = std::uint32_t(m.triangleCount());
        o.triangle_base = base;
        o.model[0] = {1, 0, 0, 0};
        o.model[1] = {0, 1, 0, 0};
        o.model[2] = {0, 0, 1, 0};
        base += o.triangle_count;
        out.objects.push_back(o);
        out.buffers.push_back(std::move(vb));
        out.buffers.push_back(std::move(ib));
    }
    out.triangles = base;
    return out;
}

struct Geometry {
    std::array<double, 3> direction{0, 0, 1};
    char axis = 'z';
    double edge = 0, extent = 0;
    gpu::Projection projection{};
};

// Direction: the axis with the largest projected triangle area; extent: the scene box
// across that view; edge: the mean edge length.
Geometry measure(const Scene& scene) {
    double area[3] = {0, 0, 0}, edges = 0, count = 0;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const HostMesh& m : scene.meshes) {
        for (const Float3& p : m.positions) {
            const double c[3] = {p.x, p.y, p.z};
            for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
        }
        for (std::size_t t = 0; t < m.triangleCount(); ++t) {
            const Float3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]], &c = m.positions[m.indices[3 * t + 2]];
            const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
            const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
            area[0] += std::fabs(e1[1] * e2[2] - e1[2] * e2[1]);
            area[1] += std::fabs(e1[2] * e2[0] - e1[0] * e2[2]);
            area[2] += std::fabs(e1[0] * e2[1] - e1[1] * e2[0]);
            auto len = [](const Float3& p, const Float3& q) {
                return std::sqrt(double(p.x - q.x) * (p.x - q.x) + double(p.y - q.y) * (p.y - q.y) + double(p.z - q.z) * (p.z - q.z));
            };
            edges += len(a, b) + len(b, c) + len(c, a);
            count += 3;
        }
    }
    Geometry g;
    const int d = int(std::max_element(area, area + 3) - area);
    g.axis = "xyz"[d];
    g.direction = {0, 0, 0};
    g.direction[d] = 1;
    const int u = (d + 1) % 3, v = (d + 2) % 3;
    g.edge = count > 0 ? edges / count : 1;
    const double size = std::max(hi[u] - lo[u], hi[v] - lo[v]), depth = std::max(hi[d] - lo[d], 1e-30);
    g.extent = size;
    auto row = [&](int axis, double s, double origin) {
        float r[4] = {0, 0, 0, float(-origin / s)};
        r[axis] = float(1 / s);
        return gpu::vec4{r[0], r[1], r[2], r[3]};
    };
    g.projection.row[0] = row(u, size, lo[u]);
    g.projection.row[1] = row(v, size, lo[v]);
    g.projection.row[2] = row(d, depth, lo[d]);
    return g;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> wanted;
    std::vector<double> factors = {0.5, 1, 2};
    double scale = 1;
    int repeat = 5, frames = 8;
    bool reference = true;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--scenes") wanted = splitList(next());
        else if (a == "--scale") scale = std::stod(next());
        else if (a == "--factors") {
            factors.clear();
            for (const auto& f : splitList(next())) factors.push_back(std::stod(f));
        } else if (a == "--repeat") repeat = std::max(1, std::stoi(next()));
        else if (a == "--frames") frames = std::max(1, std::stoi(next()));
        else if (a == "--no-reference") reference = false;
        else if (a == "--list") {
            for (const auto& s : allScenes()) std::printf("%-16s %s\n", s.name.c_str(), s.what.c_str());
            return 0;
        } else {
            std::fprintf(stderr, "usage: %s [--scenes a,b] [--scale S] [--factors 0.5,1,2] [--repeat K] [--frames F] [--no-reference] [--list]\n", argv[0]);
            return 2;
        }
    }
    auto ctx = Context::create();
    if (!ctx) {
        std::fprintf(stderr, "%s\n", ctx.error().message().c_str());
        return 1;
    }
    vk::Device& device = ContextAccess::device(**ctx);
    auto stage = passes::CellStage::create(device);
    if (!stage) {
        std::fprintf(stderr, "%s\n", stage.error().message().c_str());
        return 1;
    }
    graph::Executor executor(device);
    std::printf("device: %s, filter %s, scale %g, %d timed runs (deforming: %d frames)\n", device.info.name.c_str(),
                (*stage)->filterSupported() ? "on (shaderFloat64)" : "off", scale, repeat, frames);
    std::printf("%-15s %9s %5s %5s %6s %11s %6s %9s %7s %11s %10s %9s %5s %5s %9s %8s %8s %7s %8s %8s | %6s %6s %6s %6s %6s %6s\n", "scene", "tris", "dir",
                "f", "N", "entries", "e/tri", "max_cell", "deep", "compared", "cands", "nbrs", "dup%", "flt%", "survive", "exact", "recall", "c/pair", "gpu_ms", "wall_ms",
                "setup", "big", "scan", "fill", "sweep", "pairs");
    for (const SceneSpec& spec : allScenes()) {
        if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), spec.name) == wanted.end()) continue;
        const int frame_count = spec.deforming ? frames : 1;
        struct Row {
            std::map<std::string, double> pass_total;
            std::vector<double> gpu_ms, wall_ms;
            passes::CellStageStats stats{};  // summed over frames
            std::size_t found = 0;
            std::uint32_t n = 0;
            bool failed = false;
        };
        std::vector<Row> rows(factors.size());
        std::size_t exact = 0, tris = 0;
        char axis = '?';
        GpuScene gpu_scene;
        for (int frame = 0; frame < frame_count; ++frame) {
            auto scene = spec.build(scale, frame);
            if (!scene) {
                std::fprintf(stderr, "%s: %s\n", spec.name.c_str(), scene.error().message().c_str());
                return 1;
            }
            const Geometry geo = measure(*scene);
            axis = geo.axis;
            // Deforming frames: same topology, new positions into the same buffers (untimed).
            auto up = upload(device, executor, *scene, frame > 0 ? &gpu_scene : nullptr);
            if (!up) {
                std::fprintf(stderr, "%s\n", up.error().message().c_str());
                return 1;
            }
            gpu_scene = std::move(*up);
            tris = gpu_scene.triangles;
            std::vector<TrianglePair> ref;
            if (reference) {
                std::vector<test::ReferenceObject> objs;
                for (std::size_t i = 0; i < scene->meshes.size(); ++i)
                    objs.push_back({&scene->meshes[i], test::kIdentityTransform, scene->self[i] != 0});
                auto computed = test::computeReferencePairs(objs);
                if (!computed) {
                    std::fprintf(stderr, "reference: %s\n", computed.error().message().c_str());
                    return 1;
                }
                ref = std::move(*computed);
                exact += ref.size();
            }
            for (std::size_t fi = 0; fi < factors.size(); ++fi) {
                Row& row = rows[fi];
                if (row.failed) continue;
                row.n = std::uint32_t(std::clamp(std::lround(factors[fi] * geo.extent / geo.edge), 1l, long(gpu::kCellsMaxResolution)));
                passes::CellStageInput in;
                in.objects = gpu_scene.objects;
                in.projection = geo.projection;
                in.resolution = row.n;
                in.self_collision = scene->self;
                (void)(*stage)->run(executor, in);  // warm-up: buffers grow to this scene and resolution
                const int runs = spec.deforming ? 1 : repeat;
                passes::CellStageResult result;
                for (int r = 0; r < runs; ++r) {
                    const auto t0 = Clock::now();
                    auto res = (*stage)->run(executor, in);
                    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                    if (!res) {
                        std::fprintf(stderr, "%s N=%u: %s\n", spec.name.c_str(), row.n, res.error().message().c_str());
                        row.failed = true;
                        break;
                    }
                    row.wall_ms.push_back(wall);
                    row.gpu_ms.push_back(res->gpu_ms);
                    for (const auto& p : res->passes) {
                        std::string key = p.name.substr(std::min<std::size_t>(p.name.size(), 6));  // drop "cells-"
                        if (key == "count-big") key = "big";
                        if (key == "pair-args") key = "pairs";
                        row.pass_total[key] += p.gpu_ms;
                    }
                    result = std::move(*res);
                }
                if (row.failed) continue;
                const passes::CellStageStats& s = result.stats;
                row.stats.entries += s.entries;
                row.stats.max_cell = std::max(row.stats.max_cell, s.max_cell);
                row.stats.deep_cells += s.deep_cells;
                row.stats.candidates += s.candidates;
                row.stats.comparisons += s.comparisons;
                row.stats.survivors += s.survivors;
                row.stats.neighbours += s.neighbours;
                row.stats.duplicates += s.duplicates;
                row.stats.filtered += s.filtered;
                if (reference) {
                    std::vector<TrianglePair> mine;
                    for (const auto& g : result.pairs) {
                        auto locate = [&](std::uint32_t t) {
                            std::size_t o = gpu_scene.objects.size() - 1;
                            while (gpu_scene.objects[o].triangle_base > t) --o;
                            return std::pair<std::uint32_t, std::uint32_t>(std::uint32_t(o), t - gpu_scene.objects[o].triangle_base);
                        };
                        auto [oa, ta] = locate(g[0]);
                        auto [ob, tb] = locate(g[1]);
                        mine.push_back({oa, ta, ob, tb});
                    }
                    row.found += test::comparePairs(mine, ref).true_positives;
                }
            }
        }
        for (std::size_t fi = 0; fi < factors.size(); ++fi) {
            const Row& row = rows[fi];
            if (row.failed) continue;
            const double runs = double(row.gpu_ms.size()), per_frame = 1.0 / frame_count;
            auto pass = [&](const char* key) {
                auto it = row.pass_total.find(key);
                return it == row.pass_total.end() || runs == 0 ? 0.0 : it->second / runs;
            };
            char recall[16] = "-", per_pair[16] = "-";
            if (reference) {
                std::snprintf(recall, sizeof recall, "%.4f", exact ? double(row.found) / double(exact) : 1.0);
                std::snprintf(per_pair, sizeof per_pair, "%.1f", exact ? double(row.stats.candidates) / double(exact) : 0.0);
            }
            const double cands = std::max<double>(1.0, double(row.stats.candidates));
            std::printf("%-15s %9zu %5c %5.2f %6u %11.0f %6.2f %9llu %7.0f %11.0f %10.0f %9.0f %5.1f %5.1f %9.0f %8.0f %8s %7s %8.3f %8.3f | %6.3f %6.3f %6.3f %6.3f %6.3f %6.3f\n",
                        spec.name.c_str(), tris, axis, factors[fi], row.n, double(row.stats.entries) * per_frame,
                        tris ? double(row.stats.entries) * per_frame / double(tris) : 0.0, (unsigned long long)row.stats.max_cell,
                        double(row.stats.deep_cells) * per_frame, double(row.stats.comparisons) * per_frame,
                        double(row.stats.candidates) * per_frame, double(row.stats.neighbours) * per_frame,
                        100.0 * double(row.stats.duplicates) / cands, 100.0 * double(row.stats.filtered) / cands,
                        double(row.stats.survivors) * per_frame, double(exact) * per_frame,
                        recall, per_pair, median(row.gpu_ms), median(row.wall_ms), pass("setup"), pass("big"), pass("scan"),
                        pass("fill"), pass("sweep"), pass("pairs"));
        }
        std::fflush(stdout);
    }
    return 0;
}
