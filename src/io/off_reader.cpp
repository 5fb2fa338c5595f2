// OFF: header, counts, one vertex per line, one polygon per line. Line-based so that
// per-face colours after the indices are told apart from the next face.
#include <string>

#include "io/reader_util.hpp"

namespace vkcollide::io_detail {
namespace {

// Smallest possible lines: "0 0 0\n" for a vertex and "3 0 1 2\n" for a face. A count
// that would need more bytes than are left is rejected before anything is reserved.
constexpr std::size_t kMinVertexLineBytes = 6;
constexpr std::size_t kMinFaceLineBytes = 8;
// Colours after a face's indices: an index into a colour map, or r g b [a].
constexpr std::size_t kMaxFaceExtras = 4;

class OffReader {
public:
    explicit OffReader(std::string_view source_name) : source_(source_name), name_(stemOf(source_name)) {}

    Result<std::vector<HostMesh>> read(std::string_view text) {
        LineCursor cursor(text);
        std::string_view line;
        if (!nextContent(cursor, line)) return fail(cursor.line(), "empty file: no OFF header");

        // Header keyword: [ST][C][N][4][n]OFF. Texture coordinates, colours and normals
        // only add numbers after x y z, which are ignored; other dimensions are not 3D.
        std::string_view rest = line;
        std::string_view keyword = nextToken(rest);
        const std::string_view full_keyword = keyword;
        for (const std::string_view prefix : {"ST", "C", "N"})
            if (keyword.starts_with(prefix)) keyword.remove_prefix(prefix.size());
        if (keyword == "4OFF" || keyword == "nOFF" || keyword == "4nOFF")
            return fail(cursor.line(), quoted(full_keyword) + " (not 3D) is not supported");
        if (keyword != "OFF") return fail(cursor.line(), "expected an OFF header, got " + quoted(full_keyword));
        if (isBlank(rest)) {
            if (!nextContent(cursor, line)) return fail(cursor.line(), "truncated file: no vertex and face counts");
            rest = line;
        } else if (rest.find("BINARY") != std::string_view::npos) {
            return fail(cursor.line(), "binary OFF is not supported");
        }

        std::int64_t counts[3] = {0, 0, 0};
        std::size_t count_count = 0;
        for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest)) {
            if (count_count == 3 || !parseInt64(token, counts[count_count]) || counts[count_count] < 0)
                return fail(cursor.line(), "expected 'vertex_count face_count [edge_count]', got " + quoted(line));
            ++count_count;
        }
        if (count_count < 2)
            return fail(cursor.line(), "expected 'vertex_count face_count [edge_count]', got " + quoted(line));
        const auto vertex_count = static_cast<std::uint64_t>(counts[0]);
        const auto face_count = static_cast<std::uint64_t>(counts[1]);
        if (face_count == 0) return fail(cursor.line(), "object '" + name_ + "' has no faces");
        const std::size_t left = cursor.bytesLeft() + 1;  // the last line may lack '\n'
        if (vertex_count > left / kMinVertexLineBytes || vertex_count > kMaxVertices)
            return fail(cursor.line(), "object '" + name_ + "': vertex count " + std::to_string(vertex_count) +
                                           " is more than the remaining " + std::to_string(left - 1) +
                                           " bytes can hold");
        if (face_count > left / kMinFaceLineBytes)
            return fail(cursor.line(), "object '" + name_ + "': face count " + std::to_string(face_count) +
                                           " is more than the remaining " + std::to_string(left - 1) +
                                           " bytes can hold");

        HostMesh mesh;
        mesh.name = name_;
        mesh.positions.reserve(vertex_count);
        for (std::uint64_t v = 0; v < vertex_count; ++v) {
            if (!nextContent(cursor, line))
                return fail(cursor.line(), "truncated file: object '" + name_ + "' has " + std::to_string(v) +
                                               " of " + std::to_string(vertex_count) + " vertices");
            if (Result<void> r = vertex(line, v, cursor.line(), mesh.positions); !r) return r.error();
        }
        mesh.indices.reserve(face_count * 3);
        for (std::uint64_t f = 0; f < face_count; ++f) {
            if (!nextContent(cursor, line))
                return fail(cursor.line(), "truncated file: object '" + name_ + "' has " + std::to_string(f) +
                                               " of " + std::to_string(face_count) + " faces");
            if (Result<void> r = face(line, f, vertex_count, cursor.line(), mesh.indices); !r) return r.error();
        }
        if (nextContent(cursor, line)) return fail(cursor.line(), "unexpected data after the last face");

