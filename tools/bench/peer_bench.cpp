// vkcollide_peer_bench: times the libraries users pick instead of vkcollide (FCL, Embree,
// CGAL; tools/bench/peers), and vkcollide itself where the library was built, on a list of
// scenes for K frames, and measures their pairs against the exact reference
// (tests/support/exact_reference). Not a test: a program.
//
//   vkcollide_peer_bench [--scenes a,b,...] [--peers a,b,...] [--modes self,between]
//                        [--frames K] [--threads N] [--budget-s S] [--data DIR]
//                        [--csv FILE] [--list] [--help]
//                        [--scene a.obj,b.off[:x,y,z] ... [--sequence [--frame-files K]]] [--resolution N]
//
// --scene: the user's own scene from mesh files (world space, or moved by x,y,z; each OBJ
// group or OFF/PLY file an object), repeatable, named and read as vkcollide_bench --mesh
// names and reads them (user_scene.hpp), so that frontier.sh charts both on one panel; --sequence makes each --scene's files the frames of one
// deforming scene (K files per frame), checked to keep frame 0's topology. With --scene
// only those scenes run (unless --scenes names built-in ones too) and the peers default
// to every peer, vkcollide included.
//
// Prints a summary table (a progress line on stderr) and, with --csv FILE, writes one CSV
// row per (scene, peer, mode, frame), the scene's set (tuning, held-out, user) last; it
// writes no file unless asked. Modes: "self" = pairs within objects too (FCL cannot:
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
#include <unistd.h>
#include <vector>

#include "bench_scenes.hpp"
#include "peers.hpp"
#include "support/exact_reference.hpp"
#include "user_scene.hpp"
#include "vkcollide/scene.hpp"
#ifdef VKCOLLIDE_PEER_BENCH_GPU
#include <chrono>

