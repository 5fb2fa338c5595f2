// Benchmark of the CPU narrow phase on generated scenes; host only unless a gpu-* scene.
//
//   bench_narrow [--threads 1,2,16] [--sizes 10000,100000,1000000] [--scenes demo,spheres,torus-box]
//                [--modes all,near,contact] [--self on,off] [--paths records,lean,pairs] [--pair-repeats 0.1]
//                [--repeat 7] [--margin 1.0] [--filter] [--fresh] [--candidates FILE]... [--resolution N]
//                [--pairs-sent boxes|hits] [--decided] [--gap-us 0] [--dump PREFIX] [--csv PATH]
//   bench_narrow --wake-probe [--threads 16] [--repeat 7] [--gap-us 2000]
//   bench_narrow --front-probe [scene options as above] (bench_narrow_probes.hpp)
//
// Candidates come from tests/support/exact_reference.hpp's allTrianglesAsCandidates: every
// triangle with its world AABB mapped to [0,1] as box and depth (an orthographic camera
// looking down -z). Modes choose which triangles the "broad phase" keeps:
//   all      every triangle (with self-collision on: mostly neighbour pairs),
//   near     triangles whose AABB overlaps another object's AABB,
//   contact  triangles whose AABB, grown by `margin` median triangle extents, shares a
//            voxel of that size with a triangle of another object (close to what the GPU
//            keeps in a light contact: the triangles along the intersection curves).
// Scenes: `demo` is samples/vkcollide_demo.cpp's five objects (31,520 triangles, sizes do
// not apply); `spheres` (two overlapping UV spheres) and `torus-box` (a torus threaded on a
// subdivided box) are generated with about `size` triangles in all; `deep` is the
// deep overlap (two spheres of size/2 triangles overlapping by 85 % of their size: with
// `near`, about 1M candidates for size 1,200,000), `twin` a sphere and a copy turned by 3
// degrees (surfaces crossing all over: several tests per triangle) and `pile` its 60-mesh
// pile (60 spheres of 9,940 triangles, fixed size), `graze` two spheres of size/2 triangles
// meeting along one small circle (centres 1.8 radii apart: with `--pairs-sent hits`, about
// 500 pairs for size 100,000, near the ~650 the reliable method reads back on deform-pair-100K),
// `touching` and `touching-tilted` boxes resting face to face (bench_narrow_scenes.hpp;
// with --modes all --self off --pairs-sent hits, about 150K triangles and 600K pairs for
// size 150,000, like the GPU bench's stack-touching). Meshes
// are in object space with a transform per object; world positions are computed as the
// exact reference does.
// --candidates reads a raw array of CandidateTriangle (80 bytes each, e.g. the records of a
// GPU broad phase; only the records path).
//
// `gpu-<scene>` (gpu-demo, gpu-deep, gpu-pile, ...) takes the scene's candidates from the
// real GPU broad phase instead (the Vulkan device vkcollide finds, lavapipe without a GPU;
// resolution 512 unless --resolution; not in the default list because it needs Vulkan).
//
// Paths (--paths, a row each): `records` runs runNarrowPhase on the 80-byte records,
// `lean` on 32-byte CandidateRecords with a TriangleSource holding the scene's object-space
// meshes and transforms, `pairs` runs runPairNarrowPhase on what a GPU pair stage without
// its triangle filter would send: every pair of boxes overlapping in x, y and z that the
// self-collision switch allows and that shares no vertex index, as global ids, a fraction
// (--pair-repeats) sent twice reversed, shuffled. `--pairs-sent hits` sends only the pairs
// whose triangles intersect (what the GPU pair stage sends after its conservative triangle
// test, less its few near misses: the pair counts the reliable method reads back),
// repeats and shuffle as before. Every path and thread count must give
// the same pairs (a gpu-* workload only warns between paths: the GPU computes its records'
// vertices itself).
//
// --self sets every object's self-collision (a row each; vkcollide's default for objects
// is off, the peers' benchmarks run with it on).
//
// --dump writes each workload's candidates to PREFIX<scene>-<size>-<mode>.bin (the format
// --candidates reads), e.g. to profile the GPU's candidates without the GPU.
//
// --decided (with --pairs-sent hits) sets NarrowOptions::pairs_decided on the pair path:
// the pairs are taken as intersecting, as the GPU's exact decision sends them (no tests).
//
// --gap-us sleeps that long before every timed call, as the GPU's 0.3-2 ms between two
// detections does: the pool's workers have gone to sleep when the call starts (without it
// they are still polling from the previous call, which a frame loop never sees).
//
// Each configuration runs once to warm up, then `repeat` times; the table shows the median
// of each stage (ms), the fastest total and the median process CPU time (all threads,
// polling workers included). --filter sets NarrowOptions::may_collide (allowing
// everything) to time the object-pair filter. Calls reuse one NarrowWorkspace per
// configuration, as an engine would from frame to frame; --fresh uses the overloads
// without one (every call allocates its arrays).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "api/context_access.hpp"
#include "bench_narrow_probes.hpp"
#include "bench_narrow_scenes.hpp"
#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "mesh/mesh_upload.hpp"
#include "narrow/neighbours.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "narrow/triangle_intersection.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;

