// `vkcollide detect`'s outputs end to end: --json (well-formed, consistent with itself and
// with --pairs and --stats), --png (highlights, object colours, the collision rays, size,
// view), --csv with --frames, the run options (--device, --quiet), the help (every option
// says what it costs) and the errors (each names the option and the problem).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "api/cli_support.hpp"

using namespace clitest;

namespace {

struct Scene {
    Scratch scratch;
    std::string files;
    Scene(const std::string& name, float b_x) : scratch(name) {
        files = writeMesh(scratch, "a.off", sphere("a", {0, 0, 0})) + " " + writeMesh(scratch, "b.off", sphere("b", {b_x, 0.1f, 0.05f}));
    }
};

std::size_t lineCount(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE("vkcollide detect --json: pairs, responses, objects and statistics agree", "[cli][gpu]") {
    Scene s("json", 1.2f);
    const std::string pairs_csv = s.scratch.path("pairs.csv"), stats = s.scratch.path("stats.json");
    const Json j = detectJson(s.scratch, s.files + " --resolution 128 --pairs " + pairs_csv + " --stats " + stats);
    CHECK(j["tool"].string() == "vkcollide detect");
    CHECK(j["format"].number() == 1);
    CHECK_FALSE(j["device"].string().empty());
    CHECK(j["files"].size() == 2);
    CHECK(j["options"][0][0].string() == "--resolution");
    CHECK(j["options"][0][1].string() == "128");
    REQUIRE(j["objects"].size() == 2);
    CHECK(j["objects"][1]["first_triangle"].number() == 320);
    CHECK(j["objects"][1]["triangles"].number() == 320);
    REQUIRE(j["frames"].size() == 1);
    const Json& frame = j["frames"][0];
    const auto pairs = jsonPairs(frame);
    REQUIRE_FALSE(pairs.empty());
    CHECK(std::is_sorted(pairs.begin(), pairs.end()));

    // One response per colliding triangle, a unit direction, partners counted.
    std::set<std::pair<std::uint32_t, std::uint32_t>> colliding;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> partners;
    for (const auto& p : pairs) {
        colliding.insert({p.object_a, p.triangle_a});
        colliding.insert({p.object_b, p.triangle_b});
        ++partners[{p.object_a, p.triangle_a}];
        ++partners[{p.object_b, p.triangle_b}];
    }
    REQUIRE(frame["responses"].size() == colliding.size());
    for (const Json& r : frame["responses"].array()) {
        const std::pair<std::uint32_t, std::uint32_t> key{static_cast<std::uint32_t>(r["object"].number()),
                                                          static_cast<std::uint32_t>(r["triangle"].number())};
        CHECK(colliding.count(key) == 1);
        CHECK(r["partners"].number() == partners[key]);
        const double x = r["direction"][0].number(), y = r["direction"][1].number(), z = r["direction"][2].number();
        const double len = std::sqrt(x * x + y * y + z * z);
        CHECK((len == 0 || std::fabs(len - 1) < 1e-5));
    }
    CHECK(frame["excluded"].size() == 0);
    const Json& st = frame["stats"];
    CHECK(st["positive_tests"].number() == double(pairs.size()));
    CHECK(st["pairs"].number() == double(pairs.size()));
    CHECK(st["triangles"].number() == 640);
    CHECK(st["narrow"]["positive_tests"].number() == double(pairs.size()));
    CHECK(st["gpu_passes"].size() > 0);
    CHECK(st["total_ms"].number() > 0);
    CHECK(st["gpu_memory_bytes"].number() > 0);

    // --pairs: the same pairs as global triangle numbers; --stats: the same statistics.
    std::string csv;
    for (const auto& p : pairs) csv += std::to_string(p.object_a * 320 + p.triangle_a) + "," + std::to_string(p.object_b * 320 + p.triangle_b) + "\n";
    CHECK(readText(pairs_csv) == csv);
    const Json stats_file = Json::parse(readText(stats));
    CHECK(stats_file["positive_tests"].number() == double(pairs.size()));
    CHECK(stats_file["collision_rays"].number() == st["collision_rays"].number());
    CHECK(stats_file["objects"][1].string() == "b");
}

TEST_CASE("vkcollide detect --contacts: the object pair's contact in --json and the summary", "[cli][gpu]") {
    Scene s("contacts", 1.2f);
    const Json plain = detectJson(s.scratch, s.files);
    CHECK(plain["frames"][0]["contacts"].size() == 0);
    Run run;
    const Json j = detectJson(s.scratch, s.files + " --contacts --contact-resolution 64", run);
    CHECK(j["settings"]["used"]["contacts"].boolean());
    CHECK(j["settings"]["used"]["contact_resolution"].number() == 64);
    const Json& contacts = j["frames"][0]["contacts"];
    REQUIRE(contacts.size() == 1);
    const Json& c = contacts[0];
    CHECK(c["object_a"].number() == 0);
    CHECK(c["object_b"].number() == 1);
    CHECK_FALSE(c["contained"].boolean());
    // Two unit spheres 1.2 apart: a lens of 0.86 (analytic; the 320-triangle icospheres'
    // is smaller), the normal along the centre line (a into b), depth 0.8.
    CHECK(c["volume"].number() > 0.6);
    CHECK(c["volume"].number() < 0.9);
    CHECK(c["normal"][0].number() > 0.98);
    CHECK(c["depth"].number() > 0.6);
    CHECK(c["depth"].number() < 0.85);
    CHECK(c["point"][0].number() > 0.5);
    CHECK(c["point"][0].number() < 0.7);
    // 64 rays across the longer side of the spheres' box overlap.
    const Json& st = j["frames"][0]["stats"];
    CHECK(std::max(st["contact_rays_x"].number(), st["contact_rays_y"].number()) == 64);
    CHECK(run.out.find("contact a - b: volume") != std::string::npos);
}

TEST_CASE("vkcollide detect --png: colliding triangles highlighted, objects coloured, rays on request", "[cli][gpu]") {
    Scene touching("png", 1.2f);
    touching.files += " --method peeling";  // the collision rays are the peeling method's
    const std::string png = touching.scratch.path("scene.png");
    const Json j = detectJson(touching.scratch, touching.files + " --resolution 64 --png " + png);
    REQUIRE(j["frames"][0]["pairs"].size() > 0);
    const Image image = readPng(png);
    CHECK(image.width == 800);
    CHECK(image.height == 600);
    CHECK(image.count(isHighlight) > 50);
    CHECK(image.count(isObject0) > 1000);
    CHECK(image.count(isObject1) > 1000);
    CHECK(image.count(isRay) == 0);

    Run run;
    const std::string rays_png = touching.scratch.path("rays.png");
    const Json with_rays = detectJson(touching.scratch, touching.files + " --resolution 64 --png " + rays_png + " --rays", run);
    const std::size_t rays = static_cast<std::size_t>(with_rays["frames"][0]["stats"]["collision_rays"].number());
    REQUIRE(rays > 0);
    // Every collision ray of the detection is drawn.
    CHECK(run.out.find("png: " + rays_png + " (" + std::to_string(rays) + " collision rays drawn)") != std::string::npos);
    CHECK(readPng(rays_png).count(isRay) > 200);
    // Three directions: the rays of all three.
    const Json three = detectJson(touching.scratch, touching.files + " --resolution 64 --axes 3 --png " + rays_png + " --rays", run);
    CHECK(run.out.find("(" + std::to_string(static_cast<std::size_t>(three["frames"][0]["stats"]["collision_rays"].number())) +
                       " collision rays drawn)") != std::string::npos);

    Scene apart("png-apart", 3.0f);
    const std::string apart_png = apart.scratch.path("apart.png");
    const Json none = detectJson(apart.scratch, apart.files + " --resolution 64 --png " + apart_png + " --png-size 320,200");
    CHECK(none["frames"][0]["pairs"].size() == 0);
    const Image quiet = readPng(apart_png);
    CHECK(quiet.width == 320);
    CHECK(quiet.height == 200);
    CHECK(quiet.count(isHighlight) == 0);
    CHECK(quiet.count(isObject0) > 100);

    // --view moves the camera: another picture of the same scene.
    const std::string side = apart.scratch.path("side.png");
    detectJson(apart.scratch, apart.files + " --resolution 64 --png " + side + " --png-size 320,200 --view 0,0,1");
    CHECK(readPng(side).rgb != quiet.rgb);
}

TEST_CASE("vkcollide detect --csv with --frames: a line per detection", "[cli][gpu]") {
    Scene s("csv", 1.2f);
    const std::string csv = s.scratch.path("frames.csv");
    const Json j = detectJson(s.scratch, s.files + " --resolution 64 --frames 3 --quiet --csv " + csv);
    CHECK(lineCount(readText(csv)) == 4);
    CHECK(j["frames"].size() == 1);  // one scene: the last detection
    CHECK(j["frames"][0]["frame"].number() == 2);
}

namespace {

// The CSV's header and its last line, by column name.
std::map<std::string, std::string> lastCsvRow(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    REQUIRE(lines.size() >= 2);
    const auto split = [](const std::string& line) {
        std::vector<std::string> cells;
        std::istringstream cells_in(line);
        for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
        return cells;
    };
    const auto header = split(lines.front()), row = split(lines.back());
    REQUIRE(header.size() == row.size());
    std::map<std::string, std::string> out;
    for (std::size_t i = 0; i < header.size(); ++i) out[header[i]] = row[i];
    return out;
}

double column(const std::map<std::string, std::string>& row, const std::string& name) {
    INFO(name);
    REQUIRE(row.count(name) == 1);
    return std::stod(row.at(name));
}

}  // namespace

TEST_CASE("vkcollide detect: the GPU figure is the stages of the method that ran", "[cli][gpu]") {
    Scene s("gpu-figure", 1.2f);
    const std::string csv = s.scratch.path("frames.csv");
    Run run;
    // The reliable method (the default): the front, footprints, pairing and filtering.
    const Json reliable = detectJson(s.scratch, s.files + " --resolution 64 --csv " + csv, run);
    auto row = lastCsvRow(readText(csv));
    CHECK(row.at("method") == "reliable");
    CHECK(row.at("backend") == "none");
    CHECK(column(row, "footprints_ms") > 0);
    CHECK(column(row, "pairing_ms") > 0);
    const double stages =
        column(row, "sampling_ms") + column(row, "footprints_ms") + column(row, "pairing_ms") + column(row, "filtering_ms");
    CHECK(column(row, "gpu_ms") == Approx(stages).margin(0.0025));
    CHECK(column(row, "gpu_ms") > column(row, "sampling_ms"));
    const Json& st = reliable["frames"][0]["stats"];
    CHECK(st["backend"].string() == "none");
    CHECK(st["backend_reason"].string().rfind("none", 0) == 0);
    const std::size_t at = run.out.find("times (ms): GPU ");
    REQUIRE(at != std::string::npos);
    double gpu = 0, front = 0;
    REQUIRE(std::sscanf(run.out.c_str() + at, "times (ms): GPU %lf = front %lf + footprints", &gpu, &front) == 2);
    CHECK(gpu == Approx(st["sampling_ms"].number() + st["footprints_ms"].number() + st["pairing_ms"].number() + st["filtering_ms"].number())
                     .margin(0.0015));
    CHECK(run.out.find("sampling backend") == std::string::npos);

    // Peeling: the paper's GPU column, sampling + merging + separation.
    detectJson(s.scratch, s.files + " --method peeling --resolution 64 --csv " + csv, run);
    row = lastCsvRow(readText(csv));
    CHECK(row.at("method") == "peeling");
    CHECK(row.at("backend") != "none");
    CHECK(column(row, "footprints_ms") == 0);
    CHECK(column(row, "gpu_ms") ==
          Approx(column(row, "sampling_ms") + column(row, "merging_ms") + column(row, "separation_ms")).margin(0.0025));
    CHECK(run.out.find("times (ms): GPU ") != std::string::npos);
}

TEST_CASE("vkcollide detect --device picks the device by name", "[cli][gpu]") {
    Scene s("device", 1.2f);
    const Json any = detectJson(s.scratch, s.files + " --resolution 64");
    const std::string name = any["device"].string();
    const Json picked = detectJson(s.scratch, s.files + " --resolution 64 --device \"" + name.substr(0, 6) + "\"");
    CHECK(picked["device"].string().find(name.substr(0, 6)) != std::string::npos);
    const Run none = runCli("detect " + s.files + " --device no-such-gpu-xyz");
    CHECK(none.status == 1);
    CHECK(none.err.find("no-such-gpu-xyz") != std::string::npos);
}

TEST_CASE("vkcollide --help: every option says what it does and what it costs", "[cli]") {
    const Run help = runCli("detect --help");
    REQUIRE(help.status == 0);
    std::istringstream in(help.out);
    std::vector<std::string> options;
    std::string line, previous;
    int costs = 0;
    for (; std::getline(in, line); previous = line) {
        if (line.rfind("  --", 0) == 0) options.push_back(line.substr(2, line.find(' ', 2) - 2));
        if (line.find(" cost: ") != std::string::npos) ++costs;
    }
    CHECK(costs == static_cast<int>(options.size()));
    // Every option of the table is exercised by these tests (this list is the tests' own).
    const std::set<std::string> tested{
        "--resolution", "--direction", "--cap", "--dual", "--packing", "--backend", "--open-epsilon", "--region", "--no-depth-aware",
        "--no-measure-layers", "--axes", "--coverage", "--closed-epsilon", "--bad-objects", "--paper-packing", "--name",
        "--open", "--self", "--no-self-collision", "--transform", "--translate", "--rotate", "--scale", "--gpu-mesh",
        "--edge-length", "--sequence", "--frame-files", "--frames", "--threads", "--device", "--no-robust-access",
        "--validation", "--quiet", "--pairs", "--json", "--stats", "--csv", "--png", "--png-size", "--view", "--rays",
        "--method", "--timeout", "--wait-poll", "--max-pairs", "--max-candidate-pairs", "--contacts", "--contact-resolution", "--contact-geometry", "--exact", "--exact-pass", "--pair-sort",
        "--responses", "--pair-naming", "--grid-tuning",
        "--proximity", "--proximity-capacity", "--proximity-pairs"};
    CHECK(std::set<std::string>(options.begin(), options.end()) == tested);
}

TEST_CASE("vkcollide detect: errors name the option and the problem", "[cli][gpu]") {
    Scratch s("errors");
    const std::string a = writeMesh(s, "a.off", sphere("a", {0, 0, 0}));
    struct Case {
        std::string args;
        int status;
        std::string says;
    };
    const Case cases[] = {
        {a + " --bogus", 2, "unknown option --bogus"},
        {"--open 1", 2, "detect needs at least one scene file"},
        {a + " --resolution", 1, "--resolution needs a value (N)"},
        {a + " --resolution many", 1, "--resolution needs a number from 0 to 4294967295, got 'many'"},
        {a + " --method peeling --resolution 100", 1, "--resolution 100: resolution 100 is not a power of two"},
        {a + " --method peeling --axes 2", 1, "--axes 2: peeling.axes must be 1 or 3"},
        {a + " --direction 1,0", 1, "--direction needs 3 comma-separated numbers, got 2"},
        {a + " --direction 0,0,0", 1, "--direction 0,0,0: projection direction must be finite and non-zero"},
        {a + " --method peeling --open-epsilon -1", 1, "--open-epsilon -1: peeling.open_epsilon must be finite and >= 0"},
        {a + " --contacts --contact-resolution 8", 1, "--contact-resolution 8: contacts.resolution 8 is not in [16, 4096]"},
        {a + " --closed-epsilon nan", 1, "--closed-epsilon needs a finite number, got 'nan'"},
        {a + " --region 1,1,1,0,0,0", 1, "--region 1,1,1,0,0,0: sampling region must be finite with min <= max"},
        {a + " --coverage fuzzy", 1, "--coverage needs centre, dilate, conservative or best, got 'fuzzy'"},
        {a + " --backend gpu", 1, "--backend needs auto, raster or compute, got 'gpu'"},
        {a + " --packing zip", 1, "--packing needs scan or paper, got 'zip'"},
        {a + " --bad-objects ignore", 1, "--bad-objects needs exclude or fail, got 'ignore'"},
        {a + " --method cells", 1, "--method needs reliable or peeling, got 'cells'"},
        {a + " --max-pairs lots", 1, "--max-pairs needs a whole number"},
        {a + " --method peeling --coverage dilate --backend compute", 1, "--backend compute, --coverage dilate: thin-triangle coverage"},
        {a + " --dual=yes", 1, "--dual takes no value"},
        {a + " --open 2", 1, "--open names file 2, but there is 1 file (numbered from 1)"},
        {a + " --self x", 1, "--self needs all, none or file numbers like 1,3-4"},
        {a + " --name 1", 1, "--name needs FILES:VALUE"},
        {a + " --translate 1:1,2", 1, "--translate 1:1,2: needs 3 comma-separated numbers, got 2"},
        {a + " --rotate 1:0,0,0,90", 1, "--rotate 1:0,0,0,90: needs a non-zero axis"},
        {a + " --scale 1:1,2", 1, "--scale 1:1,2: needs one factor or three"},
        {a + " --transform 1:1,0,0", 1, "--transform 1:1,0,0: needs 12 comma-separated numbers, got 3"},
        {a + " --edge-length 1:0.1", 1, "--edge-length: file 1 is not a --gpu-mesh"},
        {a + " --gpu-mesh 1 --edge-length 1:-2", 1, "--edge-length 1:-2: needs a length > 0"},
        {a + " --gpu-mesh 1 --no-robust-access", 1, "--no-robust-access applies to vkcollide's own device"},
        {a + " --frames 0", 1, "--frames needs a number from 1 to"},
        {a + " --png-size 10,10", 1, "--png-size needs W,H, each from 16 to 8192"},
        {a + " --view 0,0,0", 1, "--view needs a non-zero direction"},
        {a + " --method peeling --rays", 1, "--rays draws on the --png picture: give --png FILE too"},
        {a + " --png " + s.path("no/such/dir/x.png"), 1, "--png: cannot write " + s.path("no/such/dir/x.png")},
        {a + " --json " + s.path("no/such/dir/x.json"), 1, "--json: cannot write"},
        {a + " --pairs " + s.path("no/such/dir/x.csv"), 1, "--pairs: cannot write"},
        {a + " --stats " + s.path("no/such/dir/x.json"), 1, "--stats: cannot write"},
        {a + " --csv " + s.path("no/such/dir/x.csv"), 1, "--csv: cannot write " + s.path("no/such/dir/x.csv")},
        {s.path("missing.off"), 1, "missing.off"},
        {s.path("a.txt"), 1, "a.txt"},
    };
    writeText(s / "a.txt", "not a mesh\n");
    for (const Case& c : cases) {
        INFO(c.args);
        const Run run = runCli("detect " + c.args);
        CHECK(run.status == c.status);
        CHECK(run.err.find(c.says) != std::string::npos);
        if (c.status == 2) CHECK(run.err.find("usage: vkcollide") != std::string::npos);
    }
    const Run no_command = runCli("frobnicate");
    CHECK(no_command.status == 2);
    CHECK(no_command.err.find("unknown command frobnicate") != std::string::npos);
}
