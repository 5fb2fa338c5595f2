// PLY reader: ascii and both binary byte orders (built byte by byte here), skipped
// elements and properties, and every rejected input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <string>

#include "vkcollide/io.hpp"
#include "io/parse_error.hpp"

using namespace vkcollide;

namespace {

// Appends values in a chosen byte order.
class Bytes {
public:
    explicit Bytes(bool big_endian) : big_endian_(big_endian) {}

    Bytes& text(std::string_view s) {
        data += s;
        return *this;
    }
    template <typename T>
    Bytes& put(T value) {
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        if ((std::endian::native == std::endian::big) != big_endian_) std::reverse(raw, raw + sizeof(T));
        data.append(reinterpret_cast<const char*>(raw), sizeof(T));
        return *this;
    }

    std::string data;

private:
    bool big_endian_;
};

Result<std::vector<HostMesh>> readPlyBytes(const std::string& bytes, std::string_view name = "test.ply") {
    return readMesh(bytes, MeshFormat::Ply, name);
}

using test::errorOf;

bool contains(const std::string& text, std::string_view part) { return text.find(part) != std::string::npos; }

// Four vertices, one quad and one triangle, wrapped in elements and properties the
// reader must skip: a material before the vertices (with a list of floats), extra
// vertex and face properties of assorted types, and an edge element at the end.
std::string binaryQuadFile(bool big_endian) {
    Bytes b(big_endian);
    b.text("ply\n");
    b.text(big_endian ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n");
    b.text("comment built byte by byte\nobj_info test\n");
    b.text("element material 2\nproperty uchar id\nproperty list uint16 float weights\n");
    b.text("element vertex 4\nproperty uchar red\nproperty double x\nproperty float nx\nproperty double y\n");
    b.text("property double z\nproperty int16 flags\n");
    b.text("element face 2\nproperty int intensity\nproperty list uint8 int16 vertex_index\n");
    b.text("property list int uint texcoord\n");
    b.text("element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n");
    // material 0: 3 weights; material 1: none
    b.put<std::uint8_t>(0).put<std::uint16_t>(3).put(0.5f).put(0.25f).put(0.25f);
    b.put<std::uint8_t>(1).put<std::uint16_t>(0);
    const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {-0.25, 1, 0}};
    for (const auto& v : xyz) b.put<std::uint8_t>(200).put(v[0]).put(1.0f).put(v[1]).put(v[2]).put<std::int16_t>(-7);
    b.put<std::int32_t>(5).put<std::uint8_t>(4).put<std::int16_t>(0).put<std::int16_t>(1).put<std::int16_t>(2).put<std::int16_t>(3);
    b.put<std::int32_t>(2).put<std::uint32_t>(1).put<std::uint32_t>(9);
    b.put<std::int32_t>(6).put<std::uint8_t>(3).put<std::int16_t>(3).put<std::int16_t>(2).put<std::int16_t>(1);
    b.put<std::int32_t>(0);
    b.put<std::int32_t>(0).put<std::int32_t>(1);
    return b.data;
}

void checkQuadMesh(const HostMesh& m) {
    REQUIRE(m.positions.size() == 4);
    CHECK(m.positions[2].x == 1.0f);
    CHECK(m.positions[2].z == 0.5f);
    CHECK(m.positions[3].x == -0.25f);
    CHECK(m.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 3, 2, 1});
}

const std::string kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kAsciiVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

}  // namespace

TEST_CASE("PLY: binary little and big endian with skipped elements", "[io][ply]") {
    for (const bool big_endian : {false, true}) {
        INFO("big endian: " << big_endian);
        const auto meshes = readPlyBytes(binaryQuadFile(big_endian), "models/quad.ply");
        REQUIRE(meshes);
        REQUIRE(meshes->size() == 1);
        CHECK(meshes->front().name == "quad");
        checkQuadMesh(meshes->front());
    }
}

