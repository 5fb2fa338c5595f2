// What the samples and `vkcollide detect --sequence` write: PNG frames, one CSV line per
// frame with the paper's Table 1 columns and the stage times, a line per frame on stdout, a progress line on stderr and
// a summary in the layout of the paper's Table 1.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "vkcollide/world.hpp"

namespace render {

// Writes RGBA8 pixels (rows top to bottom) as an RGB PNG with libpng. False on failure.
bool writePng(const std::string& path, std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgba);

// "<folder>/frame_0007.png"
std::string framePath(const std::string& folder, int frame);

// The names of the two host times each CSV line ends its fixed columns with: the
// samples' simulation and rendering, the command-line tool's file reading and PNG.
struct HostTimeColumns {
    std::string first = "sim_ms", second = "render_ms";
};

class FrameLog {
public:
    // scene_columns: the program's own per-frame values (contacts, events), appended to
    // each CSV line and printed after the statistics. csv_path empty: no CSV, the lines only.
    FrameLog(const std::string& csv_path, std::vector<std::string> scene_columns, int frames, bool quiet,
             const HostTimeColumns& host_columns = {});
    ~FrameLog();
    FrameLog(const FrameLog&) = delete;
    FrameLog& operator=(const FrameLog&) = delete;

    // One detected frame. first_ms / second_ms: the two host times (HostTimeColumns).
    void record(int frame, const vkcollide::DetectResult& result, std::span<const double> scene_values, double first_ms,
                double second_ms);
    // Prints the summary: means over the frames after the first (which also builds the
    // pipelines and buffers) and the maxima, in the columns of the paper's Table 1.
    void finish(const std::string& scene_name);

private:
    void progress(int frame);

    std::FILE* csv_ = nullptr;
    std::vector<std::string> scene_columns_;
    int frames_;
    bool quiet_, tty_;
    std::chrono::steady_clock::time_point start_;
    struct Row {
        double values[11];
    };
    std::vector<Row> rows_;
    std::string method_;  // the method of the frames recorded, for the summary
    int last_percent_ = -1;
};

// The GPU figure of the lines, the CSV's gpu_ms and the summary: the GPU stages of the
// method that ran (peeling: sampling + merging + separation, the paper's Table 1 column;
// reliable: the front + footprints + pairing + filtering). Reduce: packing + readback.
double gpuMs(const vkcollide::DetectStats& stats);
double reduceMs(const vkcollide::DetectStats& stats);
// The sampling backend that ran, "none" for the reliable method (it samples no rays).
const char* backendName(const vkcollide::DetectStats& stats);

// Milliseconds since `start`.
double msSince(std::chrono::steady_clock::time_point start);

}  // namespace render
