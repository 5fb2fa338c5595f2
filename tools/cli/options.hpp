// `vkcollide detect`'s command line: what it asks for (CommandLine) and the one table of
// options that parsing, --help, the error messages and the JSON's settings all read.
//
// Adding a DetectSettings field to the tool is one line in the table (options.cpp):
//   {"--name", "ARG", Section::Settings, "what it does", "what it costs", setting<&DetectSettings::group, &Group::field>,
//    "field", "group.field", show<&DetectSettings::group, &Group::field>},
// (a top-level field: setting<&DetectSettings::field>), for a field of type uint32, float,
// bool (a flag: settingFlag), std::array<float, N>, std::optional of those, or an enum with
// toString (values.hpp). "field" is its JSON key, "group.field" its path.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli/values.hpp"
#include "vkcollide/world.hpp"

namespace cli {

// What one file's objects get (an OBJ file may hold several objects: its o/g groups).
struct FileSlot {
    vkcollide::ObjectOptions options;  // options.name empty: the names the file gives
    bool gpu_mesh = false;             // added as engine-owned buffers (addGpuMesh)
    bool self_listed = false;          // named by a --self list
};

struct CommandLine {
    std::vector<std::string> files;  // as given
    vkcollide::DetectSettings settings;
    // One per file, or per file of a frame with --sequence (the file's place in each frame).
    std::vector<FileSlot> slots;
    bool sequence = false;
    std::uint32_t files_per_frame = 1;  // --sequence: each frame is this many consecutive files
    std::uint32_t repeats = 1;          // --frames: detections of the same scene
    std::uint32_t threads = 0;          // 0: every hardware thread
    std::string device;
    bool robust_access = true;
    bool validation = false;
    bool quiet = false;
    std::string pairs_path, stats_path, json_path, csv_path, png_path, proximity_path;
    std::uint32_t png_width = 800, png_height = 600;
    std::optional<std::array<float, 3>> view;  // from the scene's centre towards the eye
    bool rays = false;
    // The options given, in order, with their arguments (for the JSON and for naming the
    // option a library error is about).
    std::vector<std::pair<std::string, std::string>> given;

    // Frames: the sequence's, or the repeats of one scene.
    std::size_t frameCount() const { return sequence ? files.size() / files_per_frame : repeats; }
    // The files of frame f (all files without --sequence).
    std::span<const std::string> frameFiles(std::size_t f) const;
};

struct Parsed {
    enum class Kind {
        Run,    // `line` holds the command line
        Help,   // --help: print the help, exit 0
        Error,  // a bad value: print `error` (it names the option), exit 1
        Usage,  // an unknown option or no file: print `error` and the usage, exit 2
    };
    Kind kind = Kind::Run;
    CommandLine line;
    std::string error;
};

// Parses the arguments after `detect`.
Parsed parseDetect(std::span<const char* const> args);

// The whole help (`vkcollide --help`, `vkcollide detect --help`).
void printHelp(std::FILE* out);
// The usage lines only (after an unknown option).
void printUsage(std::FILE* out);

// A library error about the settings, with the options that set what it names put first:
// "--resolution 100: resolution 100 is not a power of two in [4, 16384]".
std::string nameSettingOptions(const CommandLine& line, const std::string& message);

// Every DetectSettings field as a JSON object member list ("\"resolution\": 256", ...), in
// the table's order; unset automatic fields are null.
std::vector<std::pair<std::string, std::string>> settingsJson(const vkcollide::DetectSettings& settings);

}  // namespace cli
