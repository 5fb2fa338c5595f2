// vkcollide_peer_bench's command line (peer_bench.cpp says what each option does).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "user_scene.hpp"

namespace vkcollide::bench::peer_bench {

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

// The options, checked, with the defaults that depend on others filled in (--scene alone:
// only those scenes, every peer; --threads 0: every hardware thread). Nullopt after
// printing why to stderr.
std::optional<Options> parseOptions(int argc, char** argv);
void printHelp();

}  // namespace vkcollide::bench::peer_bench
