// vkcollide_peer_bench: times the libraries users pick instead of vkcollide (FCL, Embree,
// CGAL; tools/bench/peers) on a list of scenes for K frames, and measures their pairs
// against the exact reference (tests/support/exact_reference). Not a test: a program.
//
//   vkcollide_peer_bench [--scenes a,b,...] [--peers a,b,...] [--modes self,between]
//                        [--frames K] [--threads N] [--budget-s S] [--data DIR]
//                        [--csv FILE] [--list]
//
// Writes one CSV row per (scene, peer, mode, frame) and prints a summary table; a
// progress line goes to stderr. Modes: "self" = pairs within objects too (FCL cannot:
// skipped), "between" = pairs between objects only; each scene is rigid (every frame
// builds and queries from scratch) or deforming (frame 0 builds, later frames move every
// vertex and the peer refits or rebuilds). See docs/peers.md.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_scenes.hpp"
#include "peers.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {



// ---------------------------------------------------------------------------------------
// Peers

struct PeerSpec {
    std::string name;
    bool self_collision_capable;
    bool deforming_only;  // a variant that only differs from another one when deforming
    std::function<Result<std::unique_ptr<Peer>>(const PeerMode&, unsigned threads)> create;
};

std::vector<PeerSpec> allPeers() {
    return {
        {"fcl-aabb", false, false, [](const PeerMode& m, unsigned t) { return createFclPeer(FclVolume::Aabb, m, t); }},
        {"fcl-obbrss", false, false,
         [](const PeerMode& m, unsigned t) { return createFclPeer(FclVolume::Obbrss, m, t); }},
        {"embree", true, false,
         [](const PeerMode& m, unsigned t) { return createEmbreePeer(EmbreeUpdate::Rebuild, m, t); }},
        {"embree-refit", true, true,
         [](const PeerMode& m, unsigned t) { return createEmbreePeer(EmbreeUpdate::Refit, m, t); }},
        {"cgal", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Exact, true}, m, t);
         }},
        {"cgal-seqbox", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Exact, false}, m, t);
         }},
        {"cgal-epick", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Epick, true}, m, t);
         }},
    };
}

// ---------------------------------------------------------------------------------------
// Options

struct Options {
    std::vector<std::string> scenes = {"spheres-8x10K", "bunnies-2x75K", "deform-pair-100K"};
    std::vector<std::string> peers = {"fcl-aabb", "fcl-obbrss", "embree", "embree-refit", "cgal"};
    std::vector<std::string> modes = {"self", "between"};
    int frames = 5;
    unsigned threads = 0;
    double budget_s = 30;  // per (scene, peer, mode): stop adding frames past this
    std::string data = "data/cgal";
    std::string csv = "peer_bench.csv";
    bool list = false;
};

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::optional<Options> parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const auto value = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc) return std::nullopt;
            return std::string(argv[++i]);
        };
        const auto number = [&](auto& out) {
            const std::optional<std::string> v = value();
            if (!v) return false;
            const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), out);
            return ec == std::errc() && end == v->data() + v->size();
        };
        bool ok = true;
        if (arg == "--scenes") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.scenes = splitList(*v);
        } else if (arg == "--peers") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.peers = splitList(*v);
        } else if (arg == "--modes") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.modes = splitList(*v);
        } else if (arg == "--frames") {
            ok = number(o.frames) && o.frames >= 1;
        } else if (arg == "--threads") {
            ok = number(o.threads);
        } else if (arg == "--budget-s") {
            ok = number(o.budget_s) && o.budget_s > 0;
        } else if (arg == "--data") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.data = *v;
        } else if (arg == "--csv") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.csv = *v;
        } else if (arg == "--list") {
            o.list = true;
        } else {
            ok = false;
        }
        if (!ok) {
            std::cerr
                << "vkcollide_peer_bench: bad argument '" << arg << "'\n"
                << "usage: vkcollide_peer_bench [--scenes a,b] [--peers a,b] [--modes self,between] [--frames K]\n"
                << "                            [--threads N] [--budget-s S] [--data DIR] [--csv FILE] [--list]\n";
            return std::nullopt;
        }
    }
    for (const std::string& m : o.modes) {
        if (m != "self" && m != "between") {
            std::cerr << "vkcollide_peer_bench: unknown mode '" << m << "' (self, between)\n";
            return std::nullopt;
        }
    }
    if (o.threads == 0) o.threads = std::max(1u, std::thread::hardware_concurrency());
    return o;
}

// ---------------------------------------------------------------------------------------
// Running

struct Row {
    std::string scene;
    std::size_t triangles = 0, objects = 0;
    std::string peer, mode;
    int frame = 0;
    PeerTimings timings;
    std::size_t pairs = 0, reference_pairs = 0;
    double recall = 1, precision = 1;
};

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    }
    return "unknown CPU";
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

