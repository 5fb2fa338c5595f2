// readMeshFile (extension dispatch, I/O errors) and writer -> reader round trips.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;

namespace {

// A scratch folder unique to this process, removed at the end of the test.
struct ScratchDir {
    ScratchDir() {
        path = std::filesystem::temp_directory_path() / ("vkcollide_io_tests_" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    std::string write(const std::string& name, const std::string& bytes) const {
        const std::filesystem::path file = path / name;
        std::ofstream(file, std::ios::binary) << bytes;
        return file.string();
    }
    std::filesystem::path path;
};

// Same triangles with bit-identical corner positions, in the same order. Vertex numbering
// may differ: the OBJ reader renumbers vertices in order of first use.
void checkSameMesh(const HostMesh& a, const HostMesh& b) {
    REQUIRE(a.positions.size() == b.positions.size());
    REQUIRE(a.indices.size() == b.indices.size());
    for (std::size_t i = 0; i < a.indices.size(); ++i) {
        INFO("corner " << i);
        REQUIRE(a.indices[i] < a.positions.size());
        REQUIRE(b.indices[i] < b.positions.size());
        const Float3& pa = a.positions[a.indices[i]];
        const Float3& pb = b.positions[b.indices[i]];
        CHECK(pa.x == pb.x);
        CHECK(pa.y == pb.y);
        CHECK(pa.z == pb.z);
    }
}

HostMesh testSphere() {
    Result<HostMesh> sphere = uvSphere(1.25f, 7, 5);
    REQUIRE(sphere);
    // Non-round coordinates exercise the shortest round-trip float text.
    REQUIRE(transformMesh(*sphere, Transform3x4{0.3f, 0.1f, 0, 1e-3f, 0, 0.7f, 0, -1e5f, 0, 0, 1.1f, 3.14159f}));
    return *sphere;
}

}  // namespace

TEST_CASE("meshFormatFromPath: extensions in any case", "[io]") {
    CHECK(*meshFormatFromPath("a/b/c.obj") == MeshFormat::Obj);
    CHECK(*meshFormatFromPath("C.OFF") == MeshFormat::Off);
    CHECK(*meshFormatFromPath("scan.Ply") == MeshFormat::Ply);
    for (const char* path : {"mesh.stl", "mesh", "dir.obj/mesh", "obj", "mesh.obj.gz"}) {
        INFO(path);
        const Result<MeshFormat> format = meshFormatFromPath(path);
        REQUIRE_FALSE(format);
        CHECK(format.error().code() == ErrorCode::InvalidArgument);
    }
}

TEST_CASE("readMeshFile: reads by extension and reports I/O errors", "[io]") {
    ScratchDir dir;
    const HostMesh sphere = testSphere();
    const std::string off = dir.write("Ball.OFF", writeOff(sphere));
    const auto meshes = readMeshFile(off);
    REQUIRE(meshes);
    CHECK(meshes->front().name == "Ball");
    checkSameMesh(meshes->front(), sphere);

    const std::string ply = dir.write("ball.ply", writePly(sphere, PlyEncoding::BinaryBigEndian));
    REQUIRE(readMeshFile(ply));

    const auto missing = readMeshFile((dir.path / "missing.obj").string());
    REQUIRE_FALSE(missing);
    CHECK(missing.error().code() == ErrorCode::IoError);
    CHECK(missing.error().message().find("missing.obj: cannot open: No such file or directory") != std::string::npos);

    std::filesystem::create_directories(dir.path / "folder.obj");
    const auto folder = readMeshFile((dir.path / "folder.obj").string());
    REQUIRE_FALSE(folder);
    CHECK(folder.error().code() == ErrorCode::IoError);

    const auto wrong_type = readMeshFile(dir.write("mesh.stl", "solid"));
    REQUIRE_FALSE(wrong_type);
    CHECK(wrong_type.error().code() == ErrorCode::InvalidArgument);

    // A parse error names the path and the line.
    const auto broken = readMeshFile(dir.write("broken.obj", "v 0 0 0\nf 1 2 3\n"));
    REQUIRE_FALSE(broken);
    CHECK(broken.error().code() == ErrorCode::ParseError);
    CHECK(broken.error().message() == (dir.path / "broken.obj").string() +
                                          ":2: object 'broken': vertex index 2 is out of range (1 vertices defined so far)");
}

TEST_CASE("Writers round-trip exactly through the readers", "[io]") {
    const HostMesh sphere = testSphere();
    Result<HostMesh> ring = torus(2.0f, 0.5f, 9, 5);
    REQUIRE(ring);
    ring->name = "ring";

    const std::vector<HostMesh> both = {sphere, *ring};
    const auto obj = readMesh(writeObj(both), MeshFormat::Obj, "both.obj");
    REQUIRE(obj);
    REQUIRE(obj->size() == 2);
    CHECK((*obj)[0].name == "uv_sphere");
    CHECK((*obj)[1].name == "ring");
    checkSameMesh((*obj)[0], sphere);
    checkSameMesh((*obj)[1], *ring);

    const auto off = readMesh(writeOff(*ring), MeshFormat::Off, "ring.off");
    REQUIRE(off);
    checkSameMesh(off->front(), *ring);

    for (const PlyEncoding encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian}) {
        const auto ply = readMesh(writePly(sphere, encoding), MeshFormat::Ply, "s.ply");
        REQUIRE(ply);
        checkSameMesh(ply->front(), sphere);
    }
}

TEST_CASE("readMeshFile refuses what is not a regular file, by name, before reading it", "[io]") {
    const ScratchDir dir;
    // A symbolic link to /dev/zero used to be read until memory ran out (std::bad_alloc).
    const std::filesystem::path zero = dir.path / "zero.obj";
    std::filesystem::create_symlink("/dev/zero", zero);
    const auto from_zero = readMeshFile(zero.string());
    REQUIRE_FALSE(from_zero);
    CHECK(from_zero.error().code() == ErrorCode::IoError);
    CHECK(from_zero.error().message() == zero.string() + ": not a regular file (a device, pipe, socket or directory); "
                                                         "mesh files are read from regular files only");

    // A FIFO: opening it would block until a writer comes, so it is refused unopened.
    const std::filesystem::path fifo = dir.path / "pipe.off";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const auto from_fifo = readMeshFile(fifo.string());
    REQUIRE_FALSE(from_fifo);
    CHECK(from_fifo.error().code() == ErrorCode::IoError);
    CHECK_THAT(from_fifo.error().message(), Catch::Contains("not a regular file"));

    // A symbolic link to a regular mesh file is followed.
    const std::string real = dir.write("real.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::filesystem::create_symlink(real, dir.path / "link.obj");
    const auto linked = readMeshFile((dir.path / "link.obj").string());
    REQUIRE(linked);
    CHECK(linked->front().triangleCount() == 1);

    // A dangling link: the target cannot be opened.
    std::filesystem::create_symlink(dir.path / "gone.obj", dir.path / "dangling.obj");
    const auto dangling = readMeshFile((dir.path / "dangling.obj").string());
    REQUIRE_FALSE(dangling);
    CHECK(dangling.error().code() == ErrorCode::IoError);
    CHECK_THAT(dangling.error().message(), Catch::Contains("cannot open"));
}

TEST_CASE("readMeshFile refuses a file larger than kMaxMeshFileBytes without reading it", "[io]") {
    const ScratchDir dir;
    const std::string path = dir.write("huge.ply", "ply\n");
    // A sparse file: its size is past the limit, its disk use nothing.
    std::filesystem::resize_file(path, kMaxMeshFileBytes + 1);
    const auto huge = readMeshFile(path);
    REQUIRE_FALSE(huge);
    CHECK(huge.error().code() == ErrorCode::IoError);
    CHECK(huge.error().message() == path + ": " + std::to_string(kMaxMeshFileBytes + 1) +
                                        " bytes exceed the readers' limit of " + std::to_string(kMaxMeshFileBytes) +
                                        " bytes (kMaxMeshFileBytes)");
}
