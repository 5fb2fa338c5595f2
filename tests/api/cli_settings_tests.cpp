// `vkcollide detect`: every DetectSettings option reaches the detection. Each test reads
// the --json the tool wrote: the setting as asked and as used, and an effect the setting
// must have on what ran (layers, passes, backend, rays, pairs), against a run without it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <fstream>
#include <sstream>

#include "api/cli_support.hpp"

using namespace clitest;

namespace {

// Two overlapping spheres (a at the origin, b moved along x), one OFF file each. `files`
// also names the peeling method: most options shape its ray sampling (the reliable
// method, the default, is tested at the end).
struct TwoSpheres {
    Scratch scratch{"settings"};
    std::string files, plain_files;
    std::vector<vkcollide::HostMesh> world;
    explicit TwoSpheres(float gap_x = 1.2f) {
        world = {sphere("a", {0, 0, 0}), sphere("b", {gap_x, 0.1f, 0.05f})};
        plain_files = writeMesh(scratch, "a.off", world[0]) + " " + writeMesh(scratch, "b.off", world[1]);
        files = plain_files + " --method peeling";
    }
};

const Json& stats(const Json& j) { return j["frames"][0]["stats"]; }

std::vector<std::string> passNames(const Json& j) {
    std::vector<std::string> out;
    for (const Json& p : stats(j)["gpu_passes"].array()) out.push_back(p["name"].string());
    return out;
}

bool hasPass(const Json& j, const std::string& name) {
    const auto names = passNames(j);
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

TEST_CASE("vkcollide detect: --resolution and --direction set what runs", "[cli][gpu]") {
    TwoSpheres s;
    const Json j = detectJson(s.scratch, s.files + " --resolution 128 --direction 1,0,0");
    CHECK(j["settings"]["asked"]["resolution"].number() == 128);
    CHECK(j["settings"]["used"]["resolution"].number() == 128);
    CHECK(stats(j)["resolution"].number() == 128);
    CHECK(stats(j)["direction"][0].number() == 1);
    CHECK(stats(j)["direction"][1].number() == 0);
    CHECK(stats(j)["direction"][2].number() == 0);
    // Left out: chosen from the scene, and the JSON says so.
    const Json automatic = detectJson(s.scratch, s.files);
    CHECK(automatic["settings"]["asked"]["resolution"].isNull());
    CHECK(automatic["settings"]["asked"]["direction"].isNull());
    CHECK(automatic["settings"]["used"]["resolution"].number() == stats(automatic)["resolution"].number());
    CHECK(stats(automatic)["settings_note"].string().find("resolution") != std::string::npos);
}

TEST_CASE("vkcollide detect: --cap and --dual change the peeling", "[cli][gpu]") {
    TwoSpheres s;
    const Json plain = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0");
    REQUIRE(stats(plain)["depth_complexity"].number() >= 4);  // along x: a, then b, entered and left
    const Json capped = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0 --cap 1");
    CHECK(capped["settings"]["asked"]["layer_cap"].number() == 1);
    CHECK(stats(capped)["layers"].number() == 1);
    CHECK_FALSE(stats(capped)["layers_short"].boolean());  // a cap asked for is not "short"
    // Every ray deeper than one layer is a collision ray now.
    CHECK(stats(capped)["collision_rays"].number() > stats(plain)["collision_rays"].number());

    const Json dual = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0 --dual");
    CHECK(dual["settings"]["asked"]["dual"].boolean());
    CHECK(stats(dual)["dual"].boolean());
    CHECK(stats(dual)["peel_passes"].number() < stats(plain)["peel_passes"].number());
    CHECK(jsonPairs(dual["frames"][0]) == jsonPairs(plain["frames"][0]));
}

TEST_CASE("vkcollide detect: --packing, --paper-packing and --backend choose the passes", "[cli][gpu]") {
    TwoSpheres s;
    const Json scan = detectJson(s.scratch, s.files + " --resolution 64");
    CHECK(hasPass(scan, "pack-scan"));
    CHECK_FALSE(hasPass(scan, "pack-move"));
    for (const char* option : {" --packing paper", " --paper-packing"}) {
        INFO(option);
        const Json paper = detectJson(s.scratch, s.files + " --resolution 64" + option);
        CHECK(paper["settings"]["asked"]["packing"].string() == "paper");
        CHECK(hasPass(paper, "pack-move"));
        CHECK_FALSE(hasPass(paper, "pack-scan"));
        CHECK(jsonPairs(paper["frames"][0]) == jsonPairs(scan["frames"][0]));
    }
    for (const char* backend : {"raster", "compute"}) {
        INFO(backend);
        const Json j = detectJson(s.scratch, s.files + " --resolution 64 --backend " + backend);
        CHECK(j["settings"]["asked"]["backend"].string() == backend);
        CHECK(stats(j)["backend"].string() == backend);
        CHECK(jsonPairs(j["frames"][0]) == jsonPairs(scan["frames"][0]));
    }
}

TEST_CASE("vkcollide detect: --open-epsilon is used for open objects", "[cli][gpu]") {
    TwoSpheres s;
    const Json automatic = detectJson(s.scratch, s.files + " --open 2");
    CHECK(automatic["settings"]["asked"]["open_epsilon"].isNull());
    CHECK(automatic["settings"]["used"]["open_epsilon"].number() > 0);  // half the open object's typical edge
    const Json j = detectJson(s.scratch, s.files + " --open 2 --open-epsilon 0.0625");
    CHECK(j["settings"]["asked"]["open_epsilon"].number() == 0.0625);
    CHECK(j["settings"]["used"]["open_epsilon"].number() == 0.0625);
}

TEST_CASE("vkcollide detect: --region samples only its box", "[cli][gpu]") {
    TwoSpheres s;
    // The spheres overlap for x in [0.2, 1]: a box around a's far side sees none of it (a
    // square one: the image is square, over the box's wider side).
    const Json left = detectJson(s.scratch, s.files + " --resolution 64 --direction 0,0,1 --region -1.2,-0.5,-1.2,-0.2,0.5,1.2");
    CHECK(left["settings"]["used"]["region"][0].number() == Approx(-1.2));
    CHECK(left["settings"]["used"]["region"][3].number() == Approx(-0.2));
    CHECK(stats(left)["collision_rays"].number() == 0);
    CHECK(left["frames"][0]["pairs"].size() == 0);
    const Json all = detectJson(s.scratch, s.files + " --resolution 64 --direction 0,0,1 --region -1.2,-1.8,-1.2,2.4,1.8,1.2");
    CHECK(all["frames"][0]["pairs"].size() > 0);
}

TEST_CASE("vkcollide detect: --no-measure-layers predicts from the last detection", "[cli][gpu]") {
    TwoSpheres s;
    const Json measured = detectJson(s.scratch, s.files + " --resolution 64 --frames 2");
    CHECK(measured["settings"]["asked"]["measure_layers"].boolean());
    const Json predicted = detectJson(s.scratch, s.files + " --resolution 64 --frames 2 --no-measure-layers");
    CHECK_FALSE(predicted["settings"]["asked"]["measure_layers"].boolean());
    // Measuring adds a readback between two submissions; predicting records one.
    const auto count = [](const std::vector<std::string>& names, const std::string& n) { return std::count(names.begin(), names.end(), n); };
    CHECK(count(passNames(measured), "readback-header") == 2);
    CHECK(count(passNames(predicted), "readback-header") == 1);
    CHECK(jsonPairs(predicted["frames"][0]) == jsonPairs(measured["frames"][0]));
}

TEST_CASE("vkcollide detect: --axes 3 samples three directions", "[cli][gpu]") {
    TwoSpheres s;
    const Json one = detectJson(s.scratch, s.files + " --resolution 64");
    const Json three = detectJson(s.scratch, s.files + " --resolution 64 --axes 3");
    CHECK(three["settings"]["asked"]["axes"].number() == 3);
    CHECK(stats(three)["axes"].number() == 3);
    CHECK(hasPass(three, "axis 2: merge"));
    CHECK_FALSE(hasPass(one, "axis 2: merge"));
    // The union tests at least what one direction tests, with the same exact test.
    const auto p1 = jsonPairs(one["frames"][0]), p3 = jsonPairs(three["frames"][0]);
    CHECK(std::includes(p3.begin(), p3.end(), p1.begin(), p1.end()));
}

TEST_CASE("vkcollide detect: --coverage reaches the sampling", "[cli][gpu]") {
    TwoSpheres s;
    const Json centre = detectJson(s.scratch, s.files + " --resolution 64 --backend raster");
    CHECK(stats(centre)["coverage"].string() == "centre");
    const Json dilate = detectJson(s.scratch, s.files + " --resolution 64 --backend raster --coverage dilate");
    CHECK(dilate["settings"]["asked"]["coverage"].string() == "dilate");
    CHECK(stats(dilate)["coverage"].string() == "dilate");
    // Thin triangles mark every ray they touch: never fewer collision rays.
    CHECK(stats(dilate)["collision_rays"].number() >= stats(centre)["collision_rays"].number());
    const Json best = detectJson(s.scratch, s.files + " --resolution 64 --backend raster --coverage best");
    const std::string used = best["settings"]["used"]["coverage"].string();
    CHECK((used == "dilate" || used == "conservative"));
    CHECK(stats(best)["coverage"].string() == used);
}

TEST_CASE("vkcollide detect: --closed-epsilon makes near surfaces touch", "[cli][gpu]") {
    TwoSpheres s(2.04f);  // b's surface 0.04 from a's along x, no contact
    const Json exact = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0");
    CHECK(stats(exact)["collision_rays"].number() == 0);
    const Json near = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0 --closed-epsilon 0.25");
    CHECK(near["settings"]["asked"]["closed_epsilon"].number() == 0.25);
    CHECK(stats(near)["collision_rays"].number() > 0);
    CHECK(near["frames"][0]["pairs"].size() == 0);  // the exact test still finds no contact
}

TEST_CASE("vkcollide detect: --bad-objects is handed to the detection", "[cli][gpu]") {
    TwoSpheres s;
    // Files pass the strict readers, so no engine mesh fails the GPU check here: the policy
    // is shown as asked and the detection runs under it.
    for (const char* policy : {"exclude", "fail"}) {
        INFO(policy);
        const Json j = detectJson(s.scratch, s.files + " --gpu-mesh all --bad-objects " + policy);
        CHECK(j["settings"]["asked"]["bad_objects"].string() == policy);
        CHECK(j["frames"][0]["excluded"].size() == 0);
        CHECK(j["frames"][0]["pairs"].size() > 0);
    }
}

namespace {

// The options of a --help section, and of those the ones --help marks "peeling only" and
// "reliable only".
struct HelpOptions {
    std::set<std::string> all, peeling_only, reliable_only;
};
HelpOptions helpOptions(const std::string& section, const std::string& next) {
    const Run help = runCli("detect --help");
    REQUIRE(help.status == 0);
    const std::size_t begin = help.out.find(section), end = help.out.find(next, begin);
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    HelpOptions out;
    std::istringstream lines(help.out.substr(begin, end - begin));
    std::string option;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("  --", 0) == 0) out.all.insert(option = line.substr(2, line.find(' ', 2) - 2));
        // The help follows the name on its line, or on the next one for a long name.
        if (line.find("  peeling only: ") != std::string::npos) out.peeling_only.insert(option);
        if (line.find("  reliable only: ") != std::string::npos) out.reliable_only.insert(option);
    }
    return out;
}

std::set<std::string> keys(const Json& object) {
    std::set<std::string> out;
    for (const auto& [key, value] : object.object()) out.insert(key);
    return out;
}

}  // namespace

