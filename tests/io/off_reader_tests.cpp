// OFF reader: header variants, comments, colours and every rejected input.
#include <catch2/catch.hpp>

#include <string>

#include "vkcollide/io.hpp"
#include "io/parse_error.hpp"

using namespace vkcollide;

namespace {

Result<std::vector<HostMesh>> readOffText(const std::string& text, std::string_view name = "test.off") {
    return readMesh(text, MeshFormat::Off, name);
}

using test::errorOf;

const std::string kSquareVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

}  // namespace

TEST_CASE("OFF: quads, comments and blank lines", "[io][off]") {
    const std::string text =
        "OFF\n# a unit square, two ways\n\n4 2 0\n" + kSquareVertices + "4 0 1 2 3\n# trailing comment\n3 0 2 3\n\n";
    const auto meshes = readOffText(text, "/tmp/square.off");
    REQUIRE(meshes);
    REQUIRE(meshes->size() == 1);
    const HostMesh& m = meshes->front();
    CHECK(m.name == "square");
    CHECK(m.positions.size() == 4);
    CHECK(m.positions[2].x == 1.0f);
    CHECK(m.positions[2].y == 1.0f);
    CHECK(m.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3});
}

TEST_CASE("OFF: counts on the header line, COFF colours and face colours", "[io][off]") {
    const std::string text =
        "COFF 3 1 3\n"
        "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
        "3 0 1 2 0.5 0.5 0.5 1\r\n";
    const auto meshes = readOffText(text);
    REQUIRE(meshes);
    CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(readOffText("NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"));
}

TEST_CASE("OFF: out-of-range and malformed faces name object and line", "[io][off]") {
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "3 0 1 4\n", "sq.off")) ==
          "sq.off:7: object 'sq': face 0: vertex index 4 is out of range (4 vertices)");
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "3 0 -1 2\n")).find("index -1 is out of range") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "2 0 1\n")) ==
          "test.off:7: object 'test': face 0 has 2 vertices; at least 3 needed");
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "4 0 1 2\n")).find("lists 3 of its 4") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "3 0 1 x\n")).find("'x' is not an integer") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "3 0 1 2 1 2 3 4 5\n")).find("unexpected '5'") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n4 1 0\n" + kSquareVertices + "3 0 1 2\n3 0 2 3\n")) ==
          "test.off:8: unexpected data after the last face");
}

TEST_CASE("OFF: bad vertices are rejected", "[io][off]") {
    CHECK(errorOf(readOffText("OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "v.off")) ==
          "v.off:4: object 'v': vertex 1 has a non-finite coordinate (NaN, inf or beyond float range)");
    CHECK(errorOf(readOffText("OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n")).find("non-finite") != std::string::npos);
    CHECK(errorOf(readOffText("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n")).find("needs 3 coordinates, got 2") !=
          std::string::npos);
}

TEST_CASE("OFF: truncated files and absurd counts", "[io][off]") {
    CHECK(errorOf(readOffText("OFF\n4 2 0\n" + kSquareVertices + "3 0 1 2\n")) ==
          "test.off:7: truncated file: object 'test' has 1 of 2 faces");
    CHECK(errorOf(readOffText("OFF\n4 1 0\n0 0 0\n1 0 0\n# comments do not make vertices\n")).find("has 2 of 4 vertices") != std::string::npos);
    CHECK(errorOf(readOffText("OFF\n")).find("no vertex and face counts") != std::string::npos);
    CHECK(errorOf(readOffText("")).find("no OFF header") != std::string::npos);
    // Counts far beyond what the bytes could hold fail before any allocation.
    CHECK(errorOf(readOffText("OFF\n4000000000 1 0\n0 0 0\n")).find("vertex count 4000000000 is more than") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n1 999999999999 0\n0 0 0\n")).find("face count 999999999999 is more than") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n")).find("lists 3 of its") !=
          std::string::npos);
    CHECK(errorOf(readOffText("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n")).find("has no faces") != std::string::npos);
}

TEST_CASE("OFF: header variants that are not 3D meshes are rejected", "[io][off]") {
    CHECK(errorOf(readOffText("4OFF\n1 1 0\n")).find("not 3D") != std::string::npos);
    CHECK(errorOf(readOffText("nOFF\n3\n")).find("not 3D") != std::string::npos);
    CHECK(errorOf(readOffText("OFF BINARY\n")).find("binary OFF") != std::string::npos);
    CHECK(errorOf(readOffText("PLY\n3 1 0\n")).find("expected an OFF header") != std::string::npos);
    CHECK(errorOf(readOffText("OFF\n3 -1 0\n")).find("expected 'vertex_count face_count") != std::string::npos);
    CHECK(errorOf(readOffText("OFF\n3 1 0 7\n")).find("expected 'vertex_count face_count") != std::string::npos);
}
