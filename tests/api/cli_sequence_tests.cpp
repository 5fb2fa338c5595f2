// `vkcollide detect --sequence`: files as frames of the same objects, per-frame pairs and
// statistics (CSV), the progress line, and a named error when a frame's topology differs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "api/cli_support.hpp"

using namespace clitest;
using vkcollide::HostMesh;

namespace {

// Sphere a stays at the origin; sphere b comes closer frame by frame (x = 2.6 - 0.4 f):
// no contact in frame 0, contact from frame 2 on.
struct Approach {
    Scratch scratch{"sequence"};
    std::string files;  // a_0 b_0 a_1 b_1 ... (two files per frame)
    std::vector<std::vector<HostMesh>> frames;
    explicit Approach(int count) {
        for (int f = 0; f < count; ++f) {
            frames.push_back({sphere("a", {0, 0, 0}), sphere("b", {2.6f - 0.4f * static_cast<float>(f), 0.1f, 0.05f})});
            files += writeMesh(scratch, "a_" + std::to_string(f) + ".off", frames.back()[0]) + " " +
                     writeMesh(scratch, "b_" + std::to_string(f) + ".off", frames.back()[1]) + " ";
        }
    }
};

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

}  // namespace

TEST_CASE("vkcollide detect --sequence: per-frame pairs, JSON and CSV", "[cli][gpu]") {
    Approach a(4);
    const std::string csv = a.scratch.path("frames.csv"), pairs = a.scratch.path("pairs.csv");
    Run run;
    const Json j = detectJson(a.scratch, "--sequence --frame-files 2 " + a.files + "--resolution 128 --csv " + csv + " --pairs " + pairs, run);
    CHECK(j["sequence"].boolean());
    REQUIRE(j["frames"].size() == 4);
    REQUIRE(j["objects"].size() == 2);
    CHECK(j["objects"][1]["name"].string() == "b_0");  // names come from frame 0

    std::vector<std::string> expected_pairs;
    const std::uint64_t b_base = static_cast<std::uint64_t>(j["objects"][1]["first_triangle"].number());
    for (std::size_t f = 0; f < 4; ++f) {
        INFO("frame " << f);
        const Json& frame = j["frames"][f];
        CHECK(frame["frame"].number() == double(f));
        CHECK(frame["files"][1].string() == a.scratch.path("b_" + std::to_string(f) + ".off"));
        const auto found = jsonPairs(frame);
        const auto exact = referencePairs(a.frames[f], {true, true});
        for (const auto& p : found) CHECK(std::binary_search(exact.begin(), exact.end(), p));
        CHECK(double(found.size()) >= 0.9 * double(exact.size()));
        CHECK((f < 2 ? found.empty() : !found.empty()));
        for (const auto& p : found)
            expected_pairs.push_back(std::to_string(f) + "," + std::to_string(p.triangle_a) + "," + std::to_string(b_base + p.triangle_b));
    }
    CHECK(lines(readText(pairs)) == expected_pairs);

    const std::vector<std::string> rows = lines(readText(csv));
    REQUIRE(rows.size() == 5);
    CHECK(rows[0].rfind("frame,triangles,collision_rays,triangles_downloaded,potentially_colliding_triangles,triangle_tests,positive_tests,pairs,", 0) == 0);
    CHECK(rows[0].find(",sampling_ms,merging_ms,separation_ms,packing_ms,readback_ms,narrow_ms,") != std::string::npos);
    const std::string tail = ",read_ms,png_ms";
    CHECK(rows[0].compare(rows[0].size() - tail.size(), tail.size(), tail) == 0);
    for (std::size_t f = 0; f < 4; ++f) {
        const std::string want = std::to_string(f) + ",640,";
        CHECK(rows[f + 1].rfind(want, 0) == 0);
        // The pairs column holds that frame's pair count.
        std::vector<std::string> cells;
        std::istringstream row(rows[f + 1]);
        for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
        CHECK(cells.at(7) == std::to_string(j["frames"][f]["pairs"].size()));
    }
    CHECK(run.out.find("frame    3") != std::string::npos);  // a line per frame
    CHECK(run.out.find("Table 1 (reliable method, 3 frames, the first left out)") != std::string::npos);
}

TEST_CASE("vkcollide detect --sequence: --gpu-mesh frames are written into the engine's buffers", "[cli][gpu]") {
    Approach a(3);
    const Json host = detectJson(a.scratch, "--sequence --frame-files 2 " + a.files + "--resolution 64");
    const Json gpu = detectJson(a.scratch, "--sequence --frame-files 2 " + a.files + "--resolution 64 --gpu-mesh 2");
    for (std::size_t f = 0; f < 3; ++f) CHECK(jsonPairs(gpu["frames"][f]) == jsonPairs(host["frames"][f]));
    CHECK(gpu["frames"][2]["pairs"].size() > 0);
}

