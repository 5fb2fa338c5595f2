// Wavefront OBJ reader: accepted syntax, grouping and every rejected input.
#include <catch2/catch.hpp>

#include <string>

#include "io/parse_error.hpp"
#include "vkcollide/io.hpp"

using namespace vkcollide;

namespace {

Result<std::vector<HostMesh>> readObjText(const std::string& text, std::string_view name = "test.obj") {
    return readMesh(text, MeshFormat::Obj, name);
}

using test::errorOf;

}  // namespace

TEST_CASE("OBJ: v and all face corner forms", "[io][obj]") {
    const std::string text =
        "# a tetrahedron\n"
        "mtllib scene.mtl\n"
        "v 0 0 0\n"
        "v 1 0 0 1.0\n"          // optional w
        "v 0 1 0 0.5 0.5 0.5\n"  // vertex colour
        "v +0 0 1e0\n"
        "vt 0 0\nvt 1 0\nvn 0 0 1\n"
        "usemtl red\ns off\n"
        "f 1 3 2\n"
        "f 1/1 2/2 4/1\n"
        "f 2/1/1 3/2/1 4/1/1\n"
        "f 1//1 4//1 3//1\n";
    const auto meshes = readObjText(text, "dir/tetra.obj");
    REQUIRE(meshes);
    REQUIRE(meshes->size() == 1);
    const HostMesh& m = meshes->front();
    CHECK(m.name == "tetra");
    REQUIRE(m.positions.size() == 4);
    CHECK(m.positions[1].x == 1.0f);
    CHECK(m.positions[3].z == 1.0f);
    CHECK(m.indices == std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2});
}

TEST_CASE("OBJ: negative indices are relative to the last vertex", "[io][obj]") {
    const auto meshes = readObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -4 -1 -3\n");
    REQUIRE(meshes);
    CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2, 0, 3, 1});
}

TEST_CASE("OBJ: polygons are fan-triangulated", "[io][obj]") {
    const auto meshes = readObjText("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n");
    REQUIRE(meshes);
    CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4});
}

TEST_CASE("OBJ: each o/g group is an object with its own vertices", "[io][obj]") {
    const std::string text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
        "f 1 2 3\n"  // before any group: named after the file
        "o first\n"
        "v 9 9 9\n"
        "f 4 2 3\n"
        "g\n"         // the default group again
        "g empty\n"   // no faces: dropped
        "g second\n"
        "v 7 7 7\n"
        "f 5 4 1\n"
        "o first\n"   // same name: merged
        "f 3 2 5\n";
    const auto meshes = readObjText(text, "groups.obj");
    REQUIRE(meshes);
    REQUIRE(meshes->size() == 3);
    const HostMesh& unnamed = (*meshes)[0];
    const HostMesh& first = (*meshes)[1];
    const HostMesh& second = (*meshes)[2];
    CHECK(unnamed.name == "groups");
    CHECK(unnamed.positions.size() == 3);
    CHECK(unnamed.indices == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(first.name == "first");
    // Global vertices 2, 3, 4, 5 (1-based) in file order become 0..3.
    REQUIRE(first.positions.size() == 4);
    CHECK(first.positions[0].x == 1.0f);
    CHECK(first.positions[1].y == 1.0f);
    CHECK(first.positions[2].x == 9.0f);
    CHECK(first.positions[3].x == 7.0f);
    CHECK(first.indices == std::vector<std::uint32_t>{2, 0, 1, 1, 0, 3});
    CHECK(second.name == "second");
    // The vertex shared with the first object is copied into this one.
    REQUIRE(second.positions.size() == 3);
    CHECK(second.positions[0].x == 0.0f);
    CHECK(second.positions[1].x == 9.0f);
    CHECK(second.positions[2].x == 7.0f);
    CHECK(second.indices == std::vector<std::uint32_t>{2, 1, 0});
}

TEST_CASE("OBJ: CRLF, comments, blank lines and line continuation", "[io][obj]") {
    const std::string text = "\xEF\xBB\xBF# exported\r\n\r\nv 0 0 0 # origin\r\nv 1 0 \\\r\n 0\r\nv 0 1 0\r\nf 1 \\\n2 3\r\n";
    const auto meshes = readObjText(text);
    REQUIRE(meshes);
    REQUIRE(meshes->front().positions.size() == 3);
    CHECK(meshes->front().positions[1].x == 1.0f);
    CHECK(meshes->front().indices == std::vector<std::uint32_t>{0, 1, 2});
}

TEST_CASE("OBJ: out-of-range indices name the object and the line", "[io][obj]") {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\no wing\n";
    CHECK(errorOf(readObjText(head + "f 1 2 4\n", "m.obj")) ==
          "m.obj:5: object 'wing': vertex index 4 is out of range (3 vertices defined so far)");
    CHECK(errorOf(readObjText(head + "f 0 1 2\n")).find("vertex index 0 is out of range") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f -1 -2 -4\n")).find("vertex index -4 is out of range") != std::string::npos);
    // The extremes of int64: refused by name, without overflowing (UBSan checks the
    // arithmetic in the sanitizer job).
    CHECK(errorOf(readObjText(head + "f 1 2 -9223372036854775808\n"))
              .find("vertex index -9223372036854775808 is out of range") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f 1 2 9223372036854775807\n"))
              .find("vertex index 9223372036854775807 is out of range") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f 1 2 -9223372036854775809\n")).find("is not v, v/vt") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f 1 2 99999999999999999999\n")).find("is not v, v/vt") != std::string::npos);
}

TEST_CASE("OBJ: non-finite and malformed vertices are rejected", "[io][obj]") {
    CHECK(errorOf(readObjText("o a\nv nan 0 0\n", "x.obj")) ==
          "x.obj:2: object 'a': vertex 1 has a non-finite coordinate (NaN, inf or beyond float range)");
    CHECK(errorOf(readObjText("v 0 inf 0\n")).find("non-finite") != std::string::npos);
    CHECK(errorOf(readObjText("v 0 0 1e39\n")).find("non-finite") != std::string::npos);
    CHECK(errorOf(readObjText("v 0 0\n")) == "test.obj:1: vertex needs 3 coordinates, got 2");
    CHECK(errorOf(readObjText("v 0 0 x\n")).find("'x' is not a number") != std::string::npos);
    CHECK(errorOf(readObjText("v 1 2 3 4 5 6 7 8\n")).find("more than 7") != std::string::npos);
}

TEST_CASE("OBJ: malformed faces and statements are rejected", "[io][obj]") {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    CHECK(errorOf(readObjText(head + "f 1 2\n")) == "test.obj:4: object 'test': face needs at least 3 vertices, got 2");
    CHECK(errorOf(readObjText(head + "f 1/1/1/1 2 3\n")).find("more than three parts") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f 1/ 2 3\n")).find("'1/' is not v, v/vt") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f 1/x 2 3\n")).find("is not v, v/vt") != std::string::npos);
    CHECK(errorOf(readObjText(head + "f a b c\n")).find("is not v, v/vt") != std::string::npos);
    CHECK(errorOf(readObjText(head + "bogus 1 2 3\n")) == "test.obj:4: unknown statement 'bogus'");
}

TEST_CASE("OBJ: a file without faces is an error", "[io][obj]") {
    CHECK(errorOf(readObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\n")) == "test.obj:3: file has no faces");
    CHECK(errorOf(readObjText("")).find("no faces") != std::string::npos);
    CHECK(errorOf(readObjText("g only_a_group\n")).find("no faces") != std::string::npos);
}
