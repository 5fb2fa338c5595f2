// updateVertices through the world, split over several threads: a mesh
// of several chunks gives what a world built from the same positions gives (pairs read by
// the GPU from the upload buffer and by the narrow phase from the host copy; automatic
// settings measured lazily), a bad vertex in the last chunk is named, and a refused update
// changes nothing.
#include <algorithm>
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "api/vertex_scans.hpp"
#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/world_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

using test::mentions;

HostMesh sphere(float radius, std::uint32_t rings, float dx) {
    auto m = uvSphere(radius, 2 * rings, rings);
    REQUIRE(m);
    for (Float3& p : m->positions) p.x += dx;
    return std::move(*m);
}

// A big sphere (several chunks of the update's pass on four threads) and a small one
// through its surface.
struct Scene {
    HostMesh big = sphere(1.0f, 170, 0.0f), small = sphere(0.3f, 12, 1.0f);
};

// Both objects added to a world of four threads; ids 0 and 1. `open`: the big one open.
std::unique_ptr<CollisionWorld> worldOf(ValidatedContext& ctx, const HostMesh& big, const HostMesh& small, bool open = false) {
    auto w = makeWorld(ctx, {.threads = 4});
    REQUIRE(w->addMesh(big, {.name = "big", .open = open}));
    REQUIRE(w->addMesh(small, {.name = "small"}));
    return w;
}

void requireSameSettings(const DetectSettings& a, const DetectSettings& b) {
    CHECK(a.direction == b.direction);
    CHECK(a.resolution == b.resolution);
    CHECK(a.peeling.open_epsilon == b.peeling.open_epsilon);
}

// A sphere `a` beside a sphere `b` 1.2 to its right, moved left by offset(frame) before
// each of `frames` detections (updateVertices, detect() in one submission): each frame's
// automatic resolution, whether it submitted its command buffer again instead of recording
// it (HostStats::reused_submissions), and whether it found pairs.
struct MovedFrames {
    std::vector<std::uint32_t> resolution;
    std::vector<bool> reused, found;
};
MovedFrames detectMoved(int frames, const std::function<float(int)>& offset) {
    ValidatedContext ctx;
    const HostMesh a = sphere(1.0f, 40, 0.0f), b = sphere(1.0f, 40, 1.2f);
    auto world = makeWorld(ctx, {.threads = 2});
    auto ia = world->addMesh(a, {.name = "a"});
    REQUIRE(ia);
    REQUIRE(world->addMesh(b, {.name = "b"}));
    MovedFrames out;
    for (int frame = 0; frame < frames; ++frame) {
        const float dx = offset(frame);
        std::vector<Float3> moved = a.positions;
        for (Float3& p : moved) p.x -= dx;
        REQUIRE(world->updateVertices(*ia, moved));
        auto r = world->detect();
        REQUIRE(r);
        REQUIRE(r->stats.submissions == 1);
        out.resolution.push_back(r->stats.resolution);
        out.reused.push_back(r->stats.host.reused_submissions == 1);
        out.found.push_back(!r->pairs.empty());
    }
    return out;
}

}  // namespace

