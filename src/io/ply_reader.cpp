// Stanford PLY: a text header describing elements and their properties, then the
// element instances in ascii or binary (either byte order; ply_values.hpp reads them).
#include <string>
#include <vector>

#include "io/ply_values.hpp"
#include "io/reader_util.hpp"

namespace vkcollide::io_detail {
namespace {

using namespace ply;

struct PlyProperty {
    std::string name;
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;  // lists only
    PlyType value_type = PlyType::Float32;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t line = 0;
    std::vector<PlyProperty> properties;
};

class PlyReader {
public:
    explicit PlyReader(std::string_view source_name) : source_(source_name), name_(stemOf(source_name)) {}

    Result<std::vector<HostMesh>> read(std::string_view data) {
        if (Result<void> r = header(data); !r) return r.error();
        if (Result<void> r = checkElements(); !r) return r.error();
        ValueSource values(data, body_offset_, body_line_, format_);
        for (const PlyElement& element : elements_) {
            if (Result<void> r = body(element, values); !r) return r.error();
        }
        if (!values.atCleanEnd()) return fail(values.where(), "unexpected data after the last element");
        if (have_index_ && max_index_ >= mesh_.positions.size())
            return fail(max_index_where_, "object '" + name_ + "': face " + std::to_string(max_index_face_) +
                                              ": vertex index " + std::to_string(max_index_) +
                                              " is out of range (" + std::to_string(mesh_.positions.size()) +
                                              " vertices)");
        if (mesh_.indices.empty()) return fail(values.where(), "object '" + name_ + "' has no faces");
        mesh_.name = name_;
        std::vector<HostMesh> meshes;
        meshes.push_back(std::move(mesh_));
        return meshes;
    }

private:
    Error fail(std::size_t line, std::string_view what) const { return parseErrorAtLine(source_, line, what); }
    Error fail(Location where, std::string_view what) const {
        return where.is_byte ? parseErrorAtByte(source_, where.value, what)
                             : parseErrorAtLine(source_, where.value, what);
    }

    Result<void> header(std::string_view data) {
        std::size_t pos = 0;
        std::size_t line_number = 0;
        bool have_format = false;
        while (true) {
            const std::size_t end = data.find('\n', pos);
            if (end == std::string_view::npos)
                return fail(line_number + 1, "truncated header: no 'end_header' line");
            std::string_view line = data.substr(pos, end - pos);
            pos = end + 1;
            ++line_number;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

            std::string_view rest = line;
            const std::string_view keyword = nextToken(rest);
            if (line_number == 1) {
                if (keyword != "ply" || !isBlank(rest)) return fail(1, "not a PLY file: the first line must be 'ply'");
                continue;
            }
            if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
            if (keyword == "end_header") {
                if (!have_format) return fail(line_number, "header has no 'format' line");
                body_offset_ = pos;
                body_line_ = line_number + 1;
                return {};
            }
            if (keyword == "format") {
                const std::string_view encoding = nextToken(rest);
                const std::string_view version = nextToken(rest);
                if (encoding == "ascii") {
                    format_ = PlyFormat::Ascii;
                } else if (encoding == "binary_little_endian") {
                    format_ = PlyFormat::BinaryLittleEndian;
                } else if (encoding == "binary_big_endian") {
                    format_ = PlyFormat::BinaryBigEndian;
                } else {
                    return fail(line_number, "unknown format " + quoted(encoding));
                }
                if (version != "1.0" || !isBlank(rest) || have_format)
                    return fail(line_number, "expected one 'format <encoding> 1.0' line");
                have_format = true;
                continue;
            }
            if (keyword == "element") {
                PlyElement element;
                element.name = std::string(nextToken(rest));
                std::int64_t count = -1;
                if (element.name.empty() || !parseInt64(nextToken(rest), count) || count < 0 || !isBlank(rest))
                    return fail(line_number, "expected 'element <name> <count>', got " + quoted(line));
                element.count = static_cast<std::uint64_t>(count);
                element.line = line_number;
                elements_.push_back(std::move(element));
                continue;
            }
            if (keyword == "property") {
                if (elements_.empty()) return fail(line_number, "property before any element");
                PlyProperty property;
                std::string_view type_name = nextToken(rest);
                if (type_name == "list") {
                    property.is_list = true;
                    if (!parseType(nextToken(rest), property.count_type) || !isInteger(property.count_type))
                        return fail(line_number, "list count type must be an integer type in " + quoted(line));
                    type_name = nextToken(rest);
                }
                if (!parseType(type_name, property.value_type))
                    return fail(line_number, "unknown property type " + quoted(type_name));
                property.name = std::string(nextToken(rest));
                if (property.name.empty() || !isBlank(rest))
                    return fail(line_number, "expected 'property <type> <name>', got " + quoted(line));
                elements_.back().properties.push_back(std::move(property));
                continue;
            }
            return fail(line_number, "unknown header line " + quoted(line));
        }
    }