class Progress {
public:
    void show(const std::string& line) {
        std::string padded = line;
        if (padded.size() < width_) padded.append(width_ - padded.size(), ' ');
        width_ = line.size();
        std::cerr << '\r' << padded << std::flush;
    }
    void done() {
        if (width_) std::cerr << '\n';
        width_ = 0;
    }

private:
    std::size_t width_ = 0;
};

Result<std::vector<TrianglePair>> referencePairs(const std::vector<HostMesh>& meshes, bool self, unsigned threads) {
    std::vector<test::ReferenceObject> objects;
    for (const HostMesh& m : meshes) objects.push_back({&m, test::kIdentityTransform, self});
    test::ReferenceOptions options;
    options.threads = threads;
    return test::computeReferencePairs(objects, options);
}

}  // namespace

int main(int argc, char** argv) {
    const std::optional<Options> parsed = parseOptions(argc, argv);
    if (!parsed) return 2;
    const Options& opt = *parsed;
    const std::vector<SceneSpec> scenes = allScenes(opt.data);
    const std::vector<PeerSpec> peers = allPeers();
    if (opt.list) {
        for (const SceneSpec& s : scenes) {
            std::cout << s.name << "  " << setName(s.set) << "  " << motionName(s.motion) << "  " << s.what << '\n';
        }
        for (const PeerSpec& p : peers) std::cout << p.name << '\n';
        return 0;
    }
    std::vector<const SceneSpec*> chosen_scenes;
    for (const std::string& name : opt.scenes) {
        const auto it = std::find_if(scenes.begin(), scenes.end(), [&](const SceneSpec& s) { return s.name == name; });
        if (it == scenes.end()) {
            std::cerr << "vkcollide_peer_bench: unknown scene '" << name << "' (--list)\n";
            return 2;
        }
        chosen_scenes.push_back(&*it);
    }
    std::vector<const PeerSpec*> chosen_peers;
    for (const std::string& name : opt.peers) {
        const auto it = std::find_if(peers.begin(), peers.end(), [&](const PeerSpec& p) { return p.name == name; });
        if (it == peers.end()) {
            std::cerr << "vkcollide_peer_bench: unknown peer '" << name << "' (--list)\n";
            return 2;
        }
        chosen_peers.push_back(&*it);
    }

    std::ofstream csv(opt.csv);
    if (!csv) {
        std::cerr << "vkcollide_peer_bench: cannot write " << opt.csv << '\n';
        return 1;
    }
    const std::string host =
        cpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
    csv << "# vkcollide_peer_bench: " << host << "; peers run with " << opt.threads << " threads\n";
    csv << "scene,triangles,objects,peer,mode,frame,build_ms,query_ms,total_ms,pairs,recall,precision,"
           "candidates,memory_mb,reference_pairs,threads\n";
    std::cout << "host: " << host << "; peers run with " << opt.threads << " threads\n";

    Progress progress;
    std::vector<Row> rows;
    int failures = 0;
    for (const SceneSpec* scene : chosen_scenes) {
        // Moving scenes too: the peers get world-space meshes, rebuilt every frame.
        const bool deforming = scene->motion != Motion::Rigid;
        const int frame_count = opt.frames;
        // Meshes and exact references per frame (rigid scenes: one frame, reused).
        std::vector<std::vector<HostMesh>> frames;
        std::map<std::pair<int, bool>, std::vector<TrianglePair>> references;
        bool scene_ok = true;
        for (int f = 0; f < (deforming ? frame_count : 1) && scene_ok; ++f) {
            progress.show(scene->name + ": building frame " + std::to_string(f));
            Result<std::vector<HostMesh>> meshes = [&]() -> Result<std::vector<HostMesh>> {
                auto objects = scene->build(f % scene->frames);
                if (!objects) return objects.error();
                return worldMeshes(*objects);
            }();
            if (!meshes) {
                progress.done();
                std::cerr << "vkcollide_peer_bench: scene " << scene->name << " skipped: " << meshes.error().message()
                          << '\n';
                scene_ok = false;
                break;
            }
            frames.push_back(std::move(*meshes));
            for (const std::string& mode : opt.modes) {
                const bool self = mode == "self";
                progress.show(scene->name + ": exact reference, frame " + std::to_string(f) + ", " + mode);
                Result<std::vector<TrianglePair>> ref = referencePairs(frames.back(), self, opt.threads);
                if (!ref) {
                    progress.done();
                    std::cerr << "vkcollide_peer_bench: reference for " << scene->name << ": " << ref.error().message()
                              << '\n';
                    scene_ok = false;
                    break;
                }
                references[{f, self}] = std::move(*ref);
            }
        }
        if (!scene_ok) {
            ++failures;
            continue;
        }
        std::size_t triangles = 0;
        for (const HostMesh& m : frames.front()) triangles += m.triangleCount();

        for (const PeerSpec* peer_spec : chosen_peers) {
            if (peer_spec->deforming_only && !deforming) continue;
            for (const std::string& mode_name : opt.modes) {
                const bool self = mode_name == "self";
                if (self && !peer_spec->self_collision_capable) continue;
                // The peers see world-space meshes: a moving scene is a deforming one to them.
                const PeerMode mode{self, deforming ? Motion::Deforming : Motion::Rigid};
                const std::string mode_label = std::string(deforming ? "deforming-" : "rigid-") + mode_name;
                Result<std::unique_ptr<Peer>> peer = peer_spec->create(mode, opt.threads);
                if (!peer) {
                    progress.done();
                    std::cerr << "vkcollide_peer_bench: " << peer_spec->name << ": " << peer.error().message() << '\n';
                    ++failures;
                    continue;
                }
                double spent_ms = 0;
                const int min_frames = deforming ? std::min(frame_count, 2) : 1;
                for (int f = 0; f < frame_count; ++f) {
                    if (f >= min_frames && spent_ms > opt.budget_s * 1000) break;
                    progress.show(scene->name + " | " + peer_spec->name + " | " + mode_label + " | frame " +
                                  std::to_string(f + 1) + "/" + std::to_string(frame_count));
                    const std::vector<HostMesh>& meshes = frames[deforming ? f : 0];
                    Result<PeerFrame> result = (*peer)->frame(meshes);
                    if (!result) {
                        progress.done();
                        std::cerr << "vkcollide_peer_bench: " << peer_spec->name << " on " << scene->name << ": "
                                  << result.error().message() << '\n';
                        ++failures;
                        break;
                    }
                    spent_ms += result->timings.total_ms;
                    const std::vector<TrianglePair>& truth = references.at({deforming ? f : 0, self});
                    const test::PairComparison cmp = test::comparePairs(result->pairs, truth);
                    Row row;
                    row.scene = scene->name;
                    row.triangles = triangles;
                    row.objects = meshes.size();
                    row.peer = peer_spec->name;
                    row.mode = mode_label;
                    row.frame = f;
                    row.timings = result->timings;
                    row.pairs = result->pairs.size();
                    row.reference_pairs = truth.size();
                    row.recall = cmp.recall;
                    row.precision = cmp.precision;
                    csv << row.scene << ',' << row.triangles << ',' << row.objects << ',' << row.peer << ',' << row.mode
                        << ',' << row.frame << ',' << fixed(row.timings.build_ms, 3) << ','
                        << fixed(row.timings.query_ms, 3) << ',' << fixed(row.timings.total_ms, 3) << ',' << row.pairs
                        << ',' << fixed(row.recall, 6) << ',' << fixed(row.precision, 6) << ','
                        << row.timings.candidates << ','
                        << fixed(static_cast<double>(row.timings.memory_bytes) / 1048576.0, 1) << ','
                        << row.reference_pairs << ',' << opt.threads << '\n';
                    csv.flush();
                    rows.push_back(row);
                }
            }
        }
    }
    progress.done();

    // Summary: medians per (scene, peer, mode); deforming scenes over frames >= 1 (the
    // per-frame update), with frame 0's build shown apart.
    std::cout << "\n"
              << "scene              tris      peer          mode               frames  build0_ms  build_ms  query_ms  "
                 "total_ms     pairs   ref_pairs  recall    precision\n";
    std::map<std::tuple<std::string, std::string, std::string>, std::vector<const Row*>> groups;
    std::vector<std::tuple<std::string, std::string, std::string>> order;
    for (const Row& r : rows) {
        const auto key = std::make_tuple(r.scene, r.peer, r.mode);
        if (!groups.count(key)) order.push_back(key);
        groups[key].push_back(&r);
    }
    for (const auto& key : order) {
        const std::vector<const Row*>& g = groups[key];
        const bool deforming = g.front()->mode.rfind("deforming", 0) == 0;
        std::vector<double> build, query, total;
        double min_recall = 1, min_precision = 1;
        for (const Row* r : g) {
            min_recall = std::min(min_recall, r->recall);
            min_precision = std::min(min_precision, r->precision);
            if (deforming && r->frame == 0 && g.size() > 1) continue;
            build.push_back(r->timings.build_ms);
            query.push_back(r->timings.query_ms);
            total.push_back(r->timings.total_ms);
        }
        char line[512];
        std::snprintf(line, sizeof line, "%-18s %-9zu %-13s %-18s %6zu %10.2f %9.2f %9.2f %9.2f %9zu %11zu  %.6f  %.6f",
                      g.front()->scene.c_str(), g.front()->triangles, g.front()->peer.c_str(), g.front()->mode.c_str(),
                      g.size(), g.front()->timings.build_ms, median(build), median(query), median(total),
                      g.back()->pairs, g.back()->reference_pairs, min_recall, min_precision);
        std::cout << line << '\n';
    }
    std::cout << "\nmedians; deforming: over frames >= 1 (build0 = the first frame's build); recall and precision:\n"
                 "the lowest over the frames. CSV: "
              << opt.csv << '\n';
    return failures ? 1 : 0;
}
