#include "peer_bench_options.hpp"

#include <algorithm>
#include <charconv>
#include <iostream>
#include <sstream>
#include <thread>

namespace vkcollide::bench::peer_bench {
namespace {

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

}  // namespace

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

}  // namespace vkcollide::bench::peer_bench
