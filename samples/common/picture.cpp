#include "common/picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/text.hpp"

namespace samples {
namespace {

using vkcollide::Float3;

Float3 lerp(Float3 a, Float3 b, float t) { return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t}; }
float length(Float3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// How far the camera moves towards its new aim per picture: contacts that flicker from one
// frame to the next do not shake the view, and it settles within a few pictures.
constexpr float kFollow = 0.5f;
// Slower back to the overview, so that a gap of a frame or two between contacts does not
// pull the camera away and back.
constexpr float kReturn = 0.2f;

// Three significant digits at most, and no more than a tenth of a millisecond's detail:
// 0.42, 7.31, 21.9, 3450.
std::string milliseconds(double ms) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ms < 10 ? "%.2f" : ms < 100 ? "%.1f" : "%.0f", ms);
    return buf;
}

}  // namespace

std::string shortCount(double v) {
    char buf[32];
    if (v >= 1e6) std::snprintf(buf, sizeof buf, "%.1fM", v / 1e6);
    else if (v >= 1e4) std::snprintf(buf, sizeof buf, "%.0fK", v / 1e3);
    else if (v >= 1e3) std::snprintf(buf, sizeof buf, "%.1fK", v / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
}

Picture::Picture(Renderer& renderer, const CommonOptions& options, std::string scene, const Camera& overview, float closest)
    : renderer_(renderer), options_(options), scene_(std::move(scene)), overview_(overview), closest_(closest), now_(overview) {}

Camera Picture::aim(const vkcollide::DetectResult& result) {
    const bool touching = std::any_of(result.pairs.begin(), result.pairs.end(),
                                      [](const vkcollide::TrianglePair& p) { return p.object_a != p.object_b; });
    const std::optional<render::Box> box = touching ? renderer_.highlightBox() : std::nullopt;
    const Float3 view = sub(overview_.eye, overview_.target);
    const float overview_distance = length(view);
    const Float3 towards_eye{view.x / overview_distance, view.y / overview_distance, view.z / overview_distance};
    Float3 target = overview_.target;
    float distance = overview_distance;
    if (box) {
        target = lerp(box->min, box->max, 0.5f);
        const float radius = std::max(closest_, 0.5f * length(sub(box->max, box->min)));
        // The box's sphere fits the vertical field of view (the narrower one: the pictures
        // are wider than high); never further out than the overview.
        const float half_fov = 0.5f * overview_.fov_degrees * 3.14159265f / 180.0f;
        distance = std::min(overview_distance, 1.15f * radius / std::sin(half_fov));
    }
    const float current = length(sub(now_.eye, now_.target));
    if (box && !aimed_) {
        // The first contact: straight to it (a still of the frame shows it framed).
        now_.target = target;
    } else {
        const float t = box ? kFollow : kReturn;
        now_.target = lerp(now_.target, target, t);
        distance = current + (distance - current) * t;
    }
    aimed_ = aimed_ || box.has_value();
    now_.eye = {now_.target.x + towards_eye.x * distance, now_.target.y + towards_eye.y * distance,
                now_.target.z + towards_eye.z * distance};
    now_.near_plane = std::min(overview_.near_plane, 0.02f * distance);
    return now_;
}

void Picture::write(int frame, const vkcollide::DetectResult& result, const std::string& note) {
    if (!writesFrame(options_, frame)) return;
    const vkcollide::DetectStats& s = result.stats;
    std::vector<std::uint8_t> image = renderer_.render(aim(result));
    char line[256];
    std::vector<std::string> lines;
    // Short enough for 53 characters, the width of a 640-pixel picture at the font's scale.
    std::snprintf(line, sizeof line, "%s: %s method, %s pairs", scene_.c_str(), vkcollide::toString(s.method),
                  shortCount(double(result.pairs.size())).c_str());
    lines.emplace_back(line);
    std::snprintf(line, sizeof line, "frame %d detect %s ms: GPU %s reduce %s CPU %s", frame, milliseconds(s.total_ms).c_str(),
                  milliseconds(render::gpuMs(s)).c_str(), milliseconds(render::reduceMs(s)).c_str(), milliseconds(s.narrow_ms).c_str());
    lines.emplace_back(line);
    if (!note.empty()) lines.push_back(note);
    render::drawCaption(image, renderer_.width(), renderer_.height(), lines);
    if (!writePng(framePath(options_.out, frame), renderer_.width(), renderer_.height(), image))
        die("cannot write " + framePath(options_.out, frame));
}

}  // namespace samples
