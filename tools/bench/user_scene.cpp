#include "user_scene.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>
#include <span>
#include <utility>

#include "vkcollide/io.hpp"

namespace vkcollide::bench {
namespace {

// Three comma-separated finite numbers, nothing else.
bool parseOffset(std::string_view text, Float3& out) {
    float v[3];
    const char* p = text.data();
    const char* end = p + text.size();
    for (int i = 0; i < 3; ++i) {
        if (i > 0) {
            if (p == end || *p != ',') return false;
            ++p;
        }
        const auto [next, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || !std::isfinite(v[i])) return false;
        p = next;
    }
    if (p != end) return false;
    out = {v[0], v[1], v[2]};
    return true;
}

// One frame's objects: each file's meshes in order, with the file's offset.
struct FrameMeshes {
    std::vector<HostMesh> meshes;
    std::vector<Float3> offsets;
};

Result<FrameMeshes> readFiles(std::span<const MeshFile> files) {
    FrameMeshes out;
    for (const MeshFile& f : files) {
        auto meshes = readMeshFile(f.path);
        if (!meshes) return meshes.error();
        for (HostMesh& m : *meshes) out.meshes.push_back(std::move(m)), out.offsets.push_back(f.offset);
    }
    return out;
}

// Frame f's meshes have frame 0's topology, or an error naming the files and what differs.
Result<void> sameTopology(const std::vector<HostMesh>& first, const std::vector<HostMesh>& frame, std::size_t f, const std::string& files) {
    const auto differs = [&](const std::string& what) {
        return Error(ErrorCode::InvalidArgument, "--sequence: frame " + std::to_string(f) + " (" + files + ") does not have frame 0's topology: " + what);
    };
    if (frame.size() != first.size())
        return differs(std::to_string(frame.size()) + " objects instead of " + std::to_string(first.size()));
    for (std::size_t i = 0; i < frame.size(); ++i) {
        const std::string who = "object " + std::to_string(i) + " ('" + first[i].name + "')";
        if (frame[i].positions.size() != first[i].positions.size())
            return differs(who + " has " + std::to_string(frame[i].positions.size()) + " vertices instead of " + std::to_string(first[i].positions.size()));
        if (frame[i].indices != first[i].indices) return differs(who + " has other triangles");
    }
    return {};
}

std::vector<BenchObject> asObjects(FrameMeshes frame) {
    std::vector<BenchObject> objects;
    for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
        const Float3 t = frame.offsets[i];
        objects.push_back(BenchObject{.mesh = std::move(frame.meshes[i]), .transform = {1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}});
    }
    return objects;
}

}  // namespace

Result<MeshFile> parseMeshFile(std::string_view text) {
    MeshFile out{std::string(text)};
    const std::size_t colon = text.rfind(':');
    if (colon != std::string_view::npos && parseOffset(text.substr(colon + 1), out.offset)) out.path = std::string(text.substr(0, colon));
    if (out.path.empty()) return Error(ErrorCode::InvalidArgument, "no file name in '" + std::string(text) + "' (FILE or FILE:x,y,z)");
    return out;
}

Result<std::vector<MeshFile>> parseMeshList(std::string_view text) {
    std::vector<std::string_view> items;
    for (std::size_t start = 0;;) {
        const std::size_t comma = text.find(',', start);
        items.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    std::vector<MeshFile> out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (items[i].empty()) continue;  // "a.obj,,b.off" or a trailing comma
        if (i + 2 < items.size()) {
            // items[i..i+2] are adjacent in text: their span is "FILE:x,y,z" if it is one.
            const std::size_t from = std::size_t(items[i].data() - text.data());
            const std::string_view joined = text.substr(from, std::size_t(items[i + 2].data() - items[i].data()) + items[i + 2].size());
            Result<MeshFile> f = parseMeshFile(joined);
            if (f && f->path.size() < joined.size()) {
                out.push_back(std::move(*f));
                i += 2;
                continue;
            }
        }
        Result<MeshFile> f = parseMeshFile(items[i]);
        if (!f) return f.error();
        out.push_back(std::move(*f));
    }
    if (out.empty()) return Error(ErrorCode::InvalidArgument, "no file in '" + std::string(text) + "' (FILE[:x,y,z],...)");
    return out;
}

std::string fileStem(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const std::size_t dot = name.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

Result<SceneSpec> userScene(const std::vector<MeshFile>& files, std::size_t per_frame, SceneSet set) {
    const bool sequence = per_frame > 0;
    if (!sequence) per_frame = files.size();
    if (files.empty() || files.size() % per_frame != 0)
        return Error(ErrorCode::InvalidArgument, std::to_string(files.size()) + " files do not make whole frames of " + std::to_string(per_frame));
    // Kept by the build function: frame 0 is read once, and later frames are checked against it.
    auto first = readFiles(std::span<const MeshFile>(files).subspan(0, per_frame));
    if (!first) return first.error();
    auto frame0 = std::make_shared<const FrameMeshes>(std::move(*first));
    SceneSpec s;
    for (std::size_t i = 0; i < per_frame; ++i) s.name += (i ? "+" : "") + fileStem(files[i].path);
    // The name is a CSV field and a word in the chart scripts (frontier.awk splits on spaces).
    for (char& c : s.name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '_' && c != '.') c = '_';
    if (sequence) s.name += "-sequence";
    s.motion = sequence ? Motion::Deforming : Motion::Rigid;
    s.set = set;
    s.frames = static_cast<int>(files.size() / per_frame);
    s.what = std::string("user scene: ") + (sequence ? std::to_string(s.frames) + " frames of " : "");
    for (std::size_t i = 0; i < per_frame; ++i) s.what += (i ? ", " : "") + files[i].path;
    s.build = [files, per_frame, frame0](int frame) -> Result<std::vector<BenchObject>> {
        if (frame == 0) return asObjects(*frame0);
        const auto mine = std::span<const MeshFile>(files).subspan(std::size_t(frame) * per_frame, per_frame);
        auto meshes = readFiles(mine);
        if (!meshes) return meshes.error();
        std::string names;
        for (const MeshFile& f : mine) names += (names.empty() ? "" : ", ") + f.path;
        if (auto ok = sameTopology(frame0->meshes, meshes->meshes, std::size_t(frame), names); !ok) return ok.error();
        return asObjects(std::move(*meshes));
    };
    return s;
}

}  // namespace vkcollide::bench
