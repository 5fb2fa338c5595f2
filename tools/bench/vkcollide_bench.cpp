// vkcollide_bench: the speed-against-accuracy sweep of issue 7. Not a test: a program.
//
//   vkcollide_bench [--scenes a,b,...] [--resolutions 256,512,...] [--frames K]
//                   [--variants basic|full] [--threads N] [--data DIR] [--csv FILE] [--list]
//
// For each scene (tools/bench/bench_scenes.hpp; every object self-colliding, as the peers
// run) and each configuration point it runs one warm-up detection and K timed ones
// (deforming scenes: new vertices every frame through updateVertices, timed from the
// update to the pair list) and writes one CSV row per frame: per-stage times (GPU
// timestamps per stage, readback, CPU narrow phase, total wall), GPU and host memory,
// Table 1 counts, and recall and precision against the exact reference of that frame.
// "basic" sweeps resolution x {single, dual} x {raster, compute}; "full" adds layer caps, paper packing,
// open mode and the asynchronous form at 1024. A progress line goes to stderr.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scenes.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

struct Point {
    std::string variant;  // what differs from the default
    DetectSettings settings;
    bool open = false;
    bool async = false;
};

std::vector<Point> points(const std::vector<std::uint32_t>& resolutions, bool full) {
    std::vector<Point> out;
    for (std::uint32_t r : resolutions) {
        for (bool dual : {false, true})
            for (SamplingBackend b : {SamplingBackend::Raster, SamplingBackend::Compute}) {
                Point p;
                p.variant = dual ? "dual" : "single";
                p.settings.resolution = r;
                p.settings.dual = dual;
                p.settings.backend = b;
                out.push_back(p);
            }
    }
    if (full) {
        auto at1024 = [&](const std::string& name) {
            Point p;
            p.variant = name;
            p.settings.resolution = 1024;
            return p;
        };
        for (std::uint32_t cap : {2u, 4u}) {
            Point p = at1024("cap" + std::to_string(cap));
            p.settings.layer_cap = cap;
            out.push_back(p);
        }
        Point paper = at1024("paper-packing");
        paper.settings.packing = PackingMethod::Paper;
        out.push_back(paper);
        Point open = at1024("open");
        open.open = true;
        out.push_back(open);
        Point async = at1024("async");
        async.async = true;
        out.push_back(async);
        Point autos;
        autos.variant = "auto";
        out.push_back(autos);
    }
    return out;
}

double peakHostMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