TEST_CASE("updateVertices over four threads gives what a world built from the same positions gives", "[api][gpu]") {
    ValidatedContext ctx;
    const Scene scene;
    REQUIRE(scene.big.positions.size() > 3 * vertex_scans::kMinChunkVertices);
    auto world = worldOf(ctx, scene.big, scene.small);
    REQUIRE(world->detect());
    // Squashed to half its height, twice as wide, and moved: other pairs, other edges,
    // another facing; the settings now come from the new shape.
    HostMesh moved = scene.big;
    for (Float3& p : moved.positions) p = {2.0f * p.x - 1.2f, 2.0f * p.y, 0.5f * p.z};
    REQUIRE(world->updateVertices(0, moved.positions));
    auto fresh = worldOf(ctx, moved, scene.small);
    for (const DetectSettings& s : {DetectSettings{}, DetectSettings{.method = DetectMethod::Peeling}}) {
        auto want = fresh->resolveSettings(s), got = world->resolveSettings(s);
        REQUIRE(want);
        REQUIRE(got);
        requireSameSettings(*got, *want);
        auto want_pairs = fresh->detect(s), got_pairs = world->detect(s);
        REQUIRE(want_pairs);
        REQUIRE(got_pairs);
        CHECK_FALSE(got_pairs->pairs.empty());
        CHECK(got_pairs->pairs == want_pairs->pairs);
        CHECK(got_pairs->stats.settings_note == want_pairs->stats.settings_note);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("updateVertices names a bad vertex in the last chunk, and a refused update changes nothing", "[api][gpu]") {
    ValidatedContext ctx;
    const Scene scene;
    auto world = worldOf(ctx, scene.big, scene.small);
    auto before = world->detect();
    REQUIRE(before);
    REQUIRE_FALSE(before->pairs.empty());
    auto before_settings = world->resolveSettings();
    REQUIRE(before_settings);

    // Moved apart (no pairs if any of it were taken), spoilt at the very end (the last
    // chunk): the first bad vertex is named, not the last.
    const std::size_t n = scene.big.positions.size();
    std::vector<Float3> apart = scene.big.positions;
    for (Float3& p : apart) p.x += 30;
    std::vector<Float3> bad = apart;
    bad[n - 1].z = std::numeric_limits<float>::quiet_NaN();
    bad[n - 2].x = std::numeric_limits<float>::infinity();
    auto nan = world->updateVertices(0, bad);
    REQUIRE_FALSE(nan);
    CHECK(nan.error().code() == ErrorCode::InvalidMesh);
    CHECK(nan.error().message() == "object 0 ('big'): vertex " + std::to_string(n - 2) + " is NaN or infinite");
    // Beyond the sampling range: refused after the whole pass wrote the upload buffer.
    std::vector<Float3> far = apart;
    far[n / 2].y = 3e30f;
    auto range = world->updateVertices(0, far);
    REQUIRE_FALSE(range);
    CHECK(range.error().code() == ErrorCode::LimitExceeded);
    CHECK(mentions(range.error(), "big"));

    // Nothing changed: the GPU's upload buffer, the narrow phase's host copy and the
    // automatic settings are as before.
    auto same_settings = world->resolveSettings();
    REQUIRE(same_settings);
    requireSameSettings(*same_settings, *before_settings);
    auto same = world->detect();
    REQUIRE(same);
    CHECK(same->pairs == before->pairs);
    CHECK(same->stats.settings_note == before->stats.settings_note);

    REQUIRE(world->updateVertices(0, apart));
    auto after = world->detect();
    REQUIRE(after);
    CHECK(after->pairs.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("shapes are measured when automatic settings need them, also after detections that did not", "[api][gpu]") {
    ValidatedContext ctx;
    const Scene scene;
    // Open: the open epsilon (peeling) uses its typical edge even when direction and
    // resolution are given.
    auto world = worldOf(ctx, scene.big, scene.small, true);
    REQUIRE(world->resolveSettings());  // both shapes measured
    // Both objects get finer (half the size, half the edges).
    HostMesh finer = scene.big, small = scene.small;
    for (HostMesh* m : {&finer, &small})
        for (Float3& p : m->positions) p = {0.5f * p.x, 0.5f * p.y, 0.5f * p.z};
    REQUIRE(world->updateVertices(0, finer.positions));
    REQUIRE(world->updateVertices(1, small.positions));
    auto fresh = worldOf(ctx, finer, small, true);

    DetectSettings given;  // nothing automatic: no shape is needed
    given.method = DetectMethod::Peeling;
    given.direction = std::array<float, 3>{0, 0, 1};
    given.resolution = 256;
    given.peeling.open_epsilon = 0.001f;
    REQUIRE(world->detect(given));
    DetectSettings open_auto = given;  // the open epsilon alone automatic
    open_auto.peeling.open_epsilon.reset();
    auto want = fresh->resolveSettings(open_auto), got = world->resolveSettings(open_auto);
    REQUIRE(want);
    REQUIRE(got);
    CHECK(*got->peeling.open_epsilon == *want->peeling.open_epsilon);
    CHECK(*got->peeling.open_epsilon > 0);
    // Everything automatic (the closed object's shape too, which the open epsilon did not
    // need): the same as a world that saw these positions from the start.
    for (const DetectSettings& s : {DetectSettings{}, DetectSettings{.method = DetectMethod::Peeling}}) {
        auto w = fresh->resolveSettings(s), g = world->resolveSettings(s);
        REQUIRE(w);
        REQUIRE(g);
        requireSameSettings(*g, *w);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("shapes measured with the vertex update (automatic settings last time) equal shapes measured later", "[api][gpu]") {
    ValidatedContext ctx;
    const Scene scene;
    auto eager = worldOf(ctx, scene.big, scene.small, true);
    auto lazy = worldOf(ctx, scene.big, scene.small, true);
    REQUIRE(eager->resolveSettings());  // automatic: the next updates measure on the way
    DetectSettings given;               // nothing automatic: the next updates leave shapes stale
    given.direction = std::array<float, 3>{0, 0, 1};
    given.resolution = 64;
    given.peeling.open_epsilon = 0.001f;
    REQUIRE(lazy->resolveSettings(given));
    // Stretched along x and squashed along z: another typical edge and facing.
    HostMesh big = scene.big, small = scene.small;
    for (HostMesh* m : {&big, &small})
        for (Float3& p : m->positions) p = {1.7f * p.x, p.y, 0.4f * p.z};
    for (auto* w : {eager.get(), lazy.get()}) {
        REQUIRE(w->updateVertices(0, big.positions));
        REQUIRE(w->updateVertices(1, small.positions));
    }
    for (const DetectSettings& s : {DetectSettings{}, DetectSettings{.method = DetectMethod::Peeling}}) {
        auto a = eager->detect(s), b = lazy->detect(s);
        REQUIRE(a);
        REQUIRE(b);
        CHECK(a->stats.settings_note == b->stats.settings_note);
        CHECK(a->stats.resolution == b->stats.resolution);
        CHECK(a->pairs == b->pairs);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// A deforming scene's automatic resolution follows its extent, moving by a cell or so
// between frames. Once the scene was larger (the per-cell buffers grew then and are kept),
// the cell stage still clears and scans the same cells while this run's rounded count stays
// within a band of what the buffers hold (CellStage::recordedCells), not its exact count,
// so frames a cell apart mostly record the same commands and submit the command buffer
// again instead of recording it (HostStats::reused_submissions).
TEST_CASE("a drifting resolution keeps the command buffer", "[api][gpu]") {
    // First far from b (a wide scene: the buffers grow), then through it, moving back and
    // forth by 1 % of the scene's width: the resolution moves by a cell or so.
    const MovedFrames m = detectMoved(14, [](int frame) { return frame == 0 ? 1.5f : 0.016f * float(frame % 3); });
    const std::vector<std::uint32_t>& resolution = m.resolution;
    const std::vector<bool>& reused = m.reused;
    CAPTURE(resolution, reused);
    for (std::size_t f = 1; f < m.found.size(); ++f) REQUIRE(m.found[f]);
    // After the first three frames (the first detections record): frames whose resolution
    // moved from the last frame's, mostly submitted again.
    std::size_t moved = 0, moved_reused = 0;
    for (std::size_t f = 4; f < resolution.size(); ++f)
        if (resolution[f] != resolution[f - 1]) ++moved, moved_reused += reused[f];
    REQUIRE(moved >= 4);  // the resolution did move
    CHECK(moved_reused * 2 >= moved);
}

TEST_CASE("a resolution swinging by half its cells keeps the command buffer", "[api][gpu]") {
    // a moves away from b and back, a quarter of its radius a frame: the scene's width, and
    // with it the resolution, swings by about a quarter (the cells by half). Once the widest
    // frame has sized the buffers, every frame records the same commands (the clear and the
    // scan cover every cell the buffers hold: CellStage::recordedCells).
    const MovedFrames m = detectMoved(12, [](int frame) { return 0.25f * float(frame % 4); });
    const std::vector<std::uint32_t>& resolution = m.resolution;
    const std::vector<bool>& reused = m.reused;
    CAPTURE(resolution, reused);
    for (const bool found : m.found) REQUIRE(found);
    const auto [lowest, highest] = std::minmax_element(resolution.begin(), resolution.end());
    REQUIRE(double(*highest) >= 1.15 * double(*lowest));  // the resolution did swing
    for (std::size_t f = 5; f < resolution.size(); ++f) {
        INFO("frame " << f);
        CHECK(reused[f]);
    }
}

TEST_CASE("a resolution swinging far below what the buffers hold keeps the command buffer", "[api][gpu]") {
    // Frame 0 far wider (a far from b: the per-cell buffers grow to over four times what any
    // later frame needs, as after the grid tuner's trials at a finer grid), then the swing
    // of the test above. The clear and the scan then cover the most cells of the recent
    // runs within the band (CellStage::recordedCells), the same on every frame of the
    // swing, so once the swing's widest frame has run, every frame is submitted again.
    const MovedFrames m = detectMoved(12, [](int frame) { return frame == 0 ? 6.0f : 0.25f * float(frame % 4); });
    const std::vector<std::uint32_t>& resolution = m.resolution;
    const std::vector<bool>& reused = m.reused;
    CAPTURE(resolution, reused);
    for (std::size_t f = 1; f < m.found.size(); ++f) REQUIRE(m.found[f]);
    const auto [lowest, highest] = std::minmax_element(resolution.begin() + 1, resolution.end());
    REQUIRE(double(*highest) >= 1.15 * double(*lowest));                // the swing
    REQUIRE(double(resolution[0]) >= 2.2 * double(*highest));            // over 4.8 times the cells
    for (std::size_t f = 6; f < resolution.size(); ++f) {
        INFO("frame " << f);
        CHECK(reused[f]);
    }
}
