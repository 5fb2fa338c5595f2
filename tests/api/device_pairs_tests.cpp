// Results on the GPU (DetectSettings::reliable.device_pairs, docs/api.md): the pairs the detection
// leaves in device buffers, copied back here as an engine would read them, equal
// DetectResult::pairs exactly (content and order), and with device_responses the responses
// DetectResult::responses to the bit, on the test scenes, the stability cases,
// a resting stack, many objects, self-collision, a pair filter, a run whose survivors
// overflowed (Incomplete at the signal, final after collect) and pipelined slots; a short
// capacity says so; bad settings are refused by name. Validation layer on.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "support/device_copy.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scene_world.hpp"
#include "support/stability_scenes.hpp"
#include "support/test_scenes.hpp"
#include "vk/device.hpp"
#include "vk/resources.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

struct DeviceCopy {
    DevicePairsHeader header;
    std::vector<TrianglePair> pairs;  // the first header.count records
    std::vector<TriangleResponse> responses;  // the first header.responses records (device_responses)
};

// The header, the pairs and the responses as the engine would read them.
DeviceCopy readBack(vk::Device& dev, const DevicePairs& d) {
    std::vector<BufferRead> reads = {{d.header, sizeof(DevicePairsHeader)}, {d.pairs, VkDeviceSize(d.capacity) * sizeof(TrianglePair)}};
    if (d.responses) reads.push_back({d.responses, VkDeviceSize(d.response_capacity) * sizeof(TriangleResponse)});
    const auto bytes = copyToHost(dev, reads);
    DeviceCopy out;
    std::memcpy(&out.header, bytes[0].data(), sizeof out.header);
    const std::uint32_t n = std::min(out.header.count, d.capacity);
    out.pairs.resize(n);
    if (n) std::memcpy(out.pairs.data(), bytes[1].data(), std::size_t{n} * sizeof(TrianglePair));
    if (d.responses) {
        const std::uint32_t m = std::min(out.header.responses, d.response_capacity);
        out.responses.resize(m);
        if (m) std::memcpy(out.responses.data(), bytes[2].data(), std::size_t{m} * sizeof(TriangleResponse));
    }
    return out;
}

// Byte for byte: a direction's -0 is not +0.
bool sameBits(const TriangleResponse& a, const TriangleResponse& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The device's responses are the host's, to the bit, in order.
void requireSameResponses(const DeviceCopy& d, const DetectResult& r) {
    CHECK(d.header.response_capacity == r.device->response_capacity);
    REQUIRE(d.responses.size() == r.responses.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < r.responses.size(); ++k) {
        if (sameBits(d.responses[k], r.responses[k])) continue;
        if (++differ > 5) continue;
        const TriangleResponse &g = d.responses[k], &h = r.responses[k];
        UNSCOPED_INFO("response " << k << ": GPU object " << g.object << " triangle " << g.triangle << " partners " << g.partner_count
                                  << " (" << g.direction.x << ", " << g.direction.y << ", " << g.direction.z << "), host object "
                                  << h.object << " triangle " << h.triangle << " partners " << h.partner_count << " (" << h.direction.x
                                  << ", " << h.direction.y << ", " << h.direction.z << ")");
    }
    CHECK(differ == 0);
}

// The device's pairs are the host's, in order, complete (and its responses, where asked).
void requireSame(vk::Device& dev, const DetectResult& r, const std::string& what) {
    INFO(what << ": " << r.pairs.size() << " pairs on the host");
    REQUIRE(r.device);
    const DeviceCopy d = readBack(dev, *r.device);
    CHECK(d.header.flags == 0);
    CHECK(d.header.capacity == r.device->capacity);
    CHECK(d.header.needed == r.pairs.size());
    CHECK(d.header.count == r.pairs.size());
    CHECK(d.pairs == r.pairs);
    if (r.device->responses) {
        requireSameResponses(d, r);
        CHECK(r.stats.reliable.device_responses_written == r.responses.size());
    } else {
        CHECK(d.header.responses == 0);
        CHECK(d.header.response_capacity == 0);
    }
}

// Boxes resting face to face (coplanar, exact in float) in a 3 x 2 x 3 stack: touching
// contacts only.
TestScene restingStack() {
    TestScene s{"resting stack", {}};
    for (int k = 0; k < 18; ++k) {
        auto b = box({0.5f, 0.5f, 0.5f}, 2);
        REQUIRE(b);
        const Transform3x4 at{1, 0, 0, float(k % 3), 0, 1, 0, float((k / 3) % 2), 0, 0, 1, float(k / 6)};
        s.objects.push_back({std::move(*b), {.name = "box" + std::to_string(k), .transform = at}});
    }
    return s;
}

// 64 small spheres on a jittered grid, neighbours overlapping.
TestScene manySpheres() {
    TestScene s{"many objects", {}};
    for (int k = 0; k < 64; ++k) {
        auto m = uvSphere(0.3f + 0.01f * float(k % 5), 10, 6);
        REQUIRE(m);
        const float x = 0.5f * float(k % 8) + 0.03f * float(k % 3), y = 0.5f * float(k / 8), z = 0.05f * float(k % 4);
        s.objects.push_back({std::move(*m), {.name = "s" + std::to_string(k), .transform = {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z}}});
    }
    return s;
}

// Three copies of one fine grid in one plane: far more pairs than the first run's survivor
// capacity (triangles / 2, at least 4096), so the cell stage reruns after the signal.
TestScene coincidentGrids() {
    auto s = test::coincidentGrids(40);
    REQUIRE(s);
    return std::move(*s);
}


}  // namespace