TEST_CASE("PLY: byte order matches hand-written bytes", "[io][ply]") {
    // 1.0f is 3f800000, 2.0f is 40000000; the face list is uchar count, uint32 indices.
    const std::string header_tail =
        " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
    std::string le = "ply\nformat binary_little_endian" + header_tail;
    le += std::string("\x00\x00\x80\x3f", 4) + std::string(8, '\0');
    le += std::string(4, '\0') + std::string("\x00\x00\x00\x40", 4) + std::string(4, '\0');
    le += std::string(12, '\0');
    le += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
    std::string be = "ply\nformat binary_big_endian" + header_tail;
    be += std::string("\x3f\x80\x00\x00", 4) + std::string(8, '\0');
    be += std::string(4, '\0') + std::string("\x40\x00\x00\x00", 4) + std::string(4, '\0');
    be += std::string(12, '\0');
    be += std::string("\x03\x00\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x02", 13);
    for (const std::string& bytes : {le, be}) {
        const auto meshes = readPlyBytes(bytes);
        REQUIRE(meshes);
        CHECK(meshes->front().positions[0].x == 1.0f);
        CHECK(meshes->front().positions[1].y == 2.0f);
        CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2});
    }
}

TEST_CASE("PLY: every truncation of a binary file is an error", "[io][ply]") {
    const std::string full = binaryQuadFile(false);
    for (std::size_t length = 0; length < full.size(); ++length) {
        INFO("length " << length << " of " << full.size());
        CHECK_FALSE(readPlyBytes(full.substr(0, length)));
    }
    CHECK(contains(errorOf(readPlyBytes(full + '\0')), "unexpected data after the last element"));
}

TEST_CASE("PLY: ascii with extra properties, elements and CRLF", "[io][ply]") {
    const std::string text =
        "ply\r\nformat ascii 1.0\r\ncomment x\r\n"
        "element vertex 4\r\nproperty float x\r\nproperty float y\r\nproperty double z\r\nproperty uchar red\r\n"
        "element face 2\r\nproperty list uchar int vertex_indices\r\nproperty list uchar float uv\r\n"
        "element edge 1\r\nproperty int a\r\nproperty int b\r\nend_header\r\n"
        "0 0 0 1\r\n1 0 0 2\r\n1 1 0.5 3\r\n-0.25 1 0 4\r\n"
        "4 0 1 2 3 2 0.5 0.5\r\n3 3 2 1 0\r\n"
        "0 1\r\n";
    const auto meshes = readPlyBytes(text);
    REQUIRE(meshes);
    checkQuadMesh(meshes->front());
}

TEST_CASE("PLY: the face element may come before the vertex element", "[io][ply]") {
    const std::string text =
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
        "3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n";
    const auto meshes = readPlyBytes(text);
    REQUIRE(meshes);
    CHECK(meshes->front().positions.size() == 3);
    CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2});
    const std::string bad = text.substr(0, text.find("3 0 1 2")) + "3 0 1 3\n0 0 0\n1 0 0\n0 1 0\n";
    CHECK(errorOf(readPlyBytes(bad)) == "test.ply:10: object 'test': face 0: vertex index 3 is out of range (3 vertices)");
}

TEST_CASE("PLY: out-of-range indices and bad coordinates name the object", "[io][ply]") {
    CHECK(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices + "3 0 1 4\n", "p.ply")) ==
          "p.ply:14: object 'p': face 0: vertex index 4 is out of range (4 vertices)");
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices + "3 0 -1 2\n")), "vertex index -1 is out of range"));
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + "0 0 0\nnan 0 0\n1 1 0\n0 1 0\n3 0 1 2\n")),
                   "object 'test': vertex 1 has a non-finite coordinate"));
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices + "2 0 1\n")), "face 0 has 2 vertices"));
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices + "300 0 1 2\n")), "not a valid integer"));

    Bytes b(false);
    b.text("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n");
    b.text("property float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n");
    const std::size_t body = b.data.size();
    b.put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f);
    std::string good = b.data;
    b.put<std::uint8_t>(3).put<std::uint32_t>(0).put<std::uint32_t>(1).put<std::uint32_t>(7);
    CHECK(errorOf(readPlyBytes(b.data, "bin.ply")) ==
          "bin.ply: byte " + std::to_string(body + 36 + 9) + ": object 'bin': face 0: vertex index 7 is out of range (3 vertices)");

    Bytes nan_bytes(false);
    nan_bytes.put(std::numeric_limits<float>::quiet_NaN());
    std::string with_nan = good;
    with_nan.replace(body + 16, 4, nan_bytes.data);  // vertex 1, y
    with_nan += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
    CHECK(contains(errorOf(readPlyBytes(with_nan)), "object 'test': vertex 1 has a non-finite coordinate"));
}