namespace {

struct Options {
    std::vector<unsigned> threads = {1, 2};
    std::vector<std::size_t> sizes = {10000, 100000, 1000000};
    std::vector<std::string> scenes = {"demo", "spheres", "torus-box"};
    std::vector<std::string> modes = {"all", "near", "contact"};
    std::vector<bool> self = {true};  // self-collision of every object, one row each
    std::vector<std::string> paths = {"records"};
    double pair_repeats = 0.1;  // pair path: this fraction of the pairs is sent twice (reversed)
    bool hits_only = false;     // pair path: send only the pairs whose triangles intersect
    bool decided = false;       // pair path: NarrowOptions::pairs_decided (with hits_only)
    unsigned gap_us = 0;        // sleep before each timed call
    std::vector<std::string> files;
    unsigned repeat = 7;
    std::uint32_t resolution = 512;
    float margin = 1.0f;
    bool filter = false;
    bool fresh = false;  // no NarrowWorkspace: allocate every call
    std::string csv;
    std::string dump;  // prefix for raw candidate files, empty: none
    bool wake_probe = false;
    bool front_probe = false;  // pair path: time the front's two forms instead of whole calls
};

// World positions of a SceneObject are computed as tests/support/exact_reference.hpp's
// worldPositions does.
using bench::SceneObject;

struct Workload {
    std::string scene, mode;
    std::size_t triangles = 0;
    std::vector<CandidateTriangle> candidates;
    std::vector<SceneObject> objects;  // object-space meshes and transforms; empty for --candidates files
};

[[noreturn]] void die(const std::string& what) {
    std::fprintf(stderr, "bench_narrow: %s\n", what.c_str());
    std::exit(1);
}

template <typename T>
T take(Result<T> r, const char* what) {
    if (!r) die(std::string(what) + ": " + r.error().message());
    return std::move(*r);
}

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::size_t begin = 0;
    while (begin <= s.size()) {
        const std::size_t end = std::min(s.find(',', begin), s.size());
        if (end > begin) out.push_back(s.substr(begin, end - begin));
        begin = end + 1;
    }
    return out;
}