struct Progress {
    void show(const std::string& line) const { std::fprintf(stderr, "\r\033[K%s", line.c_str()), std::fflush(stderr); }
    void done() const { std::fprintf(stderr, "\r\033[K"); }
};

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scene_names = {"spheres-8x10K", "bunnies-2x75K", "deform-pair-100K"};
    std::vector<std::uint32_t> resolutions = {256, 512, 1024, 2048, 4096};
    int frames = 5;
    bool full = true, list = false;
    unsigned threads = 0;
    std::string data = "data/cgal", csv_path = "vkcollide_bench.csv";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
        if (a == "--list") list = true;
        else if (a == "--scenes" && v) scene_names = splitList(argv[++i]);
        else if (a == "--resolutions" && v) {
            resolutions.clear();
            for (const auto& r : splitList(argv[++i])) resolutions.push_back(static_cast<std::uint32_t>(std::stoul(r)));
        } else if (a == "--frames" && v) frames = std::max(1, std::atoi(argv[++i]));
        else if (a == "--variants" && v) full = std::string(argv[++i]) == "full";
        else if (a == "--threads" && v) threads = static_cast<unsigned>(std::atoi(argv[++i]));
        else if (a == "--data" && v) data = argv[++i];
        else if (a == "--csv" && v) csv_path = argv[++i];
        else {
            std::fprintf(stderr, "usage: vkcollide_bench [--scenes a,b] [--resolutions 256,512] [--frames K] [--variants basic|full] "
                                 "[--threads N] [--data DIR] [--csv FILE] [--list]\n");
            return 2;
        }
    }
    const std::vector<SceneSpec> all = allScenes(data);
    if (list) {
        for (const SceneSpec& s : all) std::printf("%-18s %s\n", s.name.c_str(), s.what.c_str());
        return 0;
    }
    auto ctx = Context::create();
    if (!ctx) return std::fprintf(stderr, "vkcollide_bench: %s\n", ctx.error().message().c_str()), 1;
    std::string device = (*ctx)->deviceInfo().name;
    std::replace(device.begin(), device.end(), ',', ';');  // a plain CSV field
    std::ofstream csv(csv_path);
    csv << "device,scene,motion,triangles,objects,variant,backend,resolution,dual,layer_cap,packing,open,async,frame,"
           "sampling_ms,merging_ms,separation_ms,packing_ms,gpu_ms,readback_ms,narrow_ms,update_ms,total_ms,"
           "depth_complexity,layers,peel_passes,collision_rays,downloaded,pot_colliding,tests,pairs,reference_pairs,"
           "recall,precision,gpu_mib,host_peak_mib,narrow_threads,reference_crossing,recall_crossing\n";
    const Progress progress;
    std::printf("%-18s %-14s %-8s %5s %9s %9s %9s %9s %8s %8s %8s\n", "scene", "variant", "backend", "res", "gpu ms", "narrow ms", "total ms",
                "pairs", "recall", "crossing", "prec.");
    for (const std::string& name : scene_names) {
        const auto it = std::find_if(all.begin(), all.end(), [&](const SceneSpec& s) { return s.name == name; });
        if (it == all.end()) return std::fprintf(stderr, "vkcollide_bench: unknown scene '%s' (--list)\n", name.c_str()), 2;
        const SceneSpec& scene = *it;
        const bool deforming = scene.motion == Motion::Deforming;
        const int scene_frames = deforming ? frames + 1 : 1;
        // Meshes and exact references per frame (rigid: one, reused).
        std::vector<std::vector<HostMesh>> meshes;
        std::vector<std::vector<TrianglePair>> reference;
        std::vector<std::vector<TrianglePair>> crossing;  // the reference's crossing pairs (touching ones apart)
        for (int f = 0; f < scene_frames; ++f) {
            progress.show(scene.name + ": building frame " + std::to_string(f) + " and its exact reference");
            auto m = scene.build(f);
            if (!m) return std::fprintf(stderr, "\nvkcollide_bench: %s: %s\n", name.c_str(), m.error().message().c_str()), 1;
            std::vector<test::ReferenceObject> objects;
            for (const HostMesh& h : *m) objects.push_back({&h});
            auto ref = test::computeReferencePairs(objects, {.threads = threads});
            if (!ref) return std::fprintf(stderr, "\nvkcollide_bench: reference: %s\n", ref.error().message().c_str()), 1;
            auto contacts = test::classifyPairs(objects, *ref);
            if (!contacts) return std::fprintf(stderr, "\nvkcollide_bench: contacts: %s\n", contacts.error().message().c_str()), 1;
            std::vector<TrianglePair> cross;
            for (std::size_t k = 0; k < ref->size(); ++k)
                if ((*contacts)[k] == test::Contact::Crossing) cross.push_back((*ref)[k]);
            crossing.push_back(std::move(cross));
            reference.push_back(std::move(*ref));
            meshes.push_back(std::move(*m));
        }
        std::size_t triangles = 0;
        for (const HostMesh& h : meshes[0]) triangles += h.triangleCount();
        const auto pts = points(resolutions, full);
        for (std::size_t pi = 0; pi < pts.size(); ++pi) {
            const Point& p = pts[pi];
            auto world = CollisionWorld::create(**ctx, {.threads = threads});
            if (!world) return std::fprintf(stderr, "\nvkcollide_bench: %s\n", world.error().message().c_str()), 1;
            std::vector<ObjectId> ids;
            for (const HostMesh& h : meshes[0]) {
                ObjectOptions o;
                o.name = h.name;
                o.self_collision = true;
                o.open = p.open;
                auto id = (*world)->addMesh(h, o);
                if (!id) return std::fprintf(stderr, "\nvkcollide_bench: %s\n", id.error().message().c_str()), 1;
                ids.push_back(*id);
            }
            for (int f = 0; f <= frames; ++f) {  // frame 0: warm-up, not written
                progress.show(scene.name + " [" + std::to_string(triangles) + " tris]: point " + std::to_string(pi + 1) + "/" +
                              std::to_string(pts.size()) + " " + p.variant + " " +
                              std::to_string(p.settings.resolution.value_or(0)) + ", frame " + std::to_string(f) + "/" +
                              std::to_string(frames));
                const int mf = deforming ? f % scene_frames : 0;
                const auto t0 = Clock::now();
                if (deforming)
                    for (std::size_t o = 0; o < ids.size(); ++o)
                        if (auto ok = (*world)->updateVertices(ids[o], meshes[mf][o].positions); !ok)
                            return std::fprintf(stderr, "\nvkcollide_bench: %s\n", ok.error().message().c_str()), 1;
                const double update_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                Result<DetectResult> r = Error(ErrorCode::InvalidArgument, "");
                if (p.async) {
                    if (auto ok = (*world)->submit(p.settings); !ok) r = ok.error();
                    else r = (*world)->collect();
                } else {
                    r = (*world)->detect(p.settings);
                }
                const double total_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                if (!r) return std::fprintf(stderr, "\nvkcollide_bench: %s: %s\n", name.c_str(), r.error().message().c_str()), 1;
                if (f == 0) continue;
                const DetectStats& st = r->stats;
                const auto cmp = test::comparePairs(r->pairs, reference[mf]);
                // Recall of crossing pairs: found crossing pairs over all crossing pairs.
                std::size_t found_crossing = 0;
                for (const TrianglePair& c : crossing[mf]) found_crossing += std::binary_search(r->pairs.begin(), r->pairs.end(), c);
                const double recall_crossing = crossing[mf].empty() ? 1.0 : double(found_crossing) / double(crossing[mf].size());
                double gpu_ms = 0;
                for (const auto& pass : st.gpu_passes) gpu_ms += pass.gpu_ms;
                char row[1024];
                std::snprintf(row, sizeof row,
                              "%s,%s,%s,%zu,%zu,%s,%s,%u,%d,%u,%s,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%u,%u,%u,%zu,%zu,%zu,%zu,%zu,%zu,%.6f,%.6f,%.2f,%.1f,%u,%zu,%.6f\n",
                              device.c_str(), scene.name.c_str(), deforming ? "deforming" : "rigid", triangles, ids.size(),
                              p.variant.c_str(), toString(st.backend), st.resolution, st.dual ? 1 : 0, p.settings.layer_cap,
                              p.settings.packing == PackingMethod::Paper ? "paper" : "scan", p.open ? 1 : 0, p.async ? 1 : 0, f,
                              st.sampling_ms, st.merging_ms, st.separation_ms, st.packing_ms, gpu_ms, st.readback_ms, st.narrow_ms,
                              update_ms, total_ms, st.depth_complexity, st.layers, st.peel_passes, st.collision_rays,
                              st.triangles_downloaded, st.potentially_colliding_triangles, st.triangle_tests, r->pairs.size(),
                              reference[mf].size(), cmp.recall, cmp.precision, double(st.gpu_memory_bytes) / (1024.0 * 1024.0),
                              peakHostMiB(), st.narrow_threads, crossing[mf].size(), recall_crossing);
                csv << row;
                csv.flush();
                if (f == frames) {
                    progress.done();
                    std::printf("%-18s %-14s %-8s %5u %9.3f %9.3f %9.3f %9zu %8.4f %8.4f %8.4f\n", scene.name.c_str(), p.variant.c_str(),
                                toString(st.backend), st.resolution, gpu_ms, st.narrow_ms, total_ms, r->pairs.size(), cmp.recall,
                                recall_crossing, cmp.precision);
                    std::fflush(stdout);
                }
            }
        }
    }
    progress.done();
    return 0;
}