TEST_CASE("vkcollide detect --sequence: a progress line, --quiet and one picture per frame", "[cli][gpu]") {
    Approach a(20);
    const std::string png = a.scratch.path("frame.png");
    const Run run = runCli("detect --sequence --frame-files 2 " + a.files + "--resolution 32 --quiet --png-size 64,48 --png " + png);
    REQUIRE(run.status == 0);
    // Not a terminal: a line at each tenth of the run instead of a bar.
    CHECK(run.err.find("progress: 20/20 frames (100%)") != std::string::npos);
    CHECK(run.out.find("frame    3") == std::string::npos);  // --quiet
    CHECK(run.out.find("over 20 frames") != std::string::npos);
    for (int f : {0, 7, 19}) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", f);
        const Image image = readPng(a.scratch / name);
        CHECK(image.width == 64);
        CHECK(image.height == 48);
    }
}

TEST_CASE("vkcollide detect --sequence: on a terminal the progress line is a bar rewritten in place", "[cli][gpu]") {
    Approach a(3);
    // script(1) (util-linux, in every Debian) gives the tool a terminal and copies what it
    // writes there to stdout.
    const std::string inner = std::string(VKCOLLIDE_CLI_PATH) + " detect --sequence --frame-files 2 " + a.files + "--resolution 32 --validation";
    const std::string log = a.scratch.path("tty.txt");
    const std::string cmd = "script -qec '" + inner + "' /dev/null > " + log + " 2>&1";
    UNSCOPED_INFO(cmd);
    REQUIRE(std::system(cmd.c_str()) == 0);
    const std::string text = readText(log);
    INFO(text);
    CHECK(text.find("\r\033[K[##########") != std::string::npos);  // a third of the bar after frame 0
    CHECK(text.find("3/3 frames") != std::string::npos);
    CHECK(text.find("progress:") == std::string::npos);  // the line for logs is not used
}

TEST_CASE("vkcollide detect --sequence: a frame with other topology is a named error", "[cli][gpu]") {
    Scratch s("topology");
    const HostMesh ball = sphere("ball", {0, 0, 0});
    const std::string first = writeMesh(s, "f0.off", ball);

    HostMesh fewer = ball;  // one vertex less (the last one, renumbered away)
    fewer.positions.pop_back();
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < fewer.triangleCount(); ++t)
        if (std::all_of(&fewer.indices[t * 3], &fewer.indices[t * 3] + 3, [&](std::uint32_t i) { return i < fewer.positions.size(); }))
            kept.insert(kept.end(), &fewer.indices[t * 3], &fewer.indices[t * 3] + 3);
    fewer.indices = kept;
    HostMesh other_triangles = ball;
    other_triangles.indices.resize(other_triangles.indices.size() - 3);
    HostMesh other_indices = ball;
    std::swap(other_indices.indices[30], other_indices.indices[31]);

    struct Case {
        std::string file, what;
    };
    const Case cases[] = {
        {writeMesh(s, "fewer.off", fewer), "has 161 vertices instead of 162"},
        {writeMesh(s, "triangles.off", other_triangles), "has 319 triangles instead of 320"},
        {writeMesh(s, "indices.off", other_indices), "triangle 10 has other vertex indices"},
        {writeMeshes(s, "two.obj", {ball, sphere("more", {3, 0, 0})}), "2 objects instead of 1"},
    };
    for (const Case& c : cases) {
        INFO(c.file);
        const Run run = runCli("detect --sequence " + first + " " + first + " " + c.file);
        CHECK(run.status == 1);
        CHECK(run.err.find("--sequence: frame 2 (" + c.file + ") does not have frame 0's topology (" + first + ")") != std::string::npos);
        CHECK(run.err.find(c.what) != std::string::npos);
    }
    // A frame file that cannot be read names itself.
    const Run missing = runCli("detect --sequence " + first + " " + s.path("gone.off"));
    CHECK(missing.status == 1);
    CHECK(missing.err.find("gone.off") != std::string::npos);
}

TEST_CASE("vkcollide detect --sequence: frames must be whole and --frames does not mix in", "[cli]") {
    Scratch s("frames");
    const std::string f = writeMesh(s, "f.off", sphere("f", {0, 0, 0}));
    const Run odd = runCli("detect --sequence --frame-files 2 " + f + " " + f + " " + f);
    CHECK(odd.status == 1);
    CHECK(odd.err.find("--frame-files 2: 3 files do not make whole frames of 2") != std::string::npos);
    const Run mixed = runCli("detect --sequence --frames 2 " + f + " " + f);
    CHECK(mixed.status == 1);
    CHECK(mixed.err.find("--frames") != std::string::npos);
    const Run lone = runCli("detect --frame-files 2 " + f + " " + f);
    CHECK(lone.status == 1);
    CHECK(lone.err.find("--frame-files needs --sequence") != std::string::npos);
}