Options parseArgs(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) die(a + " needs a value");
            return argv[++i];
        };
        if (a == "--threads") {
            o.threads.clear();
            for (const std::string& t : splitList(value())) o.threads.push_back(static_cast<unsigned>(std::stoul(t)));
        } else if (a == "--sizes") {
            o.sizes.clear();
            for (const std::string& t : splitList(value())) o.sizes.push_back(std::stoul(t));
        } else if (a == "--scenes") {
            o.scenes = splitList(value());
        } else if (a == "--self") {
            o.self.clear();
            for (const std::string& t : splitList(value())) {
                if (t != "on" && t != "off") die("--self takes on, off or both (on,off)");
                o.self.push_back(t == "on");
            }
        } else if (a == "--paths") {
            o.paths = splitList(value());
            for (const std::string& t : o.paths) {
                if (t != "records" && t != "lean" && t != "pairs") die("--paths takes records, lean, pairs");
            }
        } else if (a == "--pair-repeats") {
            o.pair_repeats = std::stod(value());
        } else if (a == "--pairs-sent") {
            const std::string v = value();
            if (v != "boxes" && v != "hits") die("--pairs-sent takes boxes or hits");
            o.hits_only = v == "hits";
        } else if (a == "--decided") {
            o.decided = true;
        } else if (a == "--gap-us") {
            o.gap_us = static_cast<unsigned>(std::stoul(value()));
        } else if (a == "--modes") {
            o.modes = splitList(value());
        } else if (a == "--candidates") {
            o.files.push_back(value());
        } else if (a == "--repeat") {
            o.repeat = std::max(1u, static_cast<unsigned>(std::stoul(value())));
        } else if (a == "--margin") {
            o.margin = std::stof(value());
        } else if (a == "--resolution") {
            o.resolution = static_cast<std::uint32_t>(std::stoul(value()));
        } else if (a == "--fresh") {
            o.fresh = true;
        } else if (a == "--filter") {
            o.filter = true;
        } else if (a == "--dump") {
            o.dump = value();
        } else if (a == "--csv") {
            o.csv = value();
        } else if (a == "--wake-probe") {
            o.wake_probe = true;
        } else if (a == "--front-probe") {
            o.front_probe = true;
        } else {
            die("unknown argument " + a +
                " (use --threads, --sizes, --scenes, --modes, --self, --paths, --pair-repeats, --pairs-sent, --decided, --candidates, --repeat, --resolution, --margin, --filter, --fresh, --gap-us, --dump, --csv, --wake-probe, --front-probe)");
        }
    }
    if (o.threads.empty()) die("--threads needs at least one count");
    if (o.self.empty()) die("--self needs on, off or both");
    if (o.decided && !o.hits_only) die("--decided needs --pairs-sent hits (decided pairs intersect)");
    return o;
}

HostMesh generated(Result<HostMesh> mesh) { return take(std::move(mesh), "generator"); }

// Rotation by `angle` about the unit axis (x, y, z), then a translation.
Transform3x4 rotationTranslation(double x, double y, double z, double angle, Float3 t) {
    const double n = std::sqrt(x * x + y * y + z * z);
    x /= n, y /= n, z /= n;
    const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    const auto f = [](double v) { return static_cast<float>(v); };
    return {f(c + x * x * k),     f(x * y * k - z * s), f(x * z * k + y * s), t.x,
            f(y * x * k + z * s), f(c + y * y * k),     f(y * z * k - x * s), t.y,
            f(z * x * k - y * s), f(z * y * k + x * s), f(c + z * z * k),     t.z};
}

// Rotation about y, then a translation: the demo's placement of its parts.
SceneObject placed(Result<HostMesh> mesh, float angle, Float3 t) {
    return {generated(std::move(mesh)), rotationTranslation(0, 1, 0, angle, t)};
}

std::uint32_t atLeast(double x, std::uint32_t lo) { return std::max(lo, static_cast<std::uint32_t>(std::lround(x))); }

// A deterministic pseudo-random number in [0, 1) from an integer.
double hash01(std::uint32_t i) {
    std::uint32_t h = i * 2654435761u;
    h ^= h >> 16;
    h *= 2246822519u;
    h ^= h >> 13;
    return static_cast<double>(h) / 4294967296.0;
}

// Scenes that ignore --sizes.
bool fixedSize(const std::string& scene) { return scene == "demo" || scene == "pile"; }

