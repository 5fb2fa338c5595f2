// The files `vkcollide detect` writes frame by frame: --pairs (CSV of global triangle
// numbers) and --json (objects, settings, then per frame the pairs, responses, excluded
// objects and statistics; docs/cli.md has the layout and a sample), and --stats at the end.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "cli/json.hpp"
#include "cli/options.hpp"
#include "cli/scene.hpp"

namespace cli {

class Report {
public:
    // Opens the files asked for and writes the JSON's head. `used`: the settings frame 0
    // resolves to. Error: IoError naming the option and the file.
    static vkcollide::Result<std::unique_ptr<Report>> open(const CommandLine& line, const Scene& scene, const std::string& device,
                                                           const vkcollide::DetectSettings& used);
    ~Report();
    Report(const Report&) = delete;
    Report& operator=(const Report&) = delete;

    // One frame's results (--sequence: every frame; otherwise the last detection only).
    void frame(std::size_t frame, const Scene& scene, const vkcollide::DetectResult& result);
    // Ends the JSON and closes the files. Error: IoError when a write failed (disk full).
    vkcollide::Result<void> close();

private:
    explicit Report(const CommandLine& line) : line_(line) {}
    const CommandLine& line_;
    std::FILE* pairs_ = nullptr;
    std::FILE* proximity_ = nullptr;
    std::FILE* json_file_ = nullptr;
    std::unique_ptr<JsonWriter> json_;
};

// --stats: one detection's statistics as a JSON object. Error: IoError naming the file.
vkcollide::Result<void> writeStatsFile(const std::string& path, const Scene& scene, const vkcollide::DetectResult& result);

}  // namespace cli
