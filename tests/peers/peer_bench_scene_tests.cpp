// vkcollide_peer_bench on the user's own files (--scene, --sequence): every peer, vkcollide
// included, runs on them and is measured against the exact reference; bad files and
// frames that change topology are named.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

namespace fs = std::filesystem;
using namespace vkcollide;

namespace {

struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("vkcollide-peer-bench-" + std::to_string(::getpid()));
    Scratch() { fs::create_directories(dir); }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::string sphere(const std::string& file, float x) const {
        auto m = icosphere(1.0f, 2);
        REQUIRE(m);
        REQUIRE(transformMesh(*m, Transform3x4{1, 0, 0, x, 0, 1, 0, 0.1f, 0, 0, 1, 0.05f}));
        const fs::path p = dir / file;
        std::ofstream(p) << writeOff(*m);
        return p.string();
    }
};

struct Run {
    int status = 0;
    std::string err;
    std::vector<std::map<std::string, std::string>> rows;  // the CSV, by column name
};

Run bench(const Scratch& s, const std::string& args) {
    const fs::path csv = s.dir / "bench.csv", err = s.dir / "err.txt";
    fs::remove(csv);
    const std::string cmd = std::string(VKCOLLIDE_PEER_BENCH_PATH) + " " + args + " --threads 2 --csv " + csv.string() + " > /dev/null 2> " + err.string();
    UNSCOPED_INFO(cmd);
    const int status = std::system(cmd.c_str());
    Run r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::stringstream e;
    e << std::ifstream(err).rdbuf();
    r.err = e.str();
    UNSCOPED_INFO(r.err);
    std::ifstream in(csv);
    std::vector<std::string> names;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
        if (names.empty()) {
            names = cells;
            continue;
        }
        std::map<std::string, std::string> m;
        for (std::size_t i = 0; i < names.size() && i < cells.size(); ++i) m[names[i]] = cells[i];
        r.rows.push_back(m);
    }
    return r;
}

}  // namespace

TEST_CASE("peer bench: --scene runs every peer, vkcollide too, on the user's files", "[peers][gpu]") {
    Scratch s;
    const std::string files = s.sphere("a.off", 0) + "," + s.sphere("b.off", 1.2f);
    const Run r = bench(s, "--scene " + files + " --frames 1");
    REQUIRE(r.status == 0);
    std::map<std::string, int> per_peer;
    for (const auto& row : r.rows) {
        INFO(row.at("peer") << " " << row.at("mode"));
        CHECK(row.at("scene") == "a+b");
        CHECK(row.at("triangles") == "640");
        CHECK(row.at("objects") == "2");
        CHECK(std::stod(row.at("reference_pairs")) > 0);
        CHECK(std::stod(row.at("precision")) == 1.0);
        // The CPU peers are exact; vkcollide samples (its recall is measured, not assumed).
        if (row.at("peer") != "vkcollide") CHECK(std::stod(row.at("recall")) == 1.0);
        else CHECK(std::stod(row.at("recall")) > 0.5);
        ++per_peer[row.at("peer")];
    }
    CHECK(per_peer["vkcollide"] == 2);  // self and between
    CHECK(per_peer["cgal"] == 2);
    CHECK(per_peer["embree"] == 2);
    CHECK(per_peer["fcl-aabb"] == 1);  // FCL cannot test within objects
}

TEST_CASE("peer bench: --sequence runs each frame of the user's files", "[peers][gpu]") {
    Scratch s;
    std::string files;
    for (int f = 0; f < 3; ++f)
        files += (f ? "," : "") + s.sphere("a" + std::to_string(f) + ".off", 0) + "," + s.sphere("b" + std::to_string(f) + ".off", 2.4f - 0.5f * float(f));
    const Run r = bench(s, "--sequence --frame-files 2 --scene " + files + " --peers cgal,vkcollide --modes between");
    REQUIRE(r.status == 0);
    REQUIRE(r.rows.size() == 6);  // 3 frames x 2 peers
    for (const auto& row : r.rows) {
        CHECK(row.at("scene") == "a0+b0-sequence");
        CHECK(row.at("mode") == "deforming-between");
    }
    CHECK(r.rows[0].at("reference_pairs") == "0");  // frame 0: apart
    CHECK(std::stod(r.rows[2].at("reference_pairs")) > 0);

    const std::string other = s.sphere("c.off", 0);
    auto bigger = icosphere(1.0f, 3);  // another topology
    REQUIRE(bigger);
    std::ofstream(s.dir / "big.off") << writeOff(*bigger);
    const Run bad = bench(s, "--sequence --scene " + other + "," + (s.dir / "big.off").string() + " --peers cgal");
    CHECK(bad.status == 1);
    CHECK(bad.err.find("--sequence: frame 1 (" + (s.dir / "big.off").string() + ") does not have frame 0's topology") != std::string::npos);
    const Run missing = bench(s, "--scene " + other + "," + (s.dir / "gone.off").string());
    CHECK(missing.status == 1);
    CHECK(missing.err.find("gone.off") != std::string::npos);
    const Run odd = bench(s, "--sequence --frame-files 2 --scene " + other + "," + other + "," + other);
    CHECK(odd.status == 2);
    CHECK(odd.err.find("do not make two or more whole frames of 2") != std::string::npos);
}

TEST_CASE("peer bench: --scene FILE:x,y,z moves a file's objects, named and set as vkcollide_bench --mesh", "[peers][gpu]") {
    Scratch s;
    // b is made 30 away from a; its offset brings it back to 1.2 from a (as in the first case).
    const std::string a = s.sphere("a.off", 0), b = s.sphere("b.off", 30);
    const Run moved = bench(s, "--scene " + a + "," + b + ":-28.8,0,0 --peers cgal --modes between --frames 1");
    REQUIRE(moved.status == 0);
    REQUIRE(moved.rows.size() == 1);
    CHECK(moved.rows[0].at("scene") == "a+b");  // frontier.sh puts it beside vkcollide_bench's a+b
    CHECK(moved.rows[0].at("set") == "user");
    CHECK(std::stod(moved.rows[0].at("reference_pairs")) > 0);
    const Run apart = bench(s, "--scene " + a + "," + b + " --peers cgal --modes between --frames 1");
    REQUIRE(apart.status == 0);
    REQUIRE(apart.rows.size() == 1);
    CHECK(apart.rows[0].at("reference_pairs") == "0");
}