std::vector<SceneObject> buildScene(const std::string& scene, std::size_t size) {
    if (std::optional<std::vector<SceneObject>> touching = bench::touchingScene(scene, size)) return std::move(*touching);
    std::vector<SceneObject> objects;
    if (scene == "demo") {
        objects.push_back(placed(uvSphere(1.0f, 96, 48), 0.3f, {-0.6f, 0.05f, 0.0f}));
        objects.push_back(placed(uvSphere(0.9f, 96, 48), 0.7f, {0.55f, -0.1f, 0.2f}));
        objects.push_back(placed(torus(0.9f, 0.25f, 128, 32), 0.2f, {0.1f, 1.6f, 0.0f}));
        objects.push_back(placed(box({0.3f, 0.3f, 1.4f}, 16), 0.1f, {0.1f + 0.9f, 1.6f, 0.0f}));
        objects.push_back(placed(uvSphere(0.5f, 48, 24), 0.0f, {-2.2f, -1.5f, 0.0f}));
    } else if (scene == "spheres") {
        // Two spheres of 2 s (s/2 - 1) ~ s^2 triangles each.
        const std::uint32_t s = atLeast(std::sqrt(double(size) / 2.0), 8);
        objects.push_back(placed(uvSphere(1.0f, s, s / 2), 0.3f, {-0.5f, 0.0f, 0.0f}));
        objects.push_back(placed(uvSphere(0.9f, s, s / 2), 0.7f, {0.5f, 0.1f, 0.05f}));
    } else if (scene == "torus-box") {
        // Half the triangles in the torus (2 a (a/4) = a^2 / 2), half in the box (12 k^2).
        const std::uint32_t a = atLeast(std::sqrt(double(size)), 12);
        const std::uint32_t k = atLeast(std::sqrt(double(size) / 24.0), 1);
        objects.push_back(placed(torus(0.9f, 0.25f, a, std::max(3u, a / 4)), 0.2f, {0.0f, 0.0f, 0.0f}));
        objects.push_back(placed(box({0.3f, 0.3f, 1.4f}, k), 0.1f, {0.9f, 0.0f, 0.0f}));
    } else if (scene == "deep") {
        // The deep overlap: two meshes of size/2 triangles each overlapping by 85 %
        // of their size (unit spheres 0.3 apart, mostly across the view): seen along z, the
        // rays through both discs meet the surfaces interleaved, so the GPU keeps most
        // triangles of both (mode `near` keeps those whose box meets the other's box).
        const std::uint32_t s = atLeast(std::sqrt(double(size) / 2.0), 8);
        objects.push_back({generated(uvSphere(1.0f, s, s / 2)), rotationTranslation(1, 0.2, 0.1, 0.4, {-0.14f, -0.05f, 0.0f})});
        objects.push_back({generated(uvSphere(1.0f, s, s / 2)), rotationTranslation(0.1, 1, 0.3, 1.1, {0.14f, 0.05f, 0.06f})});
    } else if (scene == "twin") {
        // A sphere of size/2 triangles and a copy turned by 3 degrees about a tilted axis
        // through its centre (tools/bench/bench_scenes.cpp's meshTwin): the two surfaces
        // cross each other all over, about one test per triangle between the objects.
        const std::uint32_t s = atLeast(std::sqrt(double(size) / 2.0), 8);
        const HostMesh sphere = generated(uvSphere(1.0f, s, s / 2));
        objects.push_back({sphere, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}});
        objects.push_back({sphere, rotationTranslation(0.3, 1, 0.2, 3 * std::numbers::pi / 180, {0, 0, 0})});
    } else if (scene == "graze") {
        // Two unit spheres of size/2 triangles, centres 1.8 apart: they cross along one
        // circle of radius 0.44, a light contact between two detailed meshes.
        const std::uint32_t s = atLeast(std::sqrt(double(size) / 2.0), 8);
        const HostMesh sphere = generated(uvSphere(1.0f, s, s / 2));
        objects.push_back({sphere, rotationTranslation(0.2, 1, 0.1, 0.5, {-0.9f, 0.0f, 0.0f})});
        objects.push_back({sphere, rotationTranslation(1, 0.3, 0.2, 1.3, {0.9f, 0.05f, 0.02f})});
    } else if (scene == "pile") {
        // The pile: 60 unit spheres of 9,940 triangles (596,400 in all) on a grid
        // 1.8 apart, each turned its own way (tools/bench/bench_scenes.cpp's sphereGrid,
        // the `spheres-60x10K` scene).
        const HostMesh base = generated(uvSphere(1.0f, 70, 72));
        constexpr std::uint32_t kCount = 60, kSide = 4;  // ceil(cbrt(60))
        for (std::uint32_t i = 0; i < kCount; ++i) {
            const Float3 t{1.8f * float(i % kSide), 1.8f * float((i / kSide) % kSide), 1.8f * float(i / (kSide * kSide))};
            objects.push_back({base, rotationTranslation(hash01(3 * i) - 0.5, hash01(3 * i + 1) - 0.5, hash01(3 * i + 2) + 0.1,
                                                         2 * std::numbers::pi * hash01(7 * i + 5), t)});
        }
    } else {
        die("unknown scene " + scene + " (use demo, spheres, torus-box, deep, twin, graze, pile, touching, touching-tilted, gpu-demo, gpu-deep, gpu-pile)");
    }
    return objects;
}

struct Aabb {
    Float3 lo, hi;
};

Aabb boundsOf(const CandidateTriangle& c) {
    Aabb b{c.v[0], c.v[0]};
    for (const Float3& p : c.v) {
        b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
        b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
    }
    return b;
}