TEST_CASE("vkcollide detect: the JSON's settings are those the method that ran reads, one per option of --help", "[cli]") {
    TwoSpheres s;
    // The settings section of --help lists one option per field (and --paper-packing).
    HelpOptions options = helpOptions("Detection settings", "\nObjects");
    options.all.erase("--paper-packing");
    options.peeling_only.erase("--paper-packing");
    const Json j = detectJson(s.scratch, s.files + " --resolution 64");
    CHECK(j["settings"]["asked"].object().size() == options.all.size() - options.reliable_only.size());
    CHECK(j["settings"]["used"].object().size() == options.all.size() - options.reliable_only.size());
    CHECK(options.reliable_only == std::set<std::string>{"--exact", "--exact-pass", "--pair-sort", "--responses", "--pair-naming",
                                                         "--grid-tuning", "--proximity", "--proximity-capacity"});
    CHECK_FALSE(j["settings"]["used"].has("exact"));
    CHECK(j["settings"]["used"].has("depth_aware"));
    // The reliable method: the fields it reads, and none that only peeling reads.
    const Json reliable = detectJson(s.scratch, s.plain_files + " --resolution 64");
    CHECK(reliable["settings"]["asked"].object().size() == options.all.size() - options.peeling_only.size());
    CHECK(keys(reliable["settings"]["used"]) == keys(reliable["settings"]["asked"]));
    for (const char* read : {"method", "resolution", "direction", "region", "bad_objects", "max_candidate_pairs", "contacts", "exact", "pair_sort"})
        CHECK(reliable["settings"]["used"].has(read));
    for (const char* unread : {"layer_cap", "dual", "packing", "backend", "open_epsilon", "measure_layers", "axes", "coverage",
                               "closed_epsilon", "depth_aware"}) {
        INFO(unread);
        CHECK_FALSE(reliable["settings"]["used"].has(unread));
        CHECK(j["settings"]["used"].has(unread));
    }
}

