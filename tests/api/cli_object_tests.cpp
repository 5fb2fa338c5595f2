// `vkcollide detect`: every ObjectOptions field per file (--name, --open, --self, the
// transforms, --gpu-mesh, --edge-length). Pairs are checked against the exact reference on
// the scene as the options make it: never a pair the reference lacks, and most of its pairs.
#include <catch2/catch.hpp>

#include <algorithm>

#include "api/cli_support.hpp"
#include "vkcollide/scene.hpp"

using namespace clitest;
using vkcollide::HostMesh;
using vkcollide::TrianglePair;

namespace {

// Found pairs against the exact ones: precision 1 (the narrow phase is exact) and a recall
// the resolution reaches on these small scenes.
void checkAgainst(const std::vector<TrianglePair>& found, const std::vector<TrianglePair>& exact) {
    REQUIRE(std::is_sorted(found.begin(), found.end()));
    std::size_t hits = 0;
    for (const TrianglePair& p : found) {
        const bool known = std::binary_search(exact.begin(), exact.end(), p);
        CHECK(known);
        hits += known;
    }
    CHECK(double(hits) >= 0.9 * double(exact.size()));
}

HostMesh moved(HostMesh m, const vkcollide::Transform3x4& t) {
    REQUIRE(vkcollide::transformMesh(m, t));
    return m;
}

std::vector<float> transformOf(const Json& object) {
    std::vector<float> out;
    for (const Json& v : object["transform"].array()) out.push_back(static_cast<float>(v.number()));
    return out;
}

}  // namespace

TEST_CASE("vkcollide detect: --name names a file's objects", "[cli][gpu]") {
    Scratch s("names");
    const std::string a = writeMesh(s, "a.off", sphere("a", {0, 0, 0}));
    const std::string pair = writeMeshes(s, "pair.obj", {sphere("left", {1.2f, 0, 0}), sphere("right", {2.4f, 0, 0})});
    const Json plain = detectJson(s, a + " " + pair);
    CHECK(plain["objects"][0]["name"].string() == "a");
    CHECK(plain["objects"][1]["name"].string() == "left");
    const Json named = detectJson(s, a + " " + pair + " --name 1:ball --name 2:twins");
    CHECK(named["objects"][0]["name"].string() == "ball");
    CHECK(named["objects"][1]["name"].string() == "twins/left");
    CHECK(named["objects"][2]["name"].string() == "twins/right");
    CHECK(named["objects"][2]["file"].number() == 2);
    CHECK(named["frames"][0]["stats"]["objects"][0].string() == "ball");
}

TEST_CASE("vkcollide detect: --open marks the files' objects open", "[cli][gpu]") {
    Scratch s("open");
    const std::string files = writeMesh(s, "a.off", sphere("a", {0, 0, 0})) + " " + writeMesh(s, "b.off", sphere("b", {1.2f, 0.1f, 0}));
    // (The open epsilon is the peeling method's.)
    const Json closed = detectJson(s, files + " --method peeling");
    CHECK_FALSE(closed["objects"][1]["open"].boolean());
    CHECK(closed["settings"]["used"]["open_epsilon"].number() == 0);
    const Json open = detectJson(s, files + " --method peeling --open 2");
    CHECK_FALSE(open["objects"][0]["open"].boolean());
    CHECK(open["objects"][1]["open"].boolean());
    CHECK(open["settings"]["used"]["open_epsilon"].number() > 0);
    const Json both = detectJson(s, files + " --open 1 --open 2");  // lists add up
    CHECK(both["objects"][0]["open"].boolean());
    CHECK(both["objects"][1]["open"].boolean());
}

