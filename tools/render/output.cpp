#include "render/output.hpp"

#include <algorithm>
#include <png.h>
#include <unistd.h>

#include "render/engine.hpp"

namespace render {
namespace {

// "12K", "0.4K", "950": the paper's Table 1 style.
std::string count(double v) {
    char buf[32];
    if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", v / 1e6);
    else if (v >= 1e4) std::snprintf(buf, sizeof buf, "%.0fK", v / 1e3);
    else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.1fK", v / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
}

}  // namespace

// Table 1's timing columns. Peeling: GPU = object sampling + ray merging + primitive
// separation, Reduce = packing (texture reduction) + readback. Reliable: GPU = the front
// (sampling_ms) + footprints + pairing + filtering, Reduce = the readback of the pairs.
// CPU = the narrow phase.
double gpuMs(const vkcollide::DetectStats& s) {
    if (s.method == vkcollide::DetectMethod::Reliable) return s.sampling_ms + s.reliable.footprints_ms + s.reliable.pairing_ms + s.reliable.filtering_ms;
    return s.sampling_ms + s.peeling.merging_ms + s.peeling.separation_ms;
}
double reduceMs(const vkcollide::DetectStats& s) { return s.peeling.packing_ms + s.readback_ms; }

const char* backendName(const vkcollide::DetectStats& s) {
    return s.method == vkcollide::DetectMethod::Reliable ? "none" : vkcollide::toString(s.peeling.backend);
}

bool writePng(const std::string& path, std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgba) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = width;
    image.height = height;
    image.format = PNG_FORMAT_RGB;
    image.flags = PNG_IMAGE_FLAG_FAST;  // frames for an animation: speed over size
    std::vector<std::uint8_t> rgb(std::size_t{width} * height * 3);
    for (std::size_t i = 0, n = std::size_t{width} * height; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = rgba[i * 4 + c];
    const int ok = png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), 0, nullptr);
    png_image_free(&image);
    return ok != 0;
}

std::string framePath(const std::string& folder, int frame) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/frame_%04d.png", frame);
    return folder + buf;
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

FrameLog::FrameLog(const std::string& csv_path, std::vector<std::string> scene_columns, int frames, bool quiet,
                   const HostTimeColumns& host_columns)
    : scene_columns_(std::move(scene_columns)), frames_(frames), quiet_(quiet), tty_(::isatty(2) != 0),
      start_(std::chrono::steady_clock::now()) {
    if (csv_path.empty()) return;  // the lines and the summary only
    csv_ = std::fopen(csv_path.c_str(), "w");
    if (!csv_) die("cannot write " + csv_path);
    std::fprintf(csv_,
                 "frame,triangles,collision_rays,triangles_downloaded,potentially_colliding_triangles,triangle_tests,"
                 "positive_tests,pairs,gpu_ms,reduce_ms,cpu_ms,total_ms,sampling_ms,merging_ms,separation_ms,packing_ms,"
                 "readback_ms,narrow_ms,resolution,depth_complexity,layers,peel_passes,layers_short,backend,method,footprints_ms,"
                 "pairing_ms,filtering_ms,%s,%s",
                 host_columns.first.c_str(), host_columns.second.c_str());
    for (const std::string& c : scene_columns_) std::fprintf(csv_, ",%s", c.c_str());
    std::fprintf(csv_, "\n");
}

FrameLog::~FrameLog() {
    if (csv_) std::fclose(csv_);
}