#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"
#endif

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {

// ---------------------------------------------------------------------------------------
// vkcollide as a peer: the same world-space meshes, a CollisionWorld on the device found
// (lavapipe without a GPU). Frame 0 builds (world, pipelines, uploads); every later frame
// uploads the frame's vertices (build_ms: what a changed scene costs it) and detects
// (query_ms: broad phase on the GPU, readback, exact narrow phase). Settings automatic,
// but for --resolution. The device is made once, outside the timings.

#ifdef VKCOLLIDE_PEER_BENCH_GPU
class VkcollidePeer final : public Peer {
public:
    VkcollidePeer(std::unique_ptr<Context> context, const PeerMode& mode, unsigned threads, std::uint32_t resolution)
        : context_(std::move(context)), mode_(mode), threads_(threads) {
        if (resolution) settings_.resolution = resolution;
    }
    std::string_view name() const noexcept override { return "vkcollide"; }

    Result<PeerFrame> frame(std::span<const HostMesh> meshes) override {
        using Clock = std::chrono::steady_clock;
        const auto ms = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
        PeerFrame out;
        const auto build = Clock::now();
        if (!world_) {
            auto w = CollisionWorld::create(*context_, {.threads = threads_});
            if (!w) return w.error();
            world_ = std::move(*w);
            for (const HostMesh& m : meshes) {
                auto id = world_->addMesh(m, {.name = m.name, .self_collision = mode_.self_collision});
                if (!id) return id.error();
                ids_.push_back(*id);
            }
        } else {
            if (meshes.size() != ids_.size()) return Error(ErrorCode::InvalidArgument, "vkcollide peer: the frame has another object count");
            for (std::size_t i = 0; i < meshes.size(); ++i)
                if (auto ok = world_->updateVertices(ids_[i], meshes[i].positions); !ok) return ok.error();
        }
        out.timings.build_ms = ms(build);
        const auto query = Clock::now();
        auto r = world_->detect(settings_);
        if (!r) return r.error();
        out.timings.query_ms = ms(query);
        out.timings.total_ms = out.timings.build_ms + out.timings.query_ms;
        out.timings.candidates = r->stats.narrow.sap_pairs;
        out.timings.memory_bytes = r->stats.gpu_memory_bytes;
        out.pairs = std::move(r->pairs);  // object ids are 0, 1, ... in the order added
        return out;
    }

private:
    std::unique_ptr<Context> context_;
    PeerMode mode_;
    unsigned threads_;
    DetectSettings settings_;
    std::unique_ptr<CollisionWorld> world_;
    std::vector<ObjectId> ids_;
};

Result<std::unique_ptr<Peer>> createVkcollidePeer(const PeerMode& mode, unsigned threads, std::uint32_t resolution) {
    auto context = Context::create();
    if (!context) return context.error();
    return std::unique_ptr<Peer>(new VkcollidePeer(std::move(*context), mode, threads, resolution));
}
#endif

// ---------------------------------------------------------------------------------------
// Peers

struct PeerSpec {
    std::string name;
    bool self_collision_capable;
    bool deforming_only;  // a variant that only differs from another one when deforming
    std::function<Result<std::unique_ptr<Peer>>(const PeerMode&, unsigned threads)> create;
};

std::vector<PeerSpec> allPeers(std::uint32_t vkcollide_resolution) {
    std::vector<PeerSpec> peers = {
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
#ifdef VKCOLLIDE_PEER_BENCH_GPU
    peers.push_back({"vkcollide", true, false, [vkcollide_resolution](const PeerMode& m, unsigned t) {
                         return createVkcollidePeer(m, t, vkcollide_resolution);
                     }});
#else
    (void)vkcollide_resolution;
#endif
    return peers;
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
    std::string csv;  // empty: no CSV
    bool list = false, help = false;
    // The user's own scenes (--scene), each a list of files; with --sequence each list is
    // the frames of one scene, frame_files files per frame.
    std::vector<std::vector<MeshFile>> user_scenes;
    bool sequence = false;
    std::uint32_t frame_files = 1;
    std::uint32_t resolution = 0;  // the vkcollide peer's; 0: automatic
    bool scenes_given = false, peers_given = false, frames_given = false;
};

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

void printUsage(std::ostream& out) {
    out << "usage: vkcollide_peer_bench [--scenes a,b] [--peers a,b] [--modes self,between] [--frames K]\n"
        << "                            [--threads N] [--budget-s S] [--data DIR] [--csv FILE] [--list] [--help]\n"
        << "                            [--scene a.obj,b.off[:x,y,z] ... [--sequence [--frame-files K]]] [--resolution N]\n";
}

void printHelp() {
    printUsage(std::cout);
    std::cout << "\nTimes FCL, Embree, CGAL and vkcollide on scenes and measures their pairs against the exact\n"
                 "reference (docs/peers.md, docs/cli.md). Prints a summary table; writes no file unless --csv.\n\n"
                 "  --scenes a,b       built-in scenes (--list names them); default spheres-8x10K,bunnies-2x75K,deform-pair-100K\n"
                 "  --scene f1,f2,...  your own scene from mesh files (world space; each OBJ group or OFF/PLY file an\n"
                 "                     object; f:x,y,z moves f's objects by x,y,z); repeatable; alone, only these\n"
                 "                     scenes run, with every peer\n"
                 "  --sequence         each --scene's files are the frames of one deforming scene\n"
                 "  --frame-files K    --sequence: K files per frame (default 1)\n"
                 "  --peers a,b        which peers (--list names them)\n"
                 "  --modes self,between  pairs within objects too, or between objects only (default both)\n"
                 "  --frames K         frames per scene (default 5)\n"
                 "  --threads N        the peers' threads (default: every hardware thread)\n"
                 "  --budget-s S       stop adding frames to a (scene, peer, mode) past S seconds (default 30)\n"
                 "  --data DIR         the CGAL meshes of the built-in scenes (tools/fetch_cgal_data.sh; default data/cgal)\n"
                 "  --resolution N     the vkcollide peer's resolution (default automatic)\n"
                 "  --csv FILE         one row per scene, peer, mode and frame\n"
                 "  --list             list the scenes and peers and exit\n"
                 "  -h, --help         this help\n";
}

std::optional<Options> parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        std::optional<std::string> taken;  // the value read, for the error message
        const auto value = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc) return std::nullopt;
            taken = argv[++i];
            return taken;
        };
        const auto number = [&](auto& out) {
            const std::optional<std::string> v = value();
            if (!v) return false;
            const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), out);
            return ec == std::errc() && end == v->data() + v->size();
        };
        bool ok = true, known = true;
        if (arg == "--scenes") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.scenes = splitList(*v), o.scenes_given = true;
        } else if (arg == "--peers") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.peers = splitList(*v), o.peers_given = true;
        } else if (arg == "--scene") {
            const auto v = value();
            ok = v.has_value();
            if (ok) {
                auto files = parseMeshList(*v);
                if (!files) {
                    std::cerr << "vkcollide_peer_bench: --scene: " << files.error().message() << '\n';
                    return std::nullopt;
                }
                o.user_scenes.push_back(std::move(*files));
            }
        } else if (arg == "--sequence") {
            o.sequence = true;
        } else if (arg == "--frame-files") {
            ok = number(o.frame_files) && o.frame_files >= 1;
        } else if (arg == "--resolution") {
            ok = number(o.resolution);
        } else if (arg == "--modes") {
            const auto v = value();
            ok = v.has_value();
            if (ok) o.modes = splitList(*v);
        } else if (arg == "--frames") {
            ok = number(o.frames) && o.frames >= 1;
            o.frames_given = true;
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
        } else if (arg == "--help" || arg == "-h") {
            o.help = true;
        } else {
            ok = known = false;
        }
        if (!ok) {
            // Flags cannot fail: a known option failed on its value, or has none.
            if (!known) std::cerr << "vkcollide_peer_bench: unknown option " << arg << '\n';
            else if (taken) std::cerr << "vkcollide_peer_bench: " << arg << ": bad value '" << *taken << "'\n";
            else std::cerr << "vkcollide_peer_bench: " << arg << " needs a value\n";
            printUsage(std::cerr);
            return std::nullopt;
        }
    }
    if (o.sequence && o.user_scenes.empty()) {
        std::cerr << "vkcollide_peer_bench: --sequence makes the files of each --scene frames: give --scene too\n";
        return std::nullopt;
    }
    for (const auto& files : o.user_scenes) {
        if (o.sequence && (files.size() % o.frame_files != 0 || files.size() / o.frame_files < 2)) {
            std::cerr << "vkcollide_peer_bench: --sequence: " << files.size() << " files do not make two or more whole frames of "
                      << o.frame_files << " (--frame-files)\n";
            return std::nullopt;
        }
    }
    if (!o.user_scenes.empty()) {
        if (!o.scenes_given) o.scenes.clear();
        if (!o.peers_given) o.peers.push_back("vkcollide");
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

// One line on stderr, rewritten in place; only on a terminal (a log would get one long
// line of carriage returns).
class Progress {
public:
    void show(const std::string& line) {
        if (!tty_) return;
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
    bool tty_ = ::isatty(2) != 0;
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
    if (opt.help) {
        printHelp();
        return 0;
    }
    const std::vector<SceneSpec> scenes = allScenes(opt.data);
    const std::vector<PeerSpec> peers = allPeers(opt.resolution);
    if (opt.list) {
        for (const SceneSpec& s : scenes) {
            std::cout << s.name << "  " << setName(s.set) << "  " << motionName(s.motion) << "  " << s.what << '\n';
        }
        for (const PeerSpec& p : peers) std::cout << p.name << '\n';
        return 0;
    }
    std::vector<SceneSpec> user_scenes;
    for (const std::vector<MeshFile>& files : opt.user_scenes) {
        auto s = userScene(files, opt.sequence ? opt.frame_files : 0, SceneSet::User);
        if (!s) {
            std::cerr << "vkcollide_peer_bench: --scene: " << s.error().message() << '\n';
            return 1;
        }
        user_scenes.push_back(std::move(*s));
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
    for (const SceneSpec& s : user_scenes) chosen_scenes.push_back(&s);
    std::vector<const PeerSpec*> chosen_peers;
    for (const std::string& name : opt.peers) {
        const auto it = std::find_if(peers.begin(), peers.end(), [&](const PeerSpec& p) { return p.name == name; });
        if (it == peers.end()) {
            std::cerr << "vkcollide_peer_bench: unknown peer '" << name << "' (--list)\n";
            return 2;
        }
        chosen_peers.push_back(&*it);
    }

    std::ofstream csv;  // written only with --csv
    if (!opt.csv.empty()) {
        csv.open(opt.csv);
        if (!csv) {
            std::cerr << "vkcollide_peer_bench: --csv: cannot write " << opt.csv << '\n';
            return 1;
        }
    }
    const std::string host =
        cpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
    csv << "# vkcollide_peer_bench: " << host << "; peers run with " << opt.threads << " threads\n";
    csv << "scene,triangles,objects,peer,mode,frame,build_ms,query_ms,total_ms,pairs,recall,precision,"
           "candidates,memory_mb,reference_pairs,threads,set\n";
    std::cout << "host: " << host << "; peers run with " << opt.threads << " threads\n";

    Progress progress;
    std::vector<Row> rows;
    int failures = 0;
    for (const SceneSpec* scene : chosen_scenes) {
        // Moving scenes too: the peers get world-space meshes, rebuilt every frame.
        const bool deforming = scene->motion != Motion::Rigid;
        // A --sequence runs its frames once each, unless --frames asks for fewer.
        const bool user_sequence =
            opt.sequence && std::any_of(user_scenes.begin(), user_scenes.end(), [&](const SceneSpec& u) { return &u == scene; });
        const int frame_count = user_sequence ? (opt.frames_given ? std::min(opt.frames, scene->frames) : scene->frames) : opt.frames;
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
                        << row.reference_pairs << ',' << opt.threads << ',' << setName(scene->set) << '\n';
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
        // Pair counts are counts, not timings: the frames' own, as a range when they differ.
        std::size_t pairs_lo = g.front()->pairs, pairs_hi = pairs_lo, ref_lo = g.front()->reference_pairs, ref_hi = ref_lo;
        for (const Row* r : g) {
            pairs_lo = std::min(pairs_lo, r->pairs), pairs_hi = std::max(pairs_hi, r->pairs);
            ref_lo = std::min(ref_lo, r->reference_pairs), ref_hi = std::max(ref_hi, r->reference_pairs);
        }
        const auto range = [](std::size_t lo, std::size_t hi) {
            return lo == hi ? std::to_string(lo) : std::to_string(lo) + "-" + std::to_string(hi);
        };
        for (const Row* r : g) {
            min_recall = std::min(min_recall, r->recall);
            min_precision = std::min(min_precision, r->precision);
            if (deforming && r->frame == 0 && g.size() > 1) continue;
            build.push_back(r->timings.build_ms);
            query.push_back(r->timings.query_ms);
            total.push_back(r->timings.total_ms);
        }
        char line[512];
        std::snprintf(line, sizeof line, "%-18s %-9zu %-13s %-18s %6zu %10.2f %9.2f %9.2f %9.2f %9s %11s  %.6f  %.6f",
                      g.front()->scene.c_str(), g.front()->triangles, g.front()->peer.c_str(), g.front()->mode.c_str(), g.size(),
                      g.front()->timings.build_ms, median(build), median(query), median(total), range(pairs_lo, pairs_hi).c_str(),
                      range(ref_lo, ref_hi).c_str(), min_recall, min_precision);
        std::cout << line << '\n';
    }
    std::cout << "\ntimes: medians; deforming: over frames >= 1 (build0 = the first frame's build); pairs and ref_pairs:\n"
                 "the count found and the exact count (lowest-highest over the frames where they differ); recall and\n"
                 "precision: the lowest over the frames."
              << (opt.csv.empty() ? std::string() : " CSV: " + opt.csv) << '\n';
    return failures ? 1 : 0;
}