TEST_CASE("vkcollide detect: an option of the peeling method is refused under the reliable method, by name", "[cli]") {
    TwoSpheres s;
    const std::string png = s.scratch.path("x.png");
    const std::vector<std::string> peeling_only{"--cap 2",
                                                "--dual",
                                                "--packing paper",
                                                "--paper-packing",
                                                "--backend raster",
                                                "--open-epsilon 0.1",
                                                "--no-measure-layers",
                                                "--axes 3",
                                                "--axes 1",
                                                "--coverage dilate",
                                                "--closed-epsilon 0.01",
                                                "--no-depth-aware",
                                                "--rays --png " + png};
    std::set<std::string> refused;
    for (const std::string& option : peeling_only) {
        const std::string name = option.substr(0, option.find(' '));
        refused.insert(name);
        for (const char* method : {"", " --method reliable"}) {
            INFO(option << method);
            const Run run = runCli("detect " + s.plain_files + method + " " + option);
            CHECK(run.status == 1);
            CHECK(run.err.find(name + " belongs to the peeling method (--method peeling); the reliable method") != std::string::npos);
        }
    }
    // --help marks exactly those (its settings and its output sections).
    std::set<std::string> marked = helpOptions("Detection settings", "\nObjects").peeling_only;
    marked.merge(helpOptions("\nOutput", "-h, --help").peeling_only);
    CHECK(marked == refused);
    // Under the peeling method they run (each one's effect: the tests above).
    const Json j = detectJson(s.scratch, s.plain_files + " --method peeling --resolution 64 --dual --axes 1 --no-depth-aware");
    CHECK(j["settings"]["used"]["dual"].boolean());
}