bool overlap(const Aabb& a, const Aabb& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

// Keeps the candidates the mode selects (see the file comment).
std::vector<CandidateTriangle> selectCandidates(std::vector<CandidateTriangle> all, const std::string& mode, float margin) {
    if (mode == "all") return all;
    std::vector<Aabb> boxes(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) boxes[i] = boundsOf(all[i]);
    std::vector<char> keep(all.size(), 0);
    if (mode == "near") {
        std::vector<Aabb> object_box;
        for (std::size_t i = 0; i < all.size(); ++i) {
            const std::uint32_t o = all[i].object;
            if (o >= object_box.size()) object_box.resize(o + 1, Aabb{{1, 1, 1}, {-1, -1, -1}});
            Aabb& b = object_box[o];
            if (b.lo.x > b.hi.x) {
                b = boxes[i];
            } else {
                b.lo = {std::min(b.lo.x, boxes[i].lo.x), std::min(b.lo.y, boxes[i].lo.y), std::min(b.lo.z, boxes[i].lo.z)};
                b.hi = {std::max(b.hi.x, boxes[i].hi.x), std::max(b.hi.y, boxes[i].hi.y), std::max(b.hi.z, boxes[i].hi.z)};
            }
        }
        for (std::size_t i = 0; i < all.size(); ++i) {
            for (std::uint32_t o = 0; o < object_box.size(); ++o) {
                if (o != all[i].object && object_box[o].lo.x <= object_box[o].hi.x && overlap(boxes[i], object_box[o])) keep[i] = 1;
            }
        }
    } else if (mode == "contact") {
        // Voxels of `margin` median extents: a triangle is kept when a voxel its AABB
        // touches is also touched by another object's triangle.
        std::vector<float> extent(all.size());
        for (std::size_t i = 0; i < all.size(); ++i) {
            extent[i] = std::max({boxes[i].hi.x - boxes[i].lo.x, boxes[i].hi.y - boxes[i].lo.y, boxes[i].hi.z - boxes[i].lo.z});
        }
        std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(extent.size() / 2), extent.end());
        const double voxel = std::max(1e-6, double(extent[extent.size() / 2]) * std::max(0.01f, margin));
        constexpr std::uint32_t kMixed = 0xffffffffu;
        std::unordered_map<std::uint64_t, std::uint32_t> owner;  // voxel -> object, or kMixed
        const auto forVoxels = [&](std::size_t i, auto&& f) {
            const auto cell = [&](float x) { return static_cast<std::int64_t>(std::floor(double(x) / voxel)) + (1 << 20); };
            for (std::int64_t x = cell(boxes[i].lo.x); x <= cell(boxes[i].hi.x); ++x) {
                for (std::int64_t y = cell(boxes[i].lo.y); y <= cell(boxes[i].hi.y); ++y) {
                    for (std::int64_t z = cell(boxes[i].lo.z); z <= cell(boxes[i].hi.z); ++z) {
                        f((std::uint64_t(x) << 42) | (std::uint64_t(y) << 21) | std::uint64_t(z));
                    }
                }
            }
        };
        for (std::size_t i = 0; i < all.size(); ++i) {
            forVoxels(i, [&](std::uint64_t key) {
                auto [it, inserted] = owner.try_emplace(key, all[i].object);
                if (!inserted && it->second != all[i].object) it->second = kMixed;
            });
        }
        for (std::size_t i = 0; i < all.size(); ++i) {
            forVoxels(i, [&](std::uint64_t key) {
                if (owner[key] == kMixed) keep[i] = 1;
            });
        }
    } else {
        die("unknown mode " + mode + " (use all, near, contact)");
    }
    std::vector<CandidateTriangle> out;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (keep[i]) out.push_back(all[i]);
    }
    return out;
}

Workload makeWorkload(const std::string& scene, std::size_t size, const std::string& mode, float margin) {
    const std::vector<SceneObject> scene_objects = buildScene(scene, size);
    std::vector<test::ReferenceObject> objects;
    Workload w;
    w.scene = scene;
    w.mode = mode;
    for (const SceneObject& o : scene_objects) {
        objects.push_back({&o.mesh, test::transformFrom3x4(o.transform)});
        w.triangles += o.mesh.triangleCount();
    }
    w.candidates = selectCandidates(take(test::allTrianglesAsCandidates(objects), "candidates"), mode, margin);
    w.objects = scene_objects;
    return w;
}

