// Wavefront OBJ: `v` and `f` statements, `o`/`g` groups as objects.
#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>

#include "io/reader_util.hpp"

namespace vkcollide::io_detail {
namespace {

// Statements of the OBJ spec that carry nothing a collision mesh needs.
constexpr std::array<std::string_view, 31> kIgnoredStatements = {
    "vt",   "vn",    "vp",      "s",          "usemtl",    "mtllib",    "l",     "p",
    "cstype", "deg", "bmat",    "step",       "curv",      "curv2",     "surf",  "parm",
    "trim", "hole",  "scrv",    "sp",         "end",       "con",       "mg",    "bevel",
    "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj", "ctech", "stech",
};
constexpr std::array<std::string_view, 4> kMoreIgnoredStatements = {"maplib", "usemap", "call", "csh"};

bool isIgnoredStatement(std::string_view keyword) {
    for (const std::string_view s : kIgnoredStatements)
        if (s == keyword) return true;
    for (const std::string_view s : kMoreIgnoredStatements)
        if (s == keyword) return true;
    return false;
}

struct ObjObject {
    std::string name;
    std::vector<std::uint32_t> corners;  // global 0-based vertex indices, 3 per triangle
};

class ObjReader {
public:
    explicit ObjReader(std::string_view source_name) : source_(source_name) {}

    Result<std::vector<HostMesh>> read(std::string_view text) {
        LineCursor cursor(text);
        std::string_view raw;
        std::string joined;
        while (cursor.next(raw)) {
            line_ = cursor.line();
            std::string_view line = raw;
            // A trailing backslash continues the statement on the next line (OBJ spec).
            if (endsWithContinuation(line)) {
                joined.clear();
                std::string_view part = line;
                while (endsWithContinuation(part)) {
                    joined.append(part.substr(0, part.find_last_of('\\')));
                    joined += ' ';
                    if (!cursor.next(part)) {
                        part = {};
                        break;
                    }
                }
                joined.append(part);
                line = joined;
            }
            if (Result<void> r = statement(stripComment(line)); !r) return r.error();
        }
        return finish(cursor.line());
    }

private:
    static bool endsWithContinuation(std::string_view line) {
        while (!line.empty() && isSpace(line.back())) line.remove_suffix(1);
        return !line.empty() && line.back() == '\\';
    }

    Error fail(std::string_view what) const { return parseErrorAtLine(source_, line_, what); }

    std::string currentName() const {
        return current_ == kNone ? stemOf(source_) : objects_[current_].name;
    }

    Result<void> statement(std::string_view line) {
        std::string_view rest = line;
        const std::string_view keyword = nextToken(rest);
        if (keyword.empty()) return {};
        if (keyword == "v") return vertex(rest);
        if (keyword == "f" || keyword == "fo") return face(rest);
        if (keyword == "o" || keyword == "g") {
            selectObject(trim(rest));
            return {};
        }
        if (isIgnoredStatement(keyword)) return {};
        return fail("unknown statement " + quoted(keyword));
    }

    static std::string_view trim(std::string_view text) {
        while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
        while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
        return text;
    }

    void selectObject(std::string_view name_in) {
        // `g` without a name is the spec's "default" group: it and the faces before any
        // group belong to the object named after the file.
        const std::string name = name_in.empty() ? stemOf(source_) : std::string(name_in);
        const auto [it, inserted] = by_name_.try_emplace(name, objects_.size());
        if (inserted) objects_.push_back(ObjObject{name, {}});
        current_ = it->second;
    }

    Result<void> vertex(std::string_view rest) {
        // x y z, optionally w (ignored: rational vertices) or r g b colours (ignored).
        std::array<double, 3> xyz{};
        std::size_t count = 0;
        for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest)) {
            double value = 0;
            if (!parseDouble(token, value)) return fail("vertex coordinate " + quoted(token) + " is not a number");
            if (count < 3) xyz[count] = value;
            if (++count > 7) return fail("vertex has more than 7 numbers");
        }
        if (count < 3) return fail("vertex needs 3 coordinates, got " + std::to_string(count));
        if (positions_.size() >= kMaxVertices) return fail("more vertices than 32-bit indices can address");
        Float3 p;
        if (!toFiniteFloat(xyz[0], p.x) || !toFiniteFloat(xyz[1], p.y) || !toFiniteFloat(xyz[2], p.z))
            return fail("object '" + currentName() + "': vertex " + std::to_string(positions_.size() + 1) +
                        " has a non-finite coordinate (NaN, inf or beyond float range)");
        positions_.push_back(p);
        return {};
    }