TEST_CASE("vkcollide detect: --no-depth-aware runs the paper's separation", "[cli][gpu]") {
    TwoSpheres s;
    const Json aware = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0");
    CHECK(aware["settings"]["asked"]["depth_aware"].boolean());
    const Json paper = detectJson(s.scratch, s.files + " --resolution 64 --direction 1,0,0 --no-depth-aware");
    CHECK_FALSE(paper["settings"]["asked"]["depth_aware"].boolean());
    CHECK_FALSE(paper["settings"]["used"]["depth_aware"].boolean());
    // The same collision rays; every triangle under them is downloaded, whatever its depth.
    CHECK(stats(paper)["collision_rays"].number() == stats(aware)["collision_rays"].number());
    CHECK(stats(paper)["triangles_downloaded"].number() > stats(aware)["triangles_downloaded"].number());
    CHECK(jsonPairs(paper["frames"][0]) == jsonPairs(aware["frames"][0]));
}

TEST_CASE("vkcollide detect: --method chooses the broad phase, reliable by default, with the same pairs here", "[cli][gpu]") {
    TwoSpheres s;
    const Json reliable = detectJson(s.scratch, s.plain_files);
    CHECK(reliable["settings"]["used"]["method"].string() == "reliable");
    CHECK(stats(reliable)["method"].string() == "reliable");
    CHECK(stats(reliable)["cell_entries"].number() > 0);
    CHECK(stats(reliable)["cell_survivors"].number() >= static_cast<double>(reliable["frames"][0]["pairs"].size()));
    CHECK_FALSE(hasPass(reliable, "pack-scan"));
    const Json peeling = detectJson(s.scratch, s.plain_files + " --method peeling --resolution 512");
    CHECK(stats(peeling)["method"].string() == "peeling");
    CHECK(hasPass(peeling, "pack-scan"));
    REQUIRE(reliable["frames"][0]["pairs"].size() > 0);
    CHECK(jsonPairs(peeling["frames"][0]) == jsonPairs(reliable["frames"][0]));
}

