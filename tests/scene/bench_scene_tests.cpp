// The benchmark scene set (tools/bench/bench_scenes.hpp) at a small scale: every generated
// scene builds, keeps its objects and topology from frame to frame, has exact pairs in at
// least one frame, and is marked tuning or held-out with both sets present; the reference
// cache hands back exactly what it stored and misses when the scene changes.
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>

#include "bench_scenes.hpp"
#include "reference_cache.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {

// Scenes that read packaged meshes (tools/fetch_cgal_data.sh), not available to CI.
bool needsData(const std::string& name) {
    return name.find("bunn") != std::string::npos || name == "pile-cgal" || name == "deep-bunny-elephant" ||
           name == "deform-armadillo-bunny";
}

}  // namespace

TEST_CASE("bench scenes build at small scale with constant topology and exact pairs", "[scene][bench]") {
    const std::vector<SceneSpec> all = allScenes("", 0.01);
    std::set<std::string> names;
    std::size_t tuning = 0, held_out = 0;
    for (const SceneSpec& s : all) {
        INFO(s.name);
        CHECK(names.insert(s.name).second);  // unique names
        (s.set == SceneSet::Tuning ? tuning : held_out) += 1;
        CHECK((s.motion == Motion::Rigid) == (s.frames == 1));
        if (needsData(s.name)) continue;
        std::vector<BenchObject> first;
        std::size_t pairs = 0;
        for (int f = 0; f < s.frames; ++f) {
            auto objects = s.build(f);
            REQUIRE(objects);
            for (const BenchObject& o : *objects) REQUIRE(validateMesh(o.mesh));
            if (f == 0) first = *objects;
            REQUIRE(objects->size() == first.size());
            for (std::size_t k = 0; k < first.size(); ++k) {
                CHECK((*objects)[k].mesh.indices == first[k].mesh.indices);
                CHECK((*objects)[k].gpu == first[k].gpu);
            }
            auto ref = referenceFor(*objects, "", 2);
            REQUIRE(ref);
            pairs += ref->pairs.size();
        }
        CHECK(pairs > 0);
    }
    CHECK(tuning >= 8);
    CHECK(held_out >= 8);
}

TEST_CASE("reference cache: a stored frame reads back identical and a changed scene misses", "[scene][bench]") {
    const std::string dir = (std::filesystem::temp_directory_path() / "vkcollide_ref_cache_test").string();
    std::filesystem::remove_all(dir);
    const auto specs = allScenes("", 0.01);
    const auto stack = std::find_if(specs.begin(), specs.end(), [](const SceneSpec& s) { return s.name == "stack-touching"; });
    REQUIRE(stack != specs.end());
    auto objects = stack->build(0);
    REQUIRE(objects);
    auto computed = referenceFor(*objects, dir, 2);
    REQUIRE(computed);
    CHECK_FALSE(computed->from_cache);
    CHECK(computed->crossingCount() > 0);
    CHECK(computed->crossingCount() < computed->pairs.size());  // touching pairs too
    auto cached = referenceFor(*objects, dir, 2);
    REQUIRE(cached);
    CHECK(cached->from_cache);
    CHECK(cached->pairs == computed->pairs);
    CHECK(cached->crossing == computed->crossing);
    (*objects)[0].mesh.positions[0].x += 0.25f;
    CHECK(hashObjects(*objects) != computed->hash);
    auto changed = referenceFor(*objects, dir, 2);
    REQUIRE(changed);
    CHECK_FALSE(changed->from_cache);
    std::filesystem::remove_all(dir);
}
