// `vkcollide detect` end to end: a scene written as OBJ and OFF files, the tool run as a
// process, its CSV pairs (global triangle indices) and JSON statistics checked against
// the exact reference.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "api/cli_support.hpp"
#include "support/exact_reference.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/io.hpp"

using namespace vkcollide;
using namespace vkcollide::test;
namespace fs = std::filesystem;

namespace {

fs::path scratchDir(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("vkcollide-cli-" + name + "-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

using clitest::readText;
using clitest::writeText;

// The tool's output goes to `log` (the tests read it back).
int runCliLogged(const std::string& args, const fs::path& log) {
    const std::string cmd = std::string(VKCOLLIDE_CLI_PATH) + " " + args + " > " + log.string() + " 2>&1";
    UNSCOPED_INFO(cmd);
    return std::system(cmd.c_str());
}

// The tool's exit code, or -signal when it did not exit (an abort is SIGABRT: -6).
int exitCode(int system_status) {
    if (WIFEXITED(system_status)) return WEXITSTATUS(system_status);
    if (WIFSIGNALED(system_status)) return -WTERMSIG(system_status);
    return -1000;
}

}  // namespace

TEST_CASE("vkcollide detect writes the exact pairs as global triangle indices", "[cli][gpu]") {
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    // World-space meshes: the first two objects in one OBJ (two `o` groups), the third as OFF.
    std::vector<HostMesh> world;
    for (const SceneObject& o : scene->objects) {
        HostMesh m = o.mesh;
        m.name = o.options.name;
        REQUIRE(transformMesh(m, o.options.transform));
        world.push_back(std::move(m));
    }
    const fs::path dir = scratchDir("pairs");
    writeText(dir / "two.obj", writeObj(std::span<const HostMesh>(world.data(), 2)));
    writeText(dir / "third.off", writeOff(world[2]));
    writeText(dir / "fourth.off", writeOff(world[3]));
    const fs::path csv = dir / "pairs.csv", json = dir / "stats.json", log = dir / "log.txt";
    const int rc = runCliLogged("detect " + (dir / "two.obj").string() + " " + (dir / "third.off").string() + " " + (dir / "fourth.off").string() +
                              " --resolution 256 --direction 0.15,-0.2,1 --pairs " + csv.string() + " --stats " + json.string(),
                          log);
    INFO(readText(log));
    REQUIRE(rc == 0);

    // Expected: the exact reference on the same world-space meshes (self-collision on, the default).
    std::vector<ReferenceObject> objects;
    for (const HostMesh& m : world) objects.push_back({&m});
    auto reference = computeReferencePairs(objects);
    REQUIRE(reference);
    std::vector<std::uint64_t> base{0};
    for (const HostMesh& m : world) base.push_back(base.back() + m.triangleCount());
    std::vector<std::pair<std::uint64_t, std::uint64_t>> expected, got;
    for (const auto& p : *reference) expected.emplace_back(base[p.object_a] + p.triangle_a, base[p.object_b] + p.triangle_b);
    std::istringstream lines(readText(csv));
    std::string line;
    while (std::getline(lines, line)) {
        const auto comma = line.find(',');
        REQUIRE(comma != std::string::npos);
        got.emplace_back(std::stoull(line.substr(0, comma)), std::stoull(line.substr(comma + 1)));
        CHECK(got.back().first < got.back().second);
    }
    CHECK(std::is_sorted(got.begin(), got.end()));
    std::size_t found = 0;
    for (const auto& p : got) {
        const bool exact = std::binary_search(expected.begin(), expected.end(), p);
        CHECK(exact);  // precision 100 %
        found += exact;
    }
    CHECK(found == expected.size());  // the reliable method (default): every pair
    const std::string stats = readText(json);
    CHECK(stats.find("\"positive_tests\": " + std::to_string(got.size())) != std::string::npos);
    CHECK(stats.find("\"resolution\": 256") != std::string::npos);
    CHECK(stats.find("\"method\": \"reliable\"") != std::string::npos);
    CHECK(stats.find("\"objects\": [\"sphere-a\", \"sphere-b\", \"third\", \"fourth\"]") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("vkcollide detect names bad input and bad options", "[cli][gpu]") {
    const fs::path dir = scratchDir("errors");
    const fs::path log = dir / "log.txt";
    writeText(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    CHECK(runCliLogged("detect " + (dir / "broken.obj").string(), log) != 0);
    CHECK(readText(log).find("broken.obj") != std::string::npos);
    CHECK(runCliLogged("detect " + (dir / "missing.off").string(), log) != 0);
    CHECK(readText(log).find("missing.off") != std::string::npos);
    CHECK(runCliLogged("detect --resolution", log) != 0);
    CHECK(runCliLogged("", log) != 0);
    writeText(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(runCliLogged("detect " + (dir / "tri.obj").string() + " --method peeling --resolution 100", log) != 0);
    CHECK(readText(log).find("power of two") != std::string::npos);
    CHECK(runCliLogged("detect " + (dir / "tri.obj").string() + " --bogus", log) != 0);
    CHECK(runCliLogged("detect " + (dir / "tri.obj").string(), log) == 0);
    CHECK(readText(log).find("colliding triangle pairs: 0") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("vkcollide detect --help prints the help and succeeds", "[cli]") {
    const fs::path dir = scratchDir("help");
    const fs::path log = dir / "log.txt";
    for (const char* args : {"detect --help", "detect -h", "--help", "detect scene.obj --help"}) {
        INFO(args);
        CHECK(exitCode(runCliLogged(args, log)) == 0);
        const std::string text = readText(log);
        CHECK(text.find("usage: vkcollide info") != std::string::npos);
        CHECK(text.find("--threads T") != std::string::npos);
        CHECK(text.find("unknown option") == std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("vkcollide detect refuses an absurd --threads by name instead of aborting", "[cli][gpu]") {
    const fs::path dir = scratchDir("threads");
    const fs::path log = dir / "log.txt";
    writeText(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string scene = (dir / "tri.obj").string();
    for (const char* threads : {"4294967295", "1025", "0", "-1", "99999999999"}) {
        INFO("--threads " << threads);
        CHECK(exitCode(runCliLogged("detect " + scene + " --threads " + threads, log)) == 1);
        CHECK(readText(log).find("--threads needs a number from 1 to 1024") != std::string::npos);
    }
    // The CPU's exact decision runs on the pool; pairs the GPU decided, this few, on the
    // calling thread (narrow::kSerialDecidedBelow), where the device has 64-bit floats.
    CHECK(exitCode(runCliLogged("detect " + scene + " --threads 2 --exact cpu", log)) == 0);
    CHECK(readText(log).find("(2 threads)") != std::string::npos);
    CHECK(exitCode(runCliLogged("detect " + scene + " --threads 2 --exact gpu", log)) == 0);
    CHECK(readText(log).find("(1 thread)") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("vkcollide detect refuses a mesh path that leads to /dev/zero instead of aborting", "[cli]") {
    const fs::path dir = scratchDir("zero");
    const fs::path log = dir / "log.txt";
    fs::create_symlink("/dev/zero", dir / "zero.obj");
    CHECK(exitCode(runCliLogged("detect " + (dir / "zero.obj").string(), log)) == 1);
    const std::string text = readText(log);
    CHECK(text.find("zero.obj: not a regular file") != std::string::npos);
    CHECK(text.find("bad_alloc") == std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("vkcollide detect --no-robust-access finds the same pairs", "[cli][gpu]") {
    const fs::path dir = scratchDir("robust");
    const fs::path log = dir / "log.txt";
    // Two crossing triangles: one pair either way.
    writeText(dir / "cross.obj", "o a\nv 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n"
                                 "o b\nv 0.5 0.5 -1\nv 0.5 0.5 1\nv 1.5 -0.5 0\nf 4 5 6\n");
    const std::string scene = (dir / "cross.obj").string();
    for (const char* flag : {"", " --no-robust-access"}) {
        INFO("flag:" << flag);
        CHECK(exitCode(runCliLogged("detect " + scene + " --pairs " + (dir / "p.csv").string() + flag, log)) == 0);
        CHECK(readText(dir / "p.csv") == "0,1\n");
    }
    fs::remove_all(dir);
}