void FrameLog::record(int frame, const vkcollide::DetectResult& r, std::span<const double> scene_values, double first_ms,
                      double second_ms) {
    const vkcollide::DetectStats& s = r.stats;
    if (frame == 0) std::printf("settings: %s\n", s.settings_note.c_str());
    if (csv_) {
        std::fprintf(csv_,
                     "%d,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%u,%u,%u,%u,%d,%s,%s,%.3f,%.3f,"
                     "%.3f,%.3f,%.3f",
                     frame, s.triangles, s.collision_rays, s.triangles_downloaded, s.potentially_colliding_triangles, s.triangle_tests,
                     s.positive_tests, r.pairs.size(), gpuMs(s), reduceMs(s), s.narrow_ms, s.total_ms, s.sampling_ms, s.peeling.merging_ms,
                     s.peeling.separation_ms, s.peeling.packing_ms, s.readback_ms, s.narrow_ms, s.resolution, s.peeling.depth_complexity, s.peeling.layers, s.peeling.peel_passes,
                     s.peeling.layers_short ? 1 : 0, backendName(s), vkcollide::toString(s.method), s.reliable.footprints_ms, s.reliable.pairing_ms, s.reliable.filtering_ms,
                     first_ms, second_ms);
        for (double v : scene_values) std::fprintf(csv_, ",%g", v);
        std::fprintf(csv_, "\n");
        std::fflush(csv_);
    }
    method_ = vkcollide::toString(s.method);
    rows_.push_back({{double(s.triangles), double(s.collision_rays), double(s.triangles_downloaded),
                      double(s.potentially_colliding_triangles), double(s.triangle_tests), double(s.positive_tests), gpuMs(s),
                      reduceMs(s), s.narrow_ms, s.total_ms, double(r.pairs.size())}});

    if (!quiet_) {
        if (tty_) std::fprintf(stderr, "\r\033[K");
        std::printf("frame %4d  tris %s  rays %s  downl %s  pot %s  tests %s  pos %s | GPU %.1f reduce %.1f CPU %.1f total %.1f ms",
                    frame, count(double(s.triangles)).c_str(), count(double(s.collision_rays)).c_str(),
                    count(double(s.triangles_downloaded)).c_str(), count(double(s.potentially_colliding_triangles)).c_str(),
                    count(double(s.triangle_tests)).c_str(), count(double(s.positive_tests)).c_str(), gpuMs(s), reduceMs(s),
                    s.narrow_ms, s.total_ms);
        for (std::size_t i = 0; i < scene_values.size() && i < scene_columns_.size(); ++i)
            std::printf(" | %s %g", scene_columns_[i].c_str(), scene_values[i]);
        std::printf("\n");
        std::fflush(stdout);
    }
    progress(frame);
}

void FrameLog::progress(int frame) {
    const int done = frame + 1;
    const double elapsed = msSince(start_) / 1000.0;
    const double eta = done > 0 ? elapsed / done * (frames_ - done) : 0;
    if (tty_) {
        constexpr int kBar = 30;
        const int filled = frames_ > 0 ? done * kBar / frames_ : kBar;
        std::fprintf(stderr, "\r\033[K[%s%s] %d/%d frames, %.1f s, %.2f frames/s, about %.0f s left", std::string(filled, '#').c_str(),
                     std::string(kBar - filled, '.').c_str(), done, frames_, elapsed, done / std::max(elapsed, 1e-9), eta);
        if (done == frames_) std::fprintf(stderr, "\n");
        return;
    }
    // Not a terminal (a log file, CI): a line at every tenth of a long run.
    if (frames_ < 20) return;
    const int percent = done * 10 / frames_ * 10;
    if (percent != last_percent_) {
        last_percent_ = percent;
        std::fprintf(stderr, "progress: %d/%d frames (%d%%), %.1f s, about %.0f s left\n", done, frames_, percent, elapsed, eta);
    }
}

void FrameLog::finish(const std::string& scene_name) {
    if (rows_.empty()) return;
    const std::size_t first = rows_.size() > 1 ? 1 : 0;
    Row mean{}, peak{};
    for (std::size_t i = first; i < rows_.size(); ++i)
        for (int c = 0; c < 11; ++c) {
            mean.values[c] += rows_[i].values[c] / double(rows_.size() - first);
            peak.values[c] = std::max(peak.values[c], rows_[i].values[c]);
        }
    auto line = [&](const char* what, const Row& row) {
        const double* v = row.values;
        std::printf("%-22s %-8s %-8s %-8s %-8s %-8s %-8s %7.1f %7.1f %7.1f %7.1f ms / %.1f fps  (%s pairs)\n",
                    (scene_name + " " + what).c_str(), count(v[0]).c_str(), count(v[1]).c_str(), count(v[2]).c_str(),
                    count(v[3]).c_str(), count(v[4]).c_str(), count(v[5]).c_str(), v[6], v[7], v[8], v[9],
                    v[9] > 0 ? 1000.0 / v[9] : 0.0, count(v[10]).c_str());
    };
    std::printf("\nTable 1 (%s method, %zu frame%s%s):\n%-22s %-8s %-8s %-8s %-8s %-8s %-8s %7s %7s %7s %7s\n", method_.c_str(),
                rows_.size() - first, rows_.size() - first == 1 ? "" : "s", first ? ", the first left out" : "", "scene", "# tri's", "# coll.",
                "# downl.", "# pot.", "# tests", "# pos.", "GPU", "Reduce", "CPU", "Overall");
    line("mean", mean);
    line("max", peak);
}

}  // namespace render