        std::vector<HostMesh> meshes;
        meshes.push_back(std::move(mesh));
        return meshes;
    }

private:
    Error fail(std::size_t line, std::string_view what) const { return parseErrorAtLine(source_, line, what); }

    // The next line with something other than whitespace and comments on it.
    static bool nextContent(LineCursor& io_cursor, std::string_view& out_line) {
        while (io_cursor.next(out_line)) {
            out_line = stripComment(out_line);
            if (!isBlank(out_line)) return true;
        }
        return false;
    }

    Result<void> vertex(std::string_view line, std::uint64_t v, std::size_t line_number,
                        std::vector<Float3>& io_positions) const {
        double xyz[3] = {0, 0, 0};
        std::size_t count = 0;
        std::string_view rest = line;
        for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest)) {
            double value = 0;
            if (!parseDouble(token, value))
                return fail(line_number, "object '" + name_ + "': vertex " + std::to_string(v) + ": " +
                                             quoted(token) + " is not a number");
            if (count < 3) xyz[count] = value;
            ++count;
        }
        if (count < 3)
            return fail(line_number, "object '" + name_ + "': vertex " + std::to_string(v) +
                                         " needs 3 coordinates, got " + std::to_string(count));
        Float3 p;
        if (!toFiniteFloat(xyz[0], p.x) || !toFiniteFloat(xyz[1], p.y) || !toFiniteFloat(xyz[2], p.z))
            return fail(line_number, "object '" + name_ + "': vertex " + std::to_string(v) +
                                         " has a non-finite coordinate (NaN, inf or beyond float range)");
        io_positions.push_back(p);
        return {};
    }

    Result<void> face(std::string_view line, std::uint64_t f, std::uint64_t vertex_count, std::size_t line_number,
                      std::vector<std::uint32_t>& io_indices) {
        const std::string prefix = "object '" + name_ + "': face " + std::to_string(f);
        std::string_view rest = line;
        std::int64_t corner_count = 0;
        if (!parseInt64(nextToken(rest), corner_count))
            return fail(line_number, prefix + ": expected a vertex count, got " + quoted(line));
        if (corner_count < 3)
            return fail(line_number, prefix + " has " + std::to_string(corner_count) + " vertices; at least 3 needed");
        // No reserve(corner_count): the count is untrusted, the tokens on the line are not.
        polygon_.clear();
        for (std::int64_t c = 0; c < corner_count; ++c) {
            const std::string_view token = nextToken(rest);
            if (token.empty())
                return fail(line_number, prefix + " lists " + std::to_string(c) + " of its " +
                                             std::to_string(corner_count) + " vertex indices");
            std::int64_t index = 0;
            if (!parseInt64(token, index))
                return fail(line_number, prefix + ": vertex index " + quoted(token) + " is not an integer");
            if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count)
                return fail(line_number, prefix + ": vertex index " + std::to_string(index) + " is out of range (" +
                                             std::to_string(vertex_count) + " vertices)");
            polygon_.push_back(static_cast<std::uint32_t>(index));
        }
        std::size_t extras = 0;
        for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest)) {
            double unused = 0;
            if (!parseDouble(token, unused) || ++extras > kMaxFaceExtras)
                return fail(line_number, prefix + ": unexpected " + quoted(token) + " after the vertex indices");
        }
        appendFan(io_indices, polygon_.data(), polygon_.size());
        return {};
    }

    std::string_view source_;
    std::string name_;
    std::vector<std::uint32_t> polygon_;
};

}  // namespace

Result<std::vector<HostMesh>> readOff(std::string_view in_text, std::string_view source_name) {
    return OffReader(source_name).read(in_text);
}

}  // namespace vkcollide::io_detail