TEST_CASE("vkcollide detect: self-collision is off unless --self lists the file, as in the API", "[cli][gpu]") {
    Scratch s("self");
    // File 1: one object made of two crossing spheres (it intersects itself); file 2: a
    // sphere that touches nothing.
    HostMesh knot = sphere("knot", {0, 0, 0});
    vkcollide::HostMesh second = sphere("x", {0.9f, 0.2f, 0});
    const auto base = static_cast<std::uint32_t>(knot.positions.size());
    knot.positions.insert(knot.positions.end(), second.positions.begin(), second.positions.end());
    for (std::uint32_t i : second.indices) knot.indices.push_back(base + i);
    const HostMesh lone = sphere("lone", {5, 0, 0});
    const std::string files = writeMesh(s, "knot.off", knot) + " " + writeMesh(s, "lone.off", lone);
    const std::vector<HostMesh> world{knot, lone};

    // The default: ObjectOptions::self_collision's (off), and the summary says so.
    Run run;
    const Json plain = detectJson(s, files + " --resolution 128", run);
    CHECK_FALSE(plain["objects"][0]["self_collision"].boolean());
    CHECK_FALSE(plain["objects"][1]["self_collision"].boolean());
    CHECK(plain["frames"][0]["pairs"].size() == 0);
    CHECK(run.out.find("2 objects, 960 triangles, self-collision off (--self FILES turns it on)") != std::string::npos);

    const Json all = detectJson(s, files + " --resolution 128 --self all", run);
    CHECK(all["objects"][0]["self_collision"].boolean());
    CHECK(all["objects"][1]["self_collision"].boolean());
    CHECK(run.out.find("self-collision on for every object") != std::string::npos);
    const auto self_pairs = jsonPairs(all["frames"][0]);
    REQUIRE_FALSE(self_pairs.empty());
    checkAgainst(self_pairs, referencePairs(world, {true, true}));

    for (const char* off : {" --self none", " --no-self-collision", " --self 2"}) {
        INFO(off);
        const Json j = detectJson(s, files + " --resolution 128" + off);
        CHECK_FALSE(j["objects"][0]["self_collision"].boolean());
        CHECK(j["objects"][1]["self_collision"].boolean() == (std::string(off) == " --self 2"));
        CHECK(j["frames"][0]["pairs"].size() == 0);
    }
    const Json listed = detectJson(s, files + " --resolution 128 --self 1");
    CHECK(jsonPairs(listed["frames"][0]) == self_pairs);
}