// The demo's candidates as the GPU broad phase keeps them (samples/vkcollide_demo.cpp's
// settings): the workload the narrow phase sees in the demo.
Workload gpuWorkload(const std::string& scene, std::size_t size, std::uint32_t resolution) {
    // The broad phase takes world-space meshes: transforms applied as the exact reference does.
    std::vector<HostMesh> meshes;
    const std::vector<SceneObject> scene_objects = buildScene(scene, size);
    for (const SceneObject& o : scene_objects) {
        HostMesh m = o.mesh;
        m.positions = test::worldPositions(o.mesh, test::transformFrom3x4(o.transform));
        meshes.push_back(std::move(m));
    }
    std::vector<const HostMesh*> mesh_ptrs;
    Workload w;
    w.scene = "gpu-" + scene + "-" + std::to_string(resolution);
    w.mode = "gpu";
    for (const HostMesh& m : meshes) {
        mesh_ptrs.push_back(&m);
        w.triangles += m.triangleCount();
    }
    auto ctx = take(Context::create(), "Vulkan context");
    vk::Device& dev = ContextAccess::device(*ctx);
    const auto uploaded = take(passes::uploadMeshes(dev, mesh_ptrs), "mesh upload");
    auto broad_phase = take(passes::BroadPhase::create(dev, passes::PeelingMethod::create), "broad phase");
    passes::BroadPhaseSettings settings;
    settings.resolution = resolution;
    settings.direction = {0.15f, -0.2f, 1.0f};
    w.candidates = take(broad_phase->run(uploaded.meshes, settings), "broad phase").records;
    w.objects = scene_objects;
    return w;
}

Workload loadWorkload(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) die("cannot open " + path);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() % sizeof(CandidateTriangle) != 0) die(path + ": size is not a multiple of 80 bytes");
    Workload w;
    w.scene = "file:" + path;
    w.mode = "file";
    w.candidates.resize(bytes.size() / sizeof(CandidateTriangle));
    if (!bytes.empty()) std::memcpy(w.candidates.data(), bytes.data(), bytes.size());
    w.triangles = w.candidates.size();
    return w;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// CPU time of the whole process (all threads), in ms.
double processCpuMs() { return 1000.0 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// The inputs of the lean and pair paths for one workload and self-collision setting.
struct LeanInputs {
    TriangleSource source;
    std::vector<CandidateRecord> records;
    std::vector<CandidatePair> pairs;
};

// The source holds the scene's object-space meshes and transforms; records are the
// candidates without vertices; pairs are what a GPU pair stage without its triangle
// filter would send: every pair of boxes overlapping in x, y and z that the
// self-collision switch allows and that shares no vertex index (with hits_only: and whose
// triangles intersect), as global ids, a fraction sent twice (reversed), shuffled.
LeanInputs leanInputs(const Workload& w, bool self, double repeats, bool hits_only, bool with_pairs) {
    LeanInputs in;
    for (const SceneObject& o : w.objects) take(in.source.addHostMesh(o.mesh.positions, o.mesh.indices, o.transform), "source");
    in.records.reserve(w.candidates.size());
    for (const CandidateTriangle& c : w.candidates) {
        in.records.push_back({c.object, c.triangle, {c.box[0], c.box[1], c.box[2], c.box[3]}, c.zmin, c.zmax});
    }
    if (!with_pairs) return in;
    ThreadPool pool(0);
    for (const narrow::IndexPair& p : narrow::sweepAndPrunePairs(w.candidates, &pool)) {
        const CandidateTriangle &a = w.candidates[p.i], &b = w.candidates[p.j];
        if (a.object == b.object && (!self || narrow::shareIndex(a.vertex_index, b.vertex_index))) continue;
        if (hits_only && !narrow::trianglesIntersect(a.v, b.v)) continue;
        in.pairs.push_back({in.source.triangleBase(a.object) + a.triangle, in.source.triangleBase(b.object) + b.triangle});
    }
    const std::size_t distinct = in.pairs.size();
    const std::size_t every = repeats > 0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(1.0 / repeats))) : 0;
    for (std::size_t k = 0; every && k < distinct; k += every) in.pairs.push_back({in.pairs[k].b, in.pairs[k].a});
    std::mt19937 rng(2006);
    std::shuffle(in.pairs.begin(), in.pairs.end(), rng);
    return in;
}

