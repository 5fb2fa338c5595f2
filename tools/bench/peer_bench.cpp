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
//
// Here: choosing the scenes and peers, building each scene's frames and exact references,
// and running every peer on them; the options, the peers and the output (CSV, summary) are
// in peer_bench_options.*, peer_bench_peers.* and peer_bench_output.*.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_scenes.hpp"
#include "peer_bench_options.hpp"
#include "peer_bench_output.hpp"
#include "peer_bench_peers.hpp"
#include "peers.hpp"
#include "support/exact_reference.hpp"
#include "user_scene.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;
using namespace vkcollide::bench::peer_bench;

namespace {

Result<std::vector<TrianglePair>> referencePairs(const std::vector<HostMesh>& meshes, bool self, unsigned threads) {
    std::vector<test::ReferenceObject> objects;
    for (const HostMesh& m : meshes) objects.push_back({&m, test::kIdentityTransform, self});
    test::ReferenceOptions options;
    options.threads = threads;
    return test::computeReferencePairs(objects, options);
}

// A scene's meshes and exact references per frame (rigid scenes: one frame, reused).
struct PreparedScene {
    std::vector<std::vector<HostMesh>> frames;
    std::map<std::pair<int, bool>, std::vector<TrianglePair>> references;  // by (frame, self)
};

// Nullopt after saying on stderr why the scene is skipped.
std::optional<PreparedScene> prepareScene(const SceneSpec& scene, int frame_count, bool deforming, const Options& opt, Progress& progress) {
    PreparedScene out;
    for (int f = 0; f < (deforming ? frame_count : 1); ++f) {
        progress.show(scene.name + ": building frame " + std::to_string(f));
        Result<std::vector<HostMesh>> meshes = [&]() -> Result<std::vector<HostMesh>> {
            auto objects = scene.build(f % scene.frames);
            if (!objects) return objects.error();
            return worldMeshes(*objects);
        }();
        if (!meshes) {
            progress.done();
            std::cerr << "vkcollide_peer_bench: scene " << scene.name << " skipped: " << meshes.error().message() << '\n';
            return std::nullopt;
        }
        out.frames.push_back(std::move(*meshes));
        for (const std::string& mode : opt.modes) {
            const bool self = mode == "self";
            progress.show(scene.name + ": exact reference, frame " + std::to_string(f) + ", " + mode);
            Result<std::vector<TrianglePair>> ref = referencePairs(out.frames.back(), self, opt.threads);
            if (!ref) {
                progress.done();
                std::cerr << "vkcollide_peer_bench: reference for " << scene.name << ": " << ref.error().message() << '\n';
                return std::nullopt;
            }
            out.references[{f, self}] = std::move(*ref);
        }
    }
    return out;
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
    writeCsvHeader(csv, host, opt.threads);
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
        const std::optional<PreparedScene> prepared = prepareScene(*scene, frame_count, deforming, opt, progress);
        if (!prepared) {
            ++failures;
            continue;
        }
        const auto& [frames, references] = *prepared;
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
                    writeCsvRow(csv, row, opt.threads, setName(scene->set));
                    rows.push_back(row);
                }
            }
        }
    }
    progress.done();

    printSummary(rows, opt.csv);
    return failures ? 1 : 0;
}