TEST_CASE("PLY: absurd counts fail before allocating", "[io][ply]") {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
    CHECK(contains(errorOf(readPlyBytes(header + std::string(64, '\0'))),
                   "element vertex count 4000000000 is more than the remaining 64 bytes can hold"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\n"
                                        "property float y\nproperty float z\nend_header\n0 0 0\n")),
                   "exceeds 32-bit indices"));

    Bytes b(false);
    b.text("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n");
    b.text("property float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n");
    for (int i = 0; i < 9; ++i) b.put(0.0f);
    b.put<std::uint32_t>(0xffffffffu).put<std::uint32_t>(0);
    CHECK(contains(errorOf(readPlyBytes(b.data)), "list of 4294967295 indices runs past the end of the file"));

    // A huge list in an element that is skipped must not be looped over either.
    Bytes skip(false);
    skip.text("ply\nformat binary_little_endian 1.0\nelement junk 1\nproperty list uint double stuff\n");
    skip.text("element vertex 0\nproperty float x\nproperty float y\nproperty float z\n");
    skip.text("element face 0\nproperty list uchar int vertex_indices\nend_header\n");
    skip.put<std::uint32_t>(0xfffffff0u);
    CHECK(contains(errorOf(readPlyBytes(skip.data)), "element junk 0, property stuff: truncated data"));

    // A signed list count below zero.
    Bytes negative(false);
    negative.text("ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n");
    negative.text("property float z\nelement face 1\nproperty list char uint vertex_indices\nend_header\n");
    negative.put<std::int8_t>(-1);
    CHECK(contains(errorOf(readPlyBytes(negative.data)), "negative list length -1"));
}

TEST_CASE("PLY: malformed headers are rejected", "[io][ply]") {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
    CHECK(errorOf(readPlyBytes("plyx\n")) == "test.ply:1: not a PLY file: the first line must be 'ply'");
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 1\n")), "truncated header"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat binary_middle_endian 1.0\nend_header\n")), "unknown format"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 2.0\nend_header\n")), "expected one 'format"));
    CHECK(contains(errorOf(readPlyBytes("ply\nend_header\n")), "no 'format' line"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nproperty float x\nend_header\n")), "property before any element"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")),
                   "unknown property type 'quad'"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n")),
                   "list count type must be an integer"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n")), "expected 'element"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nmystery\nend_header\n")), "unknown header line 'mystery'"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n" +
                                        face + "end_header\n")),
                   "element vertex has no scalar property z"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + "end_header\n0 0 0\n")),
                   "header has no 'element face'"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\n" + face + "end_header\n")), "header has no 'element vertex'"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 0\n" + xyz +
                                        "element face 0\nproperty list uchar int corners\nend_header\n")),
                   "element face has no list property vertex_indices"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 0\n" + xyz +
                                        "element face 0\nproperty list uchar float vertex_indices\nend_header\n")),
                   "vertex indices must have an integer type"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 0\n" + xyz + "element vertex 0\n" + xyz +
                                        face + "end_header\n")),
                   "second 'element vertex'"));
    CHECK(contains(errorOf(readPlyBytes("ply\nformat ascii 1.0\nelement vertex 0\n" + xyz +
                                        "element face 0\nproperty list uchar int vertex_indices\nend_header\n")),
                   "has no faces"));
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices + "3 0 1 2\n7\n")),
                   "test.ply:15: unexpected data after the last element"));
    CHECK(contains(errorOf(readPlyBytes(kAsciiHeader + kAsciiVertices)), "truncated data"));
}