void runWorkload(const Workload& w, const Options& o, std::FILE* csv) {
    if (!o.dump.empty() && w.mode != "file") {
        const std::string path = o.dump + w.scene + "-" + std::to_string(w.triangles) + "-" + w.mode + ".bin";
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(w.candidates.data()),
                  static_cast<std::streamsize>(w.candidates.size() * sizeof(CandidateTriangle)));
        if (!out) die("cannot write " + path);
    }
    const bool lean_paths = std::any_of(o.paths.begin(), o.paths.end(), [](const std::string& p) { return p != "records"; });
    const bool pair_path = std::find(o.paths.begin(), o.paths.end(), "pairs") != o.paths.end();
    for (const bool self : o.self) {
        NarrowOptions options;
        options.default_self_collision = self;
        if (o.filter) options.may_collide = [](std::uint32_t, std::uint32_t) { return true; };
        NarrowOptions pair_options = options;  // the pair path's (the record paths refuse pairs_decided)
        pair_options.pairs_decided = o.decided;
        LeanInputs lean;
        if (lean_paths && !w.objects.empty()) lean = leanInputs(w, self, o.pair_repeats, o.hits_only, pair_path);
        std::vector<TrianglePair> reference_pairs;
        bool first = true, warned = false;
        if (o.front_probe && pair_path && !w.objects.empty()) {
            bench::frontProbe(w.scene + " " + std::to_string(w.triangles) + (self ? " self" : ""), lean.pairs,
                              lean.source.totalTriangles(), o.threads, o.repeat, o.gap_us);
            continue;
        }
        for (const std::string& path : o.paths) {
            if (path != "records" && w.objects.empty()) continue;  // a candidate file has no meshes
            std::vector<TrianglePair> path_pairs;
            bool path_first = true;
            const std::size_t inputs = path == "pairs" ? lean.pairs.size() : w.candidates.size();
            for (unsigned threads : o.threads) {
                ThreadPool pool(threads);
                NarrowWorkspace workspace;
                std::vector<NarrowTimings> times;
                std::vector<double> cpu;
                NarrowStats stats;
                for (unsigned r = 0; r <= o.repeat; ++r) {
                    if (o.gap_us) std::this_thread::sleep_for(std::chrono::microseconds(o.gap_us));
                    const double cpu_start = processCpuMs();
                    Result<NarrowResult> result = Error(ErrorCode::InvalidArgument, "no path");
                    if (path == "records") {
                        result = o.fresh ? runNarrowPhase(w.candidates, options, pool)
                                         : runNarrowPhase(w.candidates, options, pool, workspace);
                    } else if (path == "lean") {
                        result = o.fresh ? runNarrowPhase(lean.records, lean.source, options, pool)
                                         : runNarrowPhase(lean.records, lean.source, options, pool, workspace);
                    } else {
                        result = o.fresh ? runPairNarrowPhase(lean.pairs, lean.source, pair_options, pool)
                                         : runPairNarrowPhase(lean.pairs, lean.source, pair_options, pool, workspace);
                    }
                    const double cpu_ms = processCpuMs() - cpu_start;
                    if (!result) die(w.scene + " (" + path + "): " + result.error().message());
                    if (r == 0) {  // warm-up run: check it, do not time it
                        if (first) reference_pairs = result->pairs;
                        if (path_first) path_pairs = result->pairs;
                        first = path_first = false;
                        if (result->pairs != path_pairs) {
                            die(w.scene + ": " + path + " with " + std::to_string(threads) + " threads gives other pairs");
                        }
                        if (result->pairs != reference_pairs && !warned) {
                            // The GPU computes its records' world vertices itself (in float;
                            // -0 can become +0), the other paths take the source's.
                            const std::string what = w.scene + ": " + path + " finds " + std::to_string(result->pairs.size()) +
                                                     " pairs, " + o.paths.front() + " " + std::to_string(reference_pairs.size());
                            if (w.mode != "gpu") die(what);
                            std::printf("warning: %s (GPU records' vertices differ from the source's)\n", what.c_str());
                            warned = true;
                        }
                        stats = result->stats;
                        continue;
                    }
                    times.push_back(result->timings);
                    cpu.push_back(cpu_ms);
                }
                const auto med = [&](double NarrowTimings::*field) {
                    std::vector<double> v;
                    for (const NarrowTimings& t : times) v.push_back(t.*field);
                    return median(v);
                };
                const double validate = med(&NarrowTimings::validate_ms), gather = med(&NarrowTimings::gather_ms),
                             sweep = med(&NarrowTimings::sweep_ms), filter = med(&NarrowTimings::filter_ms),
                             test = med(&NarrowTimings::test_ms), sort = med(&NarrowTimings::sort_ms),
                             response = med(&NarrowTimings::response_ms), total = med(&NarrowTimings::total_ms);
                double total_min = times.front().total_ms;
                for (const NarrowTimings& t : times) total_min = std::min(total_min, t.total_ms);
                const double cpu_ms = median(cpu);
                std::printf("%-12s %-8s %-4s %-7s %9zu %9zu %4u %10zu %9zu %7zu | %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f | %9.3f %9.3f %8.3f\n",
                            w.scene.c_str(), w.mode.c_str(), self ? "on" : "off", path.c_str(), w.triangles, inputs,
                            pool.threadCount(), stats.sap_pairs, stats.triangle_tests, stats.positive_tests, validate, gather,
                            sweep, filter, test, sort, response, total, total_min, cpu_ms);
                std::fflush(stdout);
                if (csv) {
                    std::fprintf(csv,
                                 "%s,%s,%s,%s,%zu,%zu,%u,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%."
                                 "4f,%.4f\n",
                                 w.scene.c_str(), w.mode.c_str(), self ? "on" : "off", path.c_str(), w.triangles, inputs,
                                 pool.threadCount(), stats.candidates, stats.potentially_colliding_triangles, stats.sap_pairs,
                                 stats.filtered_pairs, stats.neighbour_pairs, stats.triangle_tests, stats.positive_tests,
                                 stats.input_pairs, validate, gather, sweep, filter, test, sort, response, total, total_min, cpu_ms);
                    std::fflush(csv);
                }
            }
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parseArgs(argc, argv);
    if (o.wake_probe) {
        bench::wakeProbe(o.threads, o.repeat, o.gap_us);
        return 0;
    }
    std::FILE* csv = nullptr;
    if (!o.csv.empty()) {
        csv = std::fopen(o.csv.c_str(), "w");
        if (!csv) die("cannot write " + o.csv);
        std::fprintf(csv, "scene,mode,self,path,triangles,inputs,threads,candidates,potentially_colliding,sap_pairs,filtered_pairs,neighbour_pairs,triangle_tests,"
                          "positive_tests,input_pairs,validate_ms,gather_ms,sweep_ms,filter_ms,test_ms,sort_ms,response_ms,total_ms,total_min_ms,cpu_ms\n");
    }
    if (o.front_probe) {
        bench::frontProbeHeader();
    } else {
        std::printf("median of %u runs (ms)%s%s%s, %u us between calls\n", o.repeat, o.filter ? ", with may_collide" : "",
                    o.fresh ? ", no workspace" : ", one workspace per row", o.hits_only ? ", intersecting pairs sent" : "", o.gap_us);
    }
    if (!o.front_probe) std::printf("%-12s %-8s %-4s %-7s %9s %9s %4s %10s %9s %7s | %8s %8s %8s %8s %8s %8s %8s | %9s %9s %8s\n", "scene", "mode",
                "self", "path", "tris", "inputs", "thr", "cand pairs", "tests", "pairs", "validate", "gather", "sweep", "filter",
                "test", "sort", "response", "total", "total min", "cpu");
    for (const std::string& path : o.files) runWorkload(loadWorkload(path), o, csv);
    for (const std::string& scene : o.scenes) {
        if (scene.rfind("gpu-", 0) == 0) {
            const std::string base = scene.substr(4);
            const std::vector<std::size_t> sizes = fixedSize(base) ? std::vector<std::size_t>{0} : o.sizes;
            for (std::size_t size : sizes) runWorkload(gpuWorkload(base, size, o.resolution), o, csv);
            continue;
        }
        const std::vector<std::size_t> sizes = fixedSize(scene) ? std::vector<std::size_t>{0} : o.sizes;
        for (std::size_t size : sizes) {
            for (const std::string& mode : o.modes) runWorkload(makeWorkload(scene, size, mode, o.margin), o, csv);
        }
    }
    if (csv) std::fclose(csv);
    return 0;
}