TEST_CASE("vkcollide detect: --max-pairs keeps that many and says the rest were left out, --timeout, --wait-poll and --max-candidate-pairs reach the settings",
          "[cli][gpu]") {
    TwoSpheres s;
    const Json all = detectJson(s.scratch, s.plain_files);
    REQUIRE(all["frames"][0]["pairs"].size() > 3);
    Run run;
    const Json capped = detectJson(s.scratch, s.plain_files + " --max-pairs 3 --timeout 30000 --wait-poll 0 --max-candidate-pairs 100000000", run);
    CHECK(capped["settings"]["used"]["max_pairs"].number() == 3);
    CHECK(capped["settings"]["used"]["timeout_ms"].number() == 30000);
    CHECK(capped["settings"]["used"]["wait_poll_us"].number() == 0);
    CHECK(all["settings"]["used"]["wait_poll_us"].number() == 500);
    CHECK(capped["settings"]["used"]["max_candidate_pairs"].number() == 100000000);
    CHECK(capped["frames"][0]["pairs"].size() == 3);
    // The reliable method (the default) checks the budget on the GPU, before the narrow phase.
    const Run few = runCli("detect " + s.plain_files + " --max-candidate-pairs 1");
    CHECK(few.status != 0);
    CHECK(few.err.find("limits.max_candidate_pairs (1)") != std::string::npos);
    const Run few_peeling = runCli("detect " + s.plain_files + " --method peeling --max-candidate-pairs 1");
    CHECK(few_peeling.status != 0);
    CHECK(few_peeling.err.find("max_box_pairs") != std::string::npos);
}

TEST_CASE("vkcollide detect: --proximity writes the pairs within a distance to the JSON and a CSV", "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const std::string csv = s.scratch.path("near.csv");
    const Json j = detectJson(s.scratch, s.plain_files + " --proximity 0.05 --proximity-pairs " + csv);
    CHECK(j["settings"]["used"]["proximity"].number() == Approx(0.05));
    const Json& near = j["frames"][0]["proximity"];
    REQUIRE(near.size() > 0);
    CHECK(stats(j)["proximity"]["pairs"].number() == double(near.size()));
    for (std::size_t i = 0; i < near.size(); ++i) CHECK(near[i]["distance"].number() <= 0.05 * (1 + 1e-6));
    std::ifstream in(csv);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) {
        ++lines;
        CHECK((line.rfind("vertex-triangle,", 0) == 0 || line.rfind("edge-edge,", 0) == 0));
    }
    CHECK(lines == near.size());
    // Without it: no pairs, no statistics; under the peeling method: refused by name.
    const Json plain = detectJson(s.scratch, s.plain_files);
    CHECK(plain["frames"][0]["proximity"].size() == 0);
    CHECK_FALSE(stats(plain).has("proximity"));
    const Run run = runCli("detect " + s.files + " --proximity 0.05");
    CHECK(run.status == 1);
    CHECK(run.err.find("--proximity belongs to the reliable method") != std::string::npos);
}

