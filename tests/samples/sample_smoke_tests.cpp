// The samples as programs: a reduced scene of each, a few frames on the device found, the
// validation layer on (ctest sets VKCOLLIDE_TEST_VALIDATION=1, which the samples obey and
// exit with status 3 on any message). Each test reads the frames.csv the sample wrote and
// checks the contacts its scene must produce, and that the frames were rendered.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

// The columns of a sample's frames.csv, numeric ones as numbers (others read as 0), and
// every one as text.
struct Csv {
    std::map<std::string, std::vector<double>> columns;
    std::map<std::string, std::vector<std::string>> text;
    std::size_t rows = 0;
    const std::vector<double>& operator[](const std::string& name) const {
        auto it = columns.find(name);
        if (it == columns.end()) FAIL("frames.csv has no column " << name);
        return it->second;
    }
};

Csv readCsv(const fs::path& path) {
    std::ifstream in(path);
    REQUIRE(in.good());
    std::string line;
    std::getline(in, line);
    std::vector<std::string> names;
    std::stringstream header(line);
    for (std::string name; std::getline(header, name, ',');) names.push_back(name);
    Csv csv;
    while (std::getline(in, line)) {
        std::stringstream row(line);
        std::size_t i = 0;
        for (std::string cell; std::getline(row, cell, ',') && i < names.size(); ++i) {
            csv.columns[names[i]].push_back(std::strtod(cell.c_str(), nullptr));
            csv.text[names[i]].push_back(cell);
        }
        ++csv.rows;
    }
    return csv;
}

// A sample's output folder and log, removed when the test is done with them.
struct Scratch {
    fs::path dir, log;
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
        fs::remove(log, ec);
    }
};

struct Run {
    int status = 0;      // the program's exit status
    std::string output;  // stdout and stderr
};

Run start(const Scratch& scratch, const char* program, const std::string& args, int frames) {
    fs::remove_all(scratch.dir);
    const std::string cmd = std::string(program) + " --out " + scratch.dir.string() + " --frames " + std::to_string(frames) +
                            " --width 96 --height 64 --quiet --stand-ins " + args + " > " + scratch.log.string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream text(scratch.log);
    std::stringstream output;
    output << text.rdbuf();
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, cmd + "\n" + output.str()};
}

// Runs a sample into a fresh folder. The sample must exit with 0 (3 would mean validation
// messages) and write one PNG per frame. Returns what it printed.
std::string runSample(const Scratch& scratch, const char* program, const std::string& args, int frames) {
    const fs::path& out = scratch.dir;
    const Run run = start(scratch, program, args, frames);
    INFO(run.output);
    REQUIRE(run.status == 0);
    for (int f = 0; f < frames; ++f) {
        char png[32];
        std::snprintf(png, sizeof png, "frame_%04d.png", f);
        std::ifstream image(out / png, std::ios::binary);
        char signature[8] = {};
        image.read(signature, 8);
        REQUIRE(std::string(signature + 1, 3) == "PNG");
    }
    return run.output;
}

Scratch scratchFor(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("vkcollide-sample-" + name + "-" + std::to_string(::getpid()));
    return {dir, dir.string() + ".log"};
}