TEST_CASE("device pairs: the GPU's sorted pairs equal DetectResult::pairs on every scene", "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64: device_pairs is refused (tested below)");
        return;
    }
    DetectSettings on;
    on.reliable.device_pairs = true;
    on.reliable.device_responses = true;
    std::vector<TestScene> scenes;
    auto all = allTestScenes();
    REQUIRE(all);
    for (TestScene& s : *all) scenes.push_back(std::move(s));
    scenes.push_back(restingStack());
    scenes.push_back(manySpheres());
    for (const TestScene& scene : scenes) {
        auto world = sceneWorld(ctx, scene);
        auto r = world->detect(on);
        REQUIRE(r);
        CHECK(r->pairs.size() > 0);
        requireSame(ctx.device(), *r, scene.name);
        auto last = world->devicePairs();
        REQUIRE(last);
        CHECK(last->pairs == r->device->pairs);
        CHECK(r->stats.reliable.sorting_ms >= 0);
        // Ids as the API returns them: remove the first object, so ids no longer equal indices.
        if (scene.objects.size() < 3) continue;
        REQUIRE(world->removeObject(0));
        auto again = world->detect(on);
        REQUIRE(again);
        requireSame(ctx.device(), *again, scene.name + " without object 0");
    }
    auto cases = allStabilityCases();
    REQUIRE(cases);
    for (const StabilityCase& c : *cases) {
        auto world = sceneWorld(ctx, c.scene);
        DetectSettings s = on;
        s.region = c.settings.region;
        auto r = world->detect(s);
        REQUIRE(r);
        requireSame(ctx.device(), *r, c.name);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("device pairs: pair filter, the final run after an overflow, pipelined slots", "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    DetectSettings on;
    on.reliable.device_pairs = true;
    on.reliable.device_responses = true;  // their passes rerun with the sort's
    {
        const TestScene scene = manySpheres();
        auto world = sceneWorld(ctx, scene);
        REQUIRE(world->setPairFilter([](ObjectId a, ObjectId b) { return (a + b) % 3 != 0; }));
        auto r = world->detect(on);
        REQUIRE(r);
        requireSame(ctx.device(), *r, "many objects, filtered");
    }
    {
        // The first run's survivors overflow: at the signal the header says Incomplete;
        // collect() reruns the stage and sorts again, so the buffers hold the final pairs.
        const TestScene scene = coincidentGrids();
        auto world = sceneWorld(ctx, scene);
        REQUIRE(world->submit(on));
        auto early = world->devicePairs();
        REQUIRE(early);
        auto r = world->collect();
        REQUIRE(r);
        CHECK(r->stats.cells.runs > 1);
        CHECK(r->pairs.size() > 4096);
        requireSame(ctx.device(), *r, "coincident grids");
        auto now = world->devicePairs();
        REQUIRE(now);
        CHECK(now->pairs == r->device->pairs);
    }
    {
        // Two in flight: slot 0 keeps frame 0's pairs while frame 1 writes slot 1.
        const TestScene scene = manySpheres();
        auto world = sceneWorld(ctx, scene);
        REQUIRE(world->submit(on));
        REQUIRE(world->submit(on));
        auto first = world->collect();
        REQUIRE(first);
        REQUIRE(world->setTransform(1, {1, 0, 0, 50, 0, 1, 0, 0, 0, 0, 1, 0}));  // moved away for frame 2 (slot 0)
        auto second = world->collect();
        REQUIRE(second);
        REQUIRE(first->device);
        REQUIRE(second->device);
        CHECK(first->device->slot == 0);
        CHECK(second->device->slot == 1);
        CHECK(first->device->pairs != second->device->pairs);
        requireSame(ctx.device(), *first, "pipelined frame 0");
        requireSame(ctx.device(), *second, "pipelined frame 1");
        auto third = world->detect(on);
        REQUIRE(third);
        CHECK(third->device->slot == 0);
        CHECK(third->pairs.size() < first->pairs.size());
        requireSame(ctx.device(), *third, "frame 2, object 1 moved away");
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("device pairs: a short capacity says overflow and the count needed", "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    auto all = allTestScenes();
    REQUIRE(all);
    auto world = sceneWorld(ctx, all->front());
    DetectSettings s;
    s.reliable.device_pairs = true;
    s.reliable.device_pair_capacity = 5;
    auto r = world->detect(s);
    REQUIRE(r);
    REQUIRE(r->pairs.size() > 5);
    REQUIRE(r->device);
    CHECK(r->device->capacity == 5);
    const DeviceCopy d = readBack(ctx.device(), *r->device);
    CHECK(d.header.flags == kDevicePairsOverflow);
    CHECK(d.header.needed == r->pairs.size());
    CHECK(d.header.count == 5);
    CHECK(d.header.capacity == 5);
    CHECK(d.pairs == std::vector<TrianglePair>(r->pairs.begin(), r->pairs.begin() + 5));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("device pairs: refused by name without the GPU's exact decision", "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    auto all = allTestScenes();
    REQUIRE(all);
    auto world = sceneWorld(ctx, all->front());
    const auto refused = [&](DetectSettings s, ErrorCode code, const char* words) {
        s.reliable.device_pairs = true;
        auto r = world->detect(s);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == code);
        CHECK_THAT(r.error().message(), Catch::Contains("reliable.device_pair") && Catch::Contains(words));
        CHECK_FALSE(world->resolveSettings(s));
        CHECK_FALSE(world->devicePairs());
    };
    CHECK_FALSE(world->devicePairs());  // none started yet
    if (!ctx.device().shader_float64) {
        refused({}, ErrorCode::UnsupportedFeature, "shaderFloat64");
        return;
    }
    refused({.method = DetectMethod::Peeling}, ErrorCode::InvalidArgument, "reliable method");
    DetectSettings cpu;
    cpu.reliable.exact = ExactDecision::Cpu;
    refused(cpu, ErrorCode::InvalidArgument, "exact decision on the GPU");
    DetectSettings big;
    big.reliable.device_pair_capacity = kMaxDevicePairCapacity + 1;
    refused(big, ErrorCode::InvalidArgument, "kMaxDevicePairCapacity");
    DetectSettings responses_alone;
    responses_alone.reliable.device_responses = true;
    auto alone = world->detect(responses_alone);
    REQUIRE_FALSE(alone);
    CHECK(alone.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(alone.error().message(), Catch::Contains("reliable.device_responses") && Catch::Contains("reliable.device_pairs"));
    // Without the setting a detection has none, and devicePairs() says so.
    auto plain = world->detect();
    REQUIRE(plain);
    CHECK_FALSE(plain->device);
    CHECK_FALSE(world->devicePairs());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// host_pairs = false: the same device buffers as with the host result, nothing on the host,
// the count in the stats; after an overflow rerun and pipelined too.
TEST_CASE("device pairs without a host result hold the host result's pairs", "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    DetectSettings with_host;
    with_host.reliable.device_pairs = true;
    with_host.reliable.device_responses = true;
    DetectSettings gpu_only = with_host;
    gpu_only.reliable.host_pairs = false;
    // The pairs and responses of a host run, then the device-only run's buffers against them.
    const auto same = [&](CollisionWorld& world, const std::string& what) {
        INFO(what);
        auto host = world.detect(with_host);
        REQUIRE(host);
        REQUIRE(host->pairs.size() > 0);
        auto only = world.detect(gpu_only);
        REQUIRE(only);
        CHECK(only->pairs.empty());
        CHECK(only->responses.empty());
        CHECK(only->stats.cpu_exact_tests == 0);
        CHECK(only->stats.reliable.device_pairs_found == host->pairs.size());
        CHECK(only->stats.reliable.device_pairs_written == host->pairs.size());
        REQUIRE(only->device);
        const DeviceCopy d = readBack(ctx.device(), *only->device);
        CHECK(d.header.flags == 0);
        CHECK(d.header.needed == host->pairs.size());
        CHECK(d.pairs == host->pairs);
        CHECK(only->stats.reliable.device_responses_written == host->responses.size());
        requireSameResponses(d, *host);
        return host->pairs;
    };
    std::vector<TestScene> scenes;
    auto all = allTestScenes();
    REQUIRE(all);
    for (TestScene& s : *all) scenes.push_back(std::move(s));
    scenes.push_back(restingStack());
    for (const TestScene& scene : scenes) {
        auto world = sceneWorld(ctx, scene);
        same(*world, scene.name);
    }
    {
        // Overflow: the first run's survivors (on the device now) do not fit; collect()
        // reruns and the buffers hold the final pairs.
        auto world = sceneWorld(ctx, coincidentGrids());
        auto only = world->detect(gpu_only);
        REQUIRE(only);
        CHECK(only->stats.cells.runs > 1);
        CHECK(only->stats.reliable.device_pairs_found > 4096);
        REQUIRE(only->device);
        const DeviceCopy d = readBack(ctx.device(), *only->device);
        CHECK(d.header.needed == only->stats.reliable.device_pairs_found);
        const auto host_pairs = same(*world, "coincident grids");
        CHECK(d.pairs == host_pairs);
    }
    {
        // Pipelined, switching between the two forms: each slot's buffers are right.
        auto world = sceneWorld(ctx, manySpheres());
        REQUIRE(world->submit(gpu_only));
        REQUIRE(world->submit(with_host));
        auto first = world->collect();
        auto second = world->collect();
        REQUIRE(first);
        REQUIRE(second);
        REQUIRE(first->device);
        CHECK(first->pairs.empty());
        const DeviceCopy d = readBack(ctx.device(), *first->device);
        CHECK(d.pairs == second->pairs);
        requireSame(ctx.device(), *second, "pipelined, with the host result");
    }
    // A short capacity: the count needed and the count written.
    {
        auto world = sceneWorld(ctx, restingStack());
        DetectSettings shorter = gpu_only;
        shorter.reliable.device_pair_capacity = 7;
        auto r = world->detect(shorter);
        REQUIRE(r);
        CHECK(r->stats.reliable.device_pairs_written == 7);
        CHECK(r->stats.reliable.device_pairs_found > 7);
    }
    // Refused by name: nowhere to keep the pairs, or contacts that need them on the host.
    auto world = sceneWorld(ctx, restingStack());
    DetectSettings nowhere;
    nowhere.reliable.host_pairs = false;
    auto r = world->detect(nowhere);
    REQUIRE_FALSE(r);
    CHECK_THAT(r.error().message(), Catch::Contains("reliable.host_pairs") && Catch::Contains("reliable.device_pairs"));
    DetectSettings contacts = gpu_only;
    contacts.contacts.objects = true;
    r = world->detect(contacts);
    REQUIRE_FALSE(r);
    CHECK_THAT(r.error().message(), Catch::Contains("reliable.host_pairs") && Catch::Contains("contacts.objects"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

namespace {

// A flat sheet (two triangles per cell) and its copy tilted about the X axis by `sin`
// (cos rounded to float: 1 for the tiniest tilts), crossing along X: the two normals
// differ by about `sin`, so every response sums terms of that size.
TestScene tiltedSheets(const std::string& name, float sin, float scale) {
    TestScene s{name, {}};
    const float cos = std::sqrt(1.0f - sin * sin);
    for (int k = 0; k < 2; ++k) {
        auto m = clothGrid(2, 2, 12, 12);
        REQUIRE(m);
        const float c = k ? cos : 1.0f, t = k ? sin : 0.0f;
        const Transform3x4 at{scale, 0, 0, 0, 0, scale * c, -scale * t, 0, 0, scale * t, scale * c, 0};
        s.objects.push_back({std::move(*m), {.name = "sheet" + std::to_string(k), .open = true, .transform = at}});
    }
    return s;
}

// Needles and zero-area triangles (segments, points on the plate) through a plate of two
// triangles that comes after them: each plate triangle has hundreds of lower partners, so
// their bucket is heap-sorted, and the zero-area ones have no normal of their own.
TestScene needlesThroughPlate() {
    TestScene s{"needles through a plate", {}};
    HostMesh needles;
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 24; ++j) {
            const float x = -0.9f + 0.075f * float(i), y = -0.9f + 0.075f * float(j);
            const auto base = static_cast<std::uint32_t>(needles.positions.size());
            const int kind = (i + j) % 4;
            const float w = kind == 0 ? 0.0f : kind == 1 ? 1e-30f : kind == 2 ? 1e-7f : 0.01f;  // segment, slivers, a thin one
            needles.positions.push_back({x, y, -1.0f});
            needles.positions.push_back({x + w, y, 1.0f});
            needles.positions.push_back({x, y + (kind == 0 ? 0.0f : w), kind == 0 ? 0.0f : 1.0f});  // kind 0: collinear, through z = 0
            needles.indices.insert(needles.indices.end(), {base, base + 1, base + 2});
        }
    HostMesh plate;
    plate.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    plate.indices = {0, 1, 2, 0, 2, 3};
    s.objects.push_back({std::move(needles), {.name = "needles", .open = true}});
    s.objects.push_back({std::move(plate), {.name = "plate", .open = true}});
    return s;
}

}  // namespace

// The responses' arithmetic where the CPU's rounding is easiest to miss: sums of tiny normal
// differences (tilts of 2^-12 .. 2^-60, down to none at all in float), scales from 2^-40 to
// 2^40, slivers, segments and points with no normal, a triangle with hundreds of partners, a
// resting stack's exact coplanar contacts (sums of exact zeros and ones).
TEST_CASE("device responses: tiny tilts, extreme scales, slivers and crowded triangles give the host's responses to the bit",
          "[api][gpu][reliable][device_pairs]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    DetectSettings on;
    on.reliable.device_pairs = true;
    on.reliable.device_responses = true;
    std::vector<TestScene> scenes;
    for (const int tilt : {12, 24, 30, 60})
        for (const int scale : {-40, 0, 40})
            scenes.push_back(tiltedSheets("sheets tilted by 2^-" + std::to_string(tilt) + " at 2^" + std::to_string(scale),
                                          std::ldexp(1.0f, -tilt), std::ldexp(1.0f, scale)));
    scenes.push_back(needlesThroughPlate());
    scenes.push_back(restingStack());
    for (const TestScene& scene : scenes) {
        auto world = sceneWorld(ctx, scene);
        auto r = world->detect(on);
        REQUIRE(r);
        INFO(scene.name);
        CHECK(r->pairs.size() > 0);
        requireSame(ctx.device(), *r, scene.name);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