TEST_CASE("vkcollide detect: --exact chooses where the reliable method's exact test runs", "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const Json gpu = detectJson(s.scratch, s.plain_files + " --exact gpu");
    const Json cpu = detectJson(s.scratch, s.plain_files + " --exact cpu");
    CHECK(gpu["settings"]["asked"]["exact"].string() == "gpu");
    CHECK(cpu["settings"]["used"]["exact"].string() == "cpu");
    REQUIRE(stats(gpu)["pairs"].number() > 0);
    CHECK(stats(gpu)["gpu_exact_tests"].number() > 0);
    CHECK(stats(gpu)["cpu_exact_tests"].number() == 0);
    CHECK(stats(cpu)["gpu_exact_tests"].number() == 0);
    CHECK(stats(cpu)["cpu_exact_tests"].number() > 0);
    // The same pairs either way, and the exact ones.
    CHECK(jsonPairs(gpu["frames"][0]) == jsonPairs(cpu["frames"][0]));
    CHECK(jsonPairs(gpu["frames"][0]) == referencePairs(s.world, {false, false}));
    // An option of the reliable method: refused under the peeling method, by name.
    const Run run = runCli("detect " + s.files + " --exact cpu");
    CHECK(run.status == 1);
    CHECK(run.err.find("--exact belongs to the reliable method") != std::string::npos);
}