TEST_CASE("vkcollide detect: per-file transforms compose in order and place the objects", "[cli][gpu]") {
    Scratch s("transforms");
    const HostMesh unit = sphere("s", {0, 0, 0});
    const std::string files = writeMesh(s, "a.off", unit) + " " + writeMesh(s, "b.off", unit);

    SECTION("--scale then --translate, and the other order") {
        const Json j = detectJson(s, files + " --scale 2:2 --translate 2:1,0,0");
        CHECK(transformOf(j["objects"][1]) == std::vector<float>{2, 0, 0, 1, 0, 2, 0, 0, 0, 0, 2, 0});
        CHECK(transformOf(j["objects"][0]) == std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
        const Json k = detectJson(s, files + " --translate 2:1,0,0 --scale 2:2");
        CHECK(transformOf(k["objects"][1]) == std::vector<float>{2, 0, 0, 2, 0, 2, 0, 0, 0, 0, 2, 0});
        const Json l = detectJson(s, files + " --scale 2:1,2,3");
        CHECK(transformOf(l["objects"][1]) == std::vector<float>{1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0});
    }
    SECTION("--translate finds the pairs of the moved object") {
        const vkcollide::Transform3x4 t{1, 0, 0, 1.2f, 0, 1, 0, 0.1f, 0, 0, 1, 0.05f};
        const Json j = detectJson(s, files + " --translate 2:1.2,0.1,0.05 --resolution 128");
        checkAgainst(jsonPairs(j["frames"][0]), referencePairs({unit, moved(unit, t)}, {true, true}));
        REQUIRE(j["frames"][0]["pairs"].size() > 0);
    }
    SECTION("--rotate turns about the axis through the origin") {
        const Json j = detectJson(s, files + " --rotate 2:0,0,1,90 --translate 2:1.2,0,0 --resolution 128");
        const std::vector<float> m = transformOf(j["objects"][1]);
        const std::vector<float> want{0, -1, 0, 1.2f, 1, 0, 0, 0, 0, 0, 1, 0};
        for (std::size_t i = 0; i < 12; ++i) CHECK(m[i] == Approx(want[i]).margin(1e-6));
        vkcollide::Transform3x4 t{};
        std::copy(m.begin(), m.end(), t.begin());
        checkAgainst(jsonPairs(j["frames"][0]), referencePairs({unit, moved(unit, t)}, {true, true}));
    }
    SECTION("--transform takes the 12 numbers as given") {
        const Json j = detectJson(s, files + " --method peeling --transform 2:0.25,0,0,0.1,0,0.25,0,0,0,0,0.25,0");
        CHECK(transformOf(j["objects"][1]) == std::vector<float>{0.25f, 0, 0, 0.1f, 0, 0.25f, 0, 0, 0, 0, 0.25f, 0});
        // A small sphere inside the big one: no surfaces meet.
        CHECK(j["frames"][0]["pairs"].size() == 0);
        CHECK(j["frames"][0]["stats"]["collision_rays"].number() > 0);  // the peeling rays see it inside
    }
    SECTION("all: applies to every file") {
        const Json j = detectJson(s, files + " --translate all:0,0,5");
        CHECK(transformOf(j["objects"][0])[11] == 5);
        CHECK(transformOf(j["objects"][1])[11] == 5);
    }
}

TEST_CASE("vkcollide detect: --gpu-mesh adds engine buffers and finds the same pairs", "[cli][gpu]") {
    Scratch s("gpu");
    const std::string files = writeMesh(s, "a.off", sphere("a", {0, 0, 0})) + " " + writeMesh(s, "b.off", sphere("b", {1.2f, 0.1f, 0.05f}));
    const Json host = detectJson(s, files + " --resolution 128");
    Run run;
    const Json gpu = detectJson(s, files + " --resolution 128 --gpu-mesh 2", run);
    CHECK_FALSE(gpu["objects"][0]["gpu_mesh"].boolean());
    CHECK(gpu["objects"][1]["gpu_mesh"].boolean());
    REQUIRE(host["frames"][0]["pairs"].size() > 0);
    CHECK(jsonPairs(gpu["frames"][0]) == jsonPairs(host["frames"][0]));
    const Json all = detectJson(s, files + " --resolution 128 --gpu-mesh all");
    CHECK(jsonPairs(all["frames"][0]) == jsonPairs(host["frames"][0]));
}

TEST_CASE("vkcollide detect: --edge-length steers the automatic resolution of a --gpu-mesh", "[cli][gpu]") {
    Scratch s("edge");
    // A host slab of a few large triangles, and a sphere added as an engine mesh: the
    // resolution follows the typical edge over both, the engine mesh's only when declared.
    auto slab = vkcollide::box({10, 10, 0.1f}, 1);
    REQUIRE(slab);
    slab->name = "slab";
    const std::string files = writeMesh(s, "slab.off", *slab) + " " + writeMesh(s, "b.off", sphere("b", {0, 0, 1.05f}));
    const Json unknown = detectJson(s, files + " --gpu-mesh 2");
    const Json fine = detectJson(s, files + " --gpu-mesh 2 --edge-length 2:0.005");
    CHECK(unknown["objects"][1]["typical_edge_length"].number() == 0);
    CHECK(fine["objects"][1]["typical_edge_length"].number() == Approx(0.005));
    CHECK(fine["settings"]["used"]["resolution"].number() > unknown["settings"]["used"]["resolution"].number());
    CHECK(fine["frames"][0]["stats"]["settings_note"].string().find("typical edge") != std::string::npos);
}

TEST_CASE("vkcollide detect: a closed file that is inside out or holed gets a warning, an open one none", "[cli][gpu]") {
    Scratch s("warnings");
    HostMesh flipped = sphere("flipped", {0, 0, 0});
    for (std::size_t t = 0; t + 2 < flipped.indices.size(); t += 3) std::swap(flipped.indices[t + 1], flipped.indices[t + 2]);
    HostMesh holed = sphere("holed", {1.2f, 0, 0});
    holed.indices.resize(holed.indices.size() - 3);
    const std::string files = writeMesh(s, "good.off", sphere("good", {0, 2.5f, 0})) + " " + writeMesh(s, "flipped.off", flipped) + " " +
                              writeMesh(s, "holed.off", holed);
    Run run;
    const Json j = detectJson(s, files, run);
    const Json& warnings = j["frames"][0]["stats"]["mesh_warnings"];
    REQUIRE(warnings.size() == 2);
    CHECK(warnings[0]["object"].number() == 1);
    CHECK(warnings[0]["inside_out"].boolean());
    CHECK(warnings[1]["object"].number() == 2);
    CHECK(warnings[1]["boundary_edges"].number() == 3);
    CHECK(run.err.find("vkcollide: warning: frame 0: object 1 ('flipped'): declared closed but inside out") != std::string::npos);
    CHECK(run.err.find("vkcollide: warning: frame 0: object 2 ('holed'): declared closed but has 3 boundary edges") != std::string::npos);
    // Declared open: no inside to get wrong.
    const Json open = detectJson(s, files + " --open 2,3", run);
    CHECK(open["frames"][0]["stats"]["mesh_warnings"].size() == 0);
    CHECK(run.err.find("warning") == std::string::npos);
}
