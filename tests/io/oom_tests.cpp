// Allocation failure inside the readers is ErrorCode::OutOfMemory, never an exception
// (the API promises none). This test program replaces the global operator new
// (support/fail_large_allocations.cpp): while a FailLargeAllocations guard is alive, every
// allocation above a size fails, so a valid but large input runs out of memory at a known
// point.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "support/fail_large_allocations.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

namespace {

// A valid mesh file of `rows` x `rows` vertices; its parsed arrays take about 24 * rows^2 bytes.
vkcollide::HostMesh bigGrid(std::uint32_t rows) {
    auto cloth = vkcollide::clothGrid(1.0f, 1.0f, rows - 1, rows - 1);
    REQUIRE(cloth);
    return *cloth;
}

}  // namespace

using namespace vkcollide;
using vkcollide::test::FailLargeAllocations;

TEST_CASE("each reader turns an allocation failure into OutOfMemory naming the source", "[io][oom]") {
    const HostMesh grid = bigGrid(400);  // 160,000 vertices: 1.9 MB of positions
    const std::vector<HostMesh> one{grid};
    const std::pair<MeshFormat, std::string> files[] = {
        {MeshFormat::Obj, writeObj(one)},
        {MeshFormat::Off, writeOff(grid)},
        {MeshFormat::Ply, writePly(grid, PlyEncoding::BinaryLittleEndian)},
        {MeshFormat::Ply, writePly(grid, PlyEncoding::Ascii)},
    };
    for (const auto& [format, bytes] : files) {
        // With memory to spare the file is fine: the failure below is memory, not input.
        REQUIRE(readMesh(bytes, format, "grid"));
        Result<std::vector<HostMesh>> starved = Error(ErrorCode::InvalidArgument, "not run");
        {
            const FailLargeAllocations guard(256 * 1024);
            starved = readMesh(bytes, format, "grid");
        }
        REQUIRE_FALSE(starved);
        CHECK(starved.error().code() == ErrorCode::OutOfMemory);
        CHECK_THAT(starved.error().message(), Catch::StartsWith("grid: out of host memory while parsing"));
    }
}

TEST_CASE("readMeshFile turns a file too large for memory into OutOfMemory", "[io][oom]") {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("vkcollide_oom_" + std::to_string(::getpid()) + ".off");
    std::ofstream(path, std::ios::binary) << writeOff(bigGrid(100));
    Result<std::vector<HostMesh>> starved = Error(ErrorCode::InvalidArgument, "not run");
    {
        const FailLargeAllocations guard(64 * 1024);  // less than the file's 200 KB
        starved = readMeshFile(path.string());
    }
    std::filesystem::remove(path);
    REQUIRE_FALSE(starved);
    CHECK(starved.error().code() == ErrorCode::OutOfMemory);
    CHECK_THAT(starved.error().message(), Catch::Contains("out of host memory for the file's"));
}