TEST_CASE("vkcollide detect: --pair-sort, --responses and --pair-naming choose where the pairs are put in order, the responses computed and the pairs named",
          "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const Json gpu = detectJson(s.scratch, s.plain_files + " --pair-sort gpu");
    const Json cpu = detectJson(s.scratch, s.plain_files + " --pair-sort cpu");
    const Json host_responses = detectJson(s.scratch, s.plain_files + " --pair-sort gpu --responses cpu");
    CHECK(gpu["settings"]["asked"]["pair_sort"].string() == "gpu");
    CHECK(cpu["settings"]["used"]["pair_sort"].string() == "cpu");
    CHECK(host_responses["settings"]["used"]["responses"].string() == "cpu");
    REQUIRE(stats(gpu)["pairs"].number() > 0);
    CHECK(stats(gpu)["pairs_sorted_on_gpu"].boolean() == (stats(gpu)["gpu_exact_tests"].number() > 0));
    CHECK(stats(gpu)["responses_on_gpu"].boolean() == stats(gpu)["pairs_sorted_on_gpu"].boolean());  // --responses auto
    CHECK_FALSE(stats(cpu)["pairs_sorted_on_gpu"].boolean());
    CHECK_FALSE(stats(cpu)["responses_on_gpu"].boolean());
    CHECK_FALSE(stats(host_responses)["responses_on_gpu"].boolean());
    for (const Json* other : {&cpu, &host_responses}) {
        CHECK(jsonPairs(gpu["frames"][0]) == jsonPairs((*other)["frames"][0]));
        const Json &rg = gpu["frames"][0]["responses"], &rc = (*other)["frames"][0]["responses"];
        REQUIRE(rg.size() == rc.size());
        for (std::size_t k = 0; k < rg.size(); ++k) {
            CHECK(rg[k]["triangle"].number() == rc[k]["triangle"].number());
            CHECK(rg[k]["partners"].number() == rc[k]["partners"].number());
            for (std::size_t c = 0; c < 3; ++c) CHECK(rg[k]["direction"][c].number() == rc[k]["direction"][c].number());
        }
    }
    const Run run = runCli("detect " + s.files + " --pair-sort gpu");
    CHECK(run.status == 1);
    CHECK(run.err.find("--pair-sort belongs to the reliable method") != std::string::npos);
    const Run refused = runCli("detect " + s.plain_files + " --responses gpu --pair-sort cpu");
    CHECK(refused.status == 1);
    CHECK(refused.err.find("reliable.responses Gpu needs the pairs sorted on the GPU") != std::string::npos);
    // --pair-naming: when the host names the GPU's sorted pairs (the same pairs either way).
    const Json after_fence = detectJson(s.scratch, s.plain_files + " --pair-sort gpu --pair-naming after-fence");
    CHECK(after_fence["settings"]["asked"]["pair_naming"].string() == "after-fence");
    CHECK(after_fence["settings"]["used"]["pair_naming"].string() == "after-fence");
    CHECK(gpu["settings"]["used"]["pair_naming"].string() == "auto");
    CHECK_FALSE(stats(after_fence)["pairs_named_during_gpu"].boolean());
    CHECK(jsonPairs(after_fence["frames"][0]) == jsonPairs(gpu["frames"][0]));
    const Run bad_naming = runCli("detect " + s.plain_files + " --pair-naming never");
    CHECK(bad_naming.status == 1);
    CHECK(bad_naming.err.find("--pair-naming needs auto or after-fence, got 'never'") != std::string::npos);
    // --pair-sort auto, few pairs: one GPU pass sorts them and computes the responses; the
    // JSON and the summary say where each part ran.
    const bool on_gpu = stats(gpu)["gpu_exact_tests"].number() > 0;
    const Json automatic = detectJson(s.scratch, s.plain_files);
    REQUIRE(stats(automatic)["pairs"].number() < 4096);
    CHECK(stats(automatic)["pairs_sorted_in_one_pass"].boolean() == on_gpu);
    CHECK(stats(automatic)["pairs_sorted_on_gpu"].boolean() == on_gpu);
    CHECK_FALSE(stats(gpu)["pairs_sorted_in_one_pass"].boolean());
    CHECK_FALSE(stats(cpu)["pairs_sorted_in_one_pass"].boolean());
    CHECK(jsonPairs(automatic["frames"][0]) == jsonPairs(cpu["frames"][0]));
    const auto summary = [&](const std::string& options) {
        const Run r = runCli("detect " + s.plain_files + options);
        CHECK(r.status == 0);
        const std::size_t at = r.out.find("exact decision: ");
        return at == std::string::npos ? std::string() : r.out.substr(at, r.out.find('\n', at) - at);
    };
    if (on_gpu) {
        CHECK(summary("").find("pairs sorted in one GPU pass, responses computed on the GPU (GPU sorting ") != std::string::npos);
        CHECK(summary(" --pair-sort gpu").find("pairs sorted on the GPU, responses computed on the GPU") != std::string::npos);
    }
    CHECK(summary(" --pair-sort cpu").find("pairs sorted on the host, responses computed on the host") != std::string::npos);
    CHECK(summary(" --exact cpu").find("exact decision: CPU (") != std::string::npos);
}

