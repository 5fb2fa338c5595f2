// vkcollide_bench's command line: its options, their defaults and --help.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "user_scene.hpp"

namespace vkcollide::bench {

struct Options {
    std::string set = "all", data = "data/cgal", variants = "default,mitigations,resolutions";
    // Built-in scenes: vkcollide_bench.csv and bench-cache/ unless told otherwise. With --mesh:
    // no file unless --csv or --cache names one.
    std::string csv = "vkcollide_bench.csv", cache = "bench-cache";
    double warmup_ms = 0;  // untimed detections per scene and variant before its frames
    std::string pipeline_stats;  // every pipeline's compiler statistics at the end (driver permitting), empty: none
    std::string profile;   // long-form per-stage times (GPU passes, narrow-phase stages), empty: none
    std::vector<std::string> scenes;
    std::vector<MeshFile> meshes;  // --mesh: one scene of the user's own files
    std::vector<std::uint32_t> resolutions = {512, 1024, 2048, 4096};
    double scale = 1.0;
    int frames = 3;
    unsigned threads = 0;
    bool list = false;
    bool reference_only = false;
    std::string write_obj;  // --write-obj DIR: the chosen scenes as OBJ files of world vertices, nothing else
    bool help = false;
};

// The options, or nothing after printing what is wrong (and the usage) to stderr: exit 2.
std::optional<Options> parseOptions(int argc, char** argv);

void printUsage(std::FILE* out);
void printHelp();

}  // namespace vkcollide::bench