double max(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double min(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("cloth sample: the falling cloth touches the sphere and does not pass through it", "[samples][gpu]") {
    const int frames = 30;
    const Scratch out = scratchFor("cloth");
    runSample(out, VKCOLLIDE_SAMPLE_CLOTH, "--cells 12 --drop 0.05 --fold 0 --dt 0.01", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(csv["cloth_sphere_pairs"].front() == 0);  // it starts above the sphere
    CHECK(max(csv["cloth_sphere_pairs"]) > 0);
    CHECK(max(csv["max_penetration"]) < 0.1);  // sphere radius 0.35: pushed back out, not through
    CHECK(min(csv["triangles"]) == max(csv["triangles"]));
}

TEST_CASE("cloth sample --ball: the pinned cloth stops the ball, and no frame has an intersecting pair", "[samples][gpu]") {
    const int frames = 30;
    const Scratch out = scratchFor("cloth-ball");
    // Ball radius 0.35, thrown down at 3 m/s from 0.2 above the cloth; 0.3 s.
    const std::string output = runSample(out, VKCOLLIDE_SAMPLE_CLOTH, "--ball --cells 10 --size 2 --dt 0.01", frames);
    INFO(output);
    CHECK(output.find("ball: no intersecting pair in any of the 30 frames") != std::string::npos);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(max(csv["intersecting_pairs"]) == 0);
    CHECK(csv["ball_cloth_near"].front() == 0);  // it starts out of reach
    CHECK(max(csv["ball_cloth_near"]) > 0);
    CHECK(min(csv["cloth_lowest"]) < -0.05);  // the ball pushed the cloth down
    // Falling freely, the ball's centre would end 1.3 below where it started (0.55) and
    // faster than it started; the cloth holds it within its sag and turns it back.
    CHECK(min(csv["ball_height"]) > 0.35 - 0.4);
    CHECK(csv["ball_speed"].back() < csv["ball_speed"].front());
    CHECK(csv["ball_height"].back() > min(csv["ball_height"]) + 0.1);
}

TEST_CASE("rigid bunnies sample: bunnies land in the box and on each other", "[samples][gpu]") {
    const int frames = 60;
    const Scratch out = scratchFor("rigid");
    runSample(out, VKCOLLIDE_SAMPLE_RIGID_BUNNIES, "--bunnies 3 --columns 1 --bunny-triangles 300 --drop 0.05", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(max(csv["bunny_box_pairs"]) > 0);
    CHECK(max(csv["bunny_bunny_pairs"]) > 0);
    CHECK(min(csv["lowest_centre"]) > 0);  // nobody fell through the floor (its top is y = 0)
    CHECK(csv["bunnies_in_box"].back() == 3);
}

TEST_CASE("dragon sample: the bunny passing through the dragon collides with it", "[samples][gpu]") {
    const int frames = 5;
    const Scratch out = scratchFor("dragon");
    runSample(out, VKCOLLIDE_SAMPLE_DRAGON, "--triangles 12000 --passer-triangles 600", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(csv["dragon_bunny_pairs"].front() == 0);  // it starts beside the dragon
    CHECK(max(csv["dragon_bunny_pairs"]) > 0);
    CHECK(csv["triangles"].front() > 12000);
}

TEST_CASE("creatures sample: a tentacle that touches another creature retracts", "[samples][gpu]") {
    const int frames = 12;
    const Scratch out = scratchFor("creatures");
    runSample(out, VKCOLLIDE_SAMPLE_CREATURES, "--creatures 2 --tentacles 10 --segments 6 --sides 6 --ships 1 --spacing 1.6", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(max(csv["tentacle_pairs"]) > 0);
    CHECK(max(csv["new_retractions"]) > 0);
    CHECK(max(csv["retracting"]) > 0);
    CHECK(min(csv["shortest_tentacle"]) < 0.9);  // and it did get shorter
}

TEST_CASE("deformable sample: two bodies collide and are pushed apart", "[samples][gpu]") {
    const int frames = 40;
    const Scratch out = scratchFor("deformable");
    runSample(out, VKCOLLIDE_SAMPLE_DEFORMABLE, "--bodies bunnies --bunny-triangles 500 --distance 0.9 --speed 3", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    const std::vector<double>& mutual = csv["mutual_pairs"];
    const std::vector<double>& distance = csv["centre_distance_01"];
    const auto first_contact = std::find_if(mutual.begin(), mutual.end(), [](double v) { return v > 0; }) - mutual.begin();
    REQUIRE(first_contact < frames);
    // After they touch, the centres move apart again.
    const double at_contact = distance[first_contact];
    CHECK(*std::max_element(distance.begin() + first_contact, distance.end()) > at_contact + 0.05);
}

TEST_CASE("samples: every scene runs under the peeling method and records the method it ran", "[samples][gpu]") {
    const struct {
        const char* name;
        const char* program;
        std::string args;
    } scenes[] = {
        {"cloth", VKCOLLIDE_SAMPLE_CLOTH, "--cells 12 --drop 0.05 --fold 0 --dt 0.01"},
        {"rigid", VKCOLLIDE_SAMPLE_RIGID_BUNNIES, "--bunnies 3 --columns 1 --bunny-triangles 300 --drop 0.05"},
        {"dragon", VKCOLLIDE_SAMPLE_DRAGON, "--triangles 12000 --passer-triangles 600"},
        {"creatures", VKCOLLIDE_SAMPLE_CREATURES, "--creatures 2 --tentacles 10 --segments 6 --sides 6 --ships 1 --spacing 1.6"},
        {"deformable", VKCOLLIDE_SAMPLE_DEFORMABLE, "--bodies bunnies --bunny-triangles 500 --distance 0.9 --speed 3"},
    };
    for (const auto& scene : scenes)
        for (const std::string& method : {std::string("peeling"), std::string("reliable")}) {
            INFO(scene.name << " --method " << method);
            const int frames = 3;
            const Scratch out = scratchFor(std::string(scene.name) + "-" + method);
            const std::string printed = runSample(out, scene.program, scene.args + " --method " + method, frames);
            const Csv csv = readCsv(out.dir / "frames.csv");
            REQUIRE(csv.rows == frames);
            for (const std::string& m : csv.text.at("method")) CHECK(m == method);
            CHECK(printed.find("Table 1 (" + method + " method") != std::string::npos);
        }
}

TEST_CASE("deformable sample: the peeling method finds the bodies' contact too", "[samples][gpu]") {
    const int frames = 40;
    const Scratch out = scratchFor("deformable-peeling");
    runSample(out, VKCOLLIDE_SAMPLE_DEFORMABLE,
              "--bodies bunnies --bunny-triangles 500 --distance 0.9 --speed 3 --method peeling --dual --backend compute", frames);
    const Csv csv = readCsv(out.dir / "frames.csv");
    REQUIRE(csv.rows == frames);
    CHECK(max(csv["mutual_pairs"]) > 0);
    CHECK(max(csv["peel_passes"]) > 0);
}

TEST_CASE("samples: an option of the peeling method is refused under the reliable method, naming its method", "[samples][gpu]") {
    const Scratch out = scratchFor("refused");
    for (const std::string& option : {std::string("--dual"), std::string("--layer-cap 4"), std::string("--backend raster"),
                                       std::string("--coverage dilate"), std::string("--axes 3")}) {
        for (const std::string& method : {std::string(), std::string(" --method reliable")}) {
            const Run run = start(out, VKCOLLIDE_SAMPLE_DEFORMABLE, "--bodies bunnies --bunny-triangles 200 " + option + method, 2);
            INFO(run.output);
            CHECK(run.status == 1);
            const std::string name = option.substr(0, option.find(' '));
            CHECK(run.output.find(name + " belongs to the peeling method (--method peeling); the reliable method does not read it") !=
                  std::string::npos);
            CHECK(!fs::exists(out.dir / "frames.csv"));  // refused before anything ran
        }
    }
    // The cloth's proximity pairs belong to the reliable method.
    const Run cloth = start(out, VKCOLLIDE_SAMPLE_CLOTH, "--cells 8 --proximity --method peeling", 2);
    INFO(cloth.output);
    CHECK(cloth.status == 1);
    CHECK(cloth.output.find("--proximity belongs to the reliable method (--method reliable, the default); the peeling method does not "
                            "read it") != std::string::npos);
    const Run ball = start(out, VKCOLLIDE_SAMPLE_CLOTH, "--cells 8 --ball --method peeling", 2);
    INFO(ball.output);
    CHECK(ball.status == 1);
    CHECK(ball.output.find("--ball belongs to the reliable method") != std::string::npos);
    CHECK(!fs::exists(out.dir / "frames.csv"));
    const Run unknown = start(out, VKCOLLIDE_SAMPLE_CLOTH, "--cells 8 --method cells", 2);
    CHECK(unknown.status != 0);
    CHECK(unknown.output.find("--method takes reliable or peeling") != std::string::npos);
}

TEST_CASE("samples: a resolution that is not a power of two fails under the peeling method with the API's message", "[samples][gpu]") {
    const Scratch out = scratchFor("resolution");
    const Run peeling =
        start(out, VKCOLLIDE_SAMPLE_DEFORMABLE, "--bodies bunnies --bunny-triangles 200 --method peeling --resolution 100", 2);
    INFO(peeling.output);
    CHECK(peeling.status == 1);
    CHECK(peeling.output.find("resolution 100 is not a power of two") != std::string::npos);
    // The reliable method takes any cell count, and runs at the one given.
    runSample(out, VKCOLLIDE_SAMPLE_DEFORMABLE, "--bodies bunnies --bunny-triangles 200 --resolution 100", 2);
    const Csv csv = readCsv(out.dir / "frames.csv");
    for (double r : csv["resolution"]) CHECK(r == 100);
}