TEST_CASE("vkcollide detect: --exact-pass runs the exact decision inside the pair pass or in a pass of its own", "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const Json inl = detectJson(s.scratch, s.plain_files + " --exact-pass inline");
    const Json queued = detectJson(s.scratch, s.plain_files + " --exact-pass queued");
    const Json automatic = detectJson(s.scratch, s.plain_files);
    CHECK(inl["settings"]["asked"]["exact_pass"].string() == "inline");
    CHECK(queued["settings"]["used"]["exact_pass"].string() == "queued");
    CHECK(automatic["settings"]["used"]["exact_pass"].string() == "auto");
    REQUIRE(stats(inl)["pairs"].number() > 0);
    if (stats(inl)["gpu_exact_tests"].number() > 0) {  // a device with shaderFloat64 (lavapipe has it)
        CHECK(stats(inl)["cell_exact_pass"].string() == "inline");
        CHECK(stats(queued)["cell_exact_pass"].string() == "queued");
        CHECK(stats(automatic)["cell_exact_pass"].string() == "inline");  // Auto's first detection
        const auto passes = [](const Json& j) {
            std::set<std::string> names;
            for (std::size_t k = 0; k < stats(j)["gpu_passes"].size(); ++k) names.insert(stats(j)["gpu_passes"][k]["name"].string());
            return names;
        };
        CHECK(passes(queued).count("cells-exact") == 1);
        CHECK(passes(inl).count("cells-exact") == 0);
        // What the filter did: it ran (a first detection always filters) and its rejections
        // and the exact tests together are the canonical candidates, either way.
        for (const Json* j : {&inl, &queued}) {
            CHECK(stats(*j)["cell_filter_ran"].boolean());
            CHECK(stats(*j)["cell_filtered"].number() + stats(*j)["gpu_exact_tests"].number() ==
                  stats(inl)["cell_filtered"].number() + stats(inl)["gpu_exact_tests"].number());
        }
    }
    CHECK(jsonPairs(inl["frames"][0]) == jsonPairs(queued["frames"][0]));
    const Run bad = runCli("detect " + s.plain_files + " --exact-pass later");
    CHECK(bad.status == 1);
    CHECK(bad.err.find("--exact-pass needs auto, inline or queued, got 'later'") != std::string::npos);
    const Run run = runCli("detect " + s.files + " --exact-pass queued");
    CHECK(run.status == 1);
    CHECK(run.err.find("--exact-pass belongs to the reliable method") != std::string::npos);
}

// --grid-tuning: auto resolves to off on lavapipe (on on a GPU); on, the scene's second detection (what
// --frames 2 reports) tries the coarser grid, says so, and gives the same pairs.
TEST_CASE("vkcollide detect: --grid-tuning chooses the grid per scene, same pairs", "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const Json plain = detectJson(s.scratch, s.plain_files + " --frames 2");
    const Json tuned = detectJson(s.scratch, s.plain_files + " --frames 2 --grid-tuning on");
    CHECK(plain["settings"]["asked"]["grid_tuning"].string() == "auto");
    CHECK(plain["settings"]["used"]["grid_tuning"].string() == "off");
    CHECK(tuned["settings"]["used"]["grid_tuning"].string() == "on");
    CHECK(jsonPairs(tuned["frames"][0]) == jsonPairs(plain["frames"][0]));
    CHECK(stats(tuned)["resolution"].number() < stats(plain)["resolution"].number());
    CHECK(stats(tuned)["settings_note"].string().find("grid tuned per scene: trying x0.71") != std::string::npos);
    const Run run = runCli("detect " + s.files + " --grid-tuning on");
    CHECK(run.status == 1);
    CHECK(run.err.find("--grid-tuning belongs to the reliable method") != std::string::npos);
}

TEST_CASE("vkcollide detect: --contact-geometry writes where each pair meets and the totals", "[cli][gpu]") {
    TwoSpheres s(1.0f);
    const Json plain = detectJson(s.scratch, s.plain_files);
    const Json on = detectJson(s.scratch, s.plain_files + " --contact-geometry");
    const Json& frame = on["frames"][0];
    REQUIRE(frame["pairs"].size() > 0);
    CHECK(jsonPairs(frame) == jsonPairs(plain["frames"][0]));
    CHECK(plain["frames"][0]["pair_contacts"].size() == 0);
    REQUIRE(frame["pair_contacts"].size() == frame["pairs"].size());
    double length = 0;
    for (const Json& c : frame["pair_contacts"].array()) {
        const std::string shape = c["shape"].string();
        CHECK((shape == "segment" || shape == "point" || shape == "coplanar"));
        if (shape == "segment") {
            double d2 = 0;
            for (std::size_t k = 0; k < 3; ++k) d2 += std::pow(c["end"][k].number() - c["start"][k].number(), 2);
            length += std::sqrt(d2);
        }
    }
    REQUIRE(frame["pair_contact_totals"].size() == 1);  // the two spheres
    const Json& total = frame["pair_contact_totals"][0];
    CHECK(total["pairs"].number() == double(frame["pairs"].size()));
    CHECK(total["length"].number() == Approx(length).epsilon(1e-4));
    CHECK(on["settings"]["used"]["contact_geometry"].boolean());
}