    // One corner: v, v/vt, v/vt/vn or v//vn. Only v is used, but the others must be
    // well-formed so garbage is not silently accepted.
    Result<void> corner(std::string_view token, std::uint32_t& out_index) {
        std::array<std::string_view, 3> parts{};
        std::size_t part_count = 0;
        std::string_view rest = token;
        while (true) {
            const std::size_t slash = rest.find('/');
            if (part_count == 3) return fail("face corner " + quoted(token) + " has more than three parts");
            parts[part_count++] = rest.substr(0, slash);
            if (slash == std::string_view::npos) break;
            rest.remove_prefix(slash + 1);
        }
        std::int64_t index = 0;
        std::int64_t unused = 0;
        const bool parts_ok = parseInt64(parts[0], index) && (part_count < 2 || (part_count == 3 && parts[1].empty()) ||
                                                               parseInt64(parts[1], unused)) &&
                              (part_count < 3 || parseInt64(parts[2], unused));
        if (!parts_ok) return fail("face corner " + quoted(token) + " is not v, v/vt, v/vt/vn or v//vn");

        const auto defined = static_cast<std::int64_t>(positions_.size());
        std::int64_t resolved = -1;
        if (index > 0 && index <= defined) resolved = index - 1;
        // Relative to the last vertex. Compared as index >= -defined, never by negating
        // index: -INT64_MIN overflows.
        if (index < 0 && index >= -defined) resolved = defined + index;
        if (resolved < 0)
            return fail("object '" + currentName() + "': vertex index " + std::to_string(index) +
                        " is out of range (" + std::to_string(defined) + " vertices defined so far)");
        out_index = static_cast<std::uint32_t>(resolved);
        return {};
    }

    Result<void> face(std::string_view rest) {
        polygon_.clear();
        for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest)) {
            std::uint32_t index = 0;
            if (Result<void> r = corner(token, index); !r) return r;
            polygon_.push_back(index);
        }
        if (polygon_.size() < 3)
            return fail("object '" + currentName() + "': face needs at least 3 vertices, got " +
                        std::to_string(polygon_.size()));
        if (current_ == kNone) selectObject({});
        appendFan(objects_[current_].corners, polygon_.data(), polygon_.size());
        return {};
    }

    Result<std::vector<HostMesh>> finish(std::size_t last_line) {
        // Each object keeps only the vertices its faces use, in file order (so a file
        // with one object keeps its numbering); `local` maps global to local indices and
        // is reset after each object.
        constexpr std::uint32_t kUnset = 0xffffffffu;
        std::vector<std::uint32_t> local(positions_.size(), kUnset);
        std::vector<std::uint32_t> used;
        std::vector<HostMesh> meshes;
        for (ObjObject& object : objects_) {
            if (object.corners.empty()) continue;
            used.clear();
            for (const std::uint32_t global : object.corners) {
                if (local[global] == kUnset) {
                    local[global] = 0;
                    used.push_back(global);
                }
            }
            std::sort(used.begin(), used.end());
            HostMesh mesh;
            mesh.name = std::move(object.name);
            mesh.positions.reserve(used.size());
            for (const std::uint32_t global : used) {
                local[global] = static_cast<std::uint32_t>(mesh.positions.size());
                mesh.positions.push_back(positions_[global]);
            }
            mesh.indices.reserve(object.corners.size());
            for (const std::uint32_t global : object.corners) mesh.indices.push_back(local[global]);
            for (const std::uint32_t global : used) local[global] = kUnset;
            object.corners = {};
            meshes.push_back(std::move(mesh));
        }
        if (meshes.empty()) return parseErrorAtLine(source_, last_line, "file has no faces");
        return meshes;
    }

    static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

    std::string_view source_;
    std::size_t line_ = 0;
    std::vector<Float3> positions_;
    std::vector<ObjObject> objects_;
    std::unordered_map<std::string, std::size_t> by_name_;
    std::size_t current_ = kNone;
    std::vector<std::uint32_t> polygon_;
};

}  // namespace

Result<std::vector<HostMesh>> readObj(std::string_view in_text, std::string_view source_name) {
    return ObjReader(source_name).read(in_text);
}

}  // namespace vkcollide::io_detail