    // Finds the properties we read and rejects counts the body cannot possibly hold.
    Result<void> checkElements() {
        bool have_vertex = false;
        bool have_face = false;
        for (PlyElement& element : elements_) {
            if (element.name == "vertex") {
                if (have_vertex) return fail(element.line, "second 'element vertex'");
                have_vertex = true;
                const char* axes[3] = {"x", "y", "z"};
                for (std::size_t axis = 0; axis < 3; ++axis) {
                    std::size_t found = kNone;
                    for (std::size_t p = 0; p < element.properties.size(); ++p)
                        if (element.properties[p].name == axes[axis]) found = p;
                    if (found == kNone || element.properties[found].is_list)
                        return fail(element.line, std::string("object '") + name_ +
                                                      "': element vertex has no scalar property " + axes[axis]);
                    xyz_[axis] = found;
                }
                if (element.count > kMaxVertices)
                    return fail(element.line, "object '" + name_ + "': vertex count " + std::to_string(element.count) +
                                                  " exceeds 32-bit indices");
            } else if (element.name == "face") {
                if (have_face) return fail(element.line, "second 'element face'");
                have_face = true;
                for (std::size_t p = 0; p < element.properties.size(); ++p) {
                    const PlyProperty& property = element.properties[p];
                    if (property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index"))
                        face_list_ = p;
                }
                if (face_list_ == kNone)
                    return fail(element.line, "object '" + name_ +
                                                  "': element face has no list property vertex_indices");
                if (!isInteger(element.properties[face_list_].value_type))
                    return fail(element.line, "object '" + name_ + "': vertex indices must have an integer type");
            }
        }
        if (!have_vertex) return fail(body_line_ - 1, "object '" + name_ + "': header has no 'element vertex'");
        if (!have_face) return fail(body_line_ - 1, "object '" + name_ + "': header has no 'element face'");
        return {};
    }

    // The fewest bytes one instance of `element` can take: binary scalars and list
    // counts have fixed sizes; an ascii value is at least one character and a separator.
    std::size_t minInstanceBytes(const PlyElement& element) const {
        std::size_t bytes = 0;
        for (const PlyProperty& property : element.properties)
            bytes += format_ == PlyFormat::Ascii ? 2
                                                 : sizeOf(property.is_list ? property.count_type : property.value_type);
        return bytes;
    }

    Result<void> body(const PlyElement& element, ValueSource& io_values) {
        const std::size_t min_bytes = minInstanceBytes(element);
        // An element without properties takes no space whatever its count.
        if (min_bytes == 0 || element.count == 0) return {};
        // +1: the last ascii value of the file needs no separator after it.
        if (element.count > (io_values.bytesLeft() + 1) / min_bytes)
            return fail(io_values.where(), "object '" + name_ + "': element " + element.name + " count " +
                                               std::to_string(element.count) + " is more than the remaining " +
                                               std::to_string(io_values.bytesLeft()) + " bytes can hold");
        const bool is_vertex = element.name == "vertex";
        const bool is_face = element.name == "face";
        if (is_vertex) mesh_.positions.reserve(static_cast<std::size_t>(element.count));

        std::string problem;
        for (std::uint64_t i = 0; i < element.count; ++i) {
            double xyz[3] = {0, 0, 0};
            for (std::size_t p = 0; p < element.properties.size(); ++p) {
                const PlyProperty& property = element.properties[p];
                const Location where = io_values.where();
                bool ok = true;
                if (property.is_list) {
                    std::int64_t count = 0;
                    ok = io_values.readInteger(property.count_type, count, problem);
                    if (ok && count < 0) {
                        ok = false;
                        problem = "negative list length " + std::to_string(count);
                    }
                    if (ok && is_face && p == face_list_) {
                        if (Result<void> r = faceIndices(property, static_cast<std::uint64_t>(count), i, where, io_values);
                            !r)
                            return r;
                    } else if (ok) {
                        ok = io_values.skip(property.value_type, static_cast<std::uint64_t>(count), problem);
                    }
                } else if (is_vertex && (p == xyz_[0] || p == xyz_[1] || p == xyz_[2])) {
                    double value = 0;
                    ok = io_values.readReal(property.value_type, value, problem);
                    xyz[p == xyz_[0] ? 0 : p == xyz_[1] ? 1 : 2] = value;
                } else {
                    ok = io_values.skip(property.value_type, 1, problem);
                }
                if (!ok)
                    return fail(where, "object '" + name_ + "': element " + element.name + " " +
                                                       std::to_string(i) + ", property " + property.name + ": " +
                                                       problem);
            }
            if (is_vertex) {
                Float3 v;
                if (!toFiniteFloat(xyz[0], v.x) || !toFiniteFloat(xyz[1], v.y) || !toFiniteFloat(xyz[2], v.z))
                    return fail(io_values.where(), "object '" + name_ + "': vertex " + std::to_string(i) +
                                                       " has a non-finite coordinate (NaN, inf or beyond float "
                                                       "range)");
                mesh_.positions.push_back(v);
            }
        }
        return {};
    }

    Result<void> faceIndices(const PlyProperty& property, std::uint64_t count, std::uint64_t face, Location where,
                             ValueSource& io_values) {
        const std::string prefix = "object '" + name_ + "': face " + std::to_string(face);
        if (count < 3)
            return fail(where, prefix + " has " + std::to_string(count) + " vertices; at least 3 needed");
        // Checked before the loop so a huge count fails at once instead of after reading
        // the rest of the file; ascii needs at least two bytes per index.
        const std::size_t per_index = io_values.binary() ? sizeOf(property.value_type) : 2;
        if (count > (io_values.bytesLeft() + 1) / per_index)
            return fail(where, prefix + ": list of " + std::to_string(count) + " indices runs past the end of the file");
        polygon_.clear();
        std::string problem;
        for (std::uint64_t c = 0; c < count; ++c) {
            const Location index_where = io_values.where();
            std::int64_t index = 0;
            if (!io_values.readInteger(property.value_type, index, problem))
                return fail(index_where, prefix + ": " + problem);
            if (index < 0 || static_cast<std::uint64_t>(index) >= kMaxVertices)
                return fail(index_where, prefix + ": vertex index " + std::to_string(index) + " is out of range");
            const auto u = static_cast<std::uint32_t>(index);
            // The vertex element may come after the faces, so the range check against
            // the vertex count waits for the end; the largest index is kept for it.
            if (!have_index_ || u > max_index_) {
                have_index_ = true;
                max_index_ = u;
                max_index_face_ = face;
                max_index_where_ = index_where;
            }
            polygon_.push_back(u);
        }
        appendFan(mesh_.indices, polygon_.data(), polygon_.size());
        return {};
    }

    static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

    std::string_view source_;
    std::string name_;
    PlyFormat format_ = PlyFormat::Ascii;
    std::size_t body_offset_ = 0;
    std::size_t body_line_ = 0;
    std::vector<PlyElement> elements_;
    std::size_t xyz_[3] = {kNone, kNone, kNone};
    std::size_t face_list_ = kNone;

    HostMesh mesh_;
    std::vector<std::uint32_t> polygon_;
    bool have_index_ = false;
    std::uint32_t max_index_ = 0;
    std::uint64_t max_index_face_ = 0;
    Location max_index_where_;
};

}  // namespace

Result<std::vector<HostMesh>> readPly(std::string_view in_data, std::string_view source_name) {
    return PlyReader(source_name).read(in_data);
}

}  // namespace vkcollide::io_detail
