// Bad input and faults: engine meshes that fail the GPU check are left out and
// named while the others keep their pairs; bad descriptions are refused naming the object
// and the problem without disturbing the other objects; a scene too large for the device
// is OutOfMemory, after which the world and a new Context work; Vulkan's device-loss and
// out-of-memory results map to their error codes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "broad/broad_phase.hpp"
#include "stability_support.hpp"
#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vk/loader.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// The paper's method: the memory check below is its table's (broadPhaseMemory); the
// reliable method's handling of bad engine meshes is tested in tests/api/reliable_tests.cpp.
DetectSettings fixed(std::uint32_t resolution = 128) {
    DetectSettings s;
    s.method = DetectMethod::Peeling;
    s.resolution = resolution;
    s.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    return s;
}


// The pairs of the scene without object `skip` (host meshes, ids renumbered back).
std::vector<TrianglePair> pairsWithout(ValidatedContext& ctx, const TestScene& scene, std::vector<ObjectId> skip) {
    auto w = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(w);
    std::vector<ObjectId> ids;  // world id -> scene index
    for (ObjectId i = 0; i < scene.objects.size(); ++i) {
        if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
        REQUIRE((*w)->addMesh(scene.objects[i].mesh, scene.objects[i].options));
        ids.push_back(i);
    }
    auto r = (*w)->detect(fixed());
    REQUIRE(r);
    for (TrianglePair& p : r->pairs) p.object_a = ids[p.object_a], p.object_b = ids[p.object_b];
    return r->pairs;
}

}  // namespace

TEST_CASE("a bad engine mesh is left out and named, the other objects keep their pairs", "[stability][gpu][faults]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    std::vector<EngineMesh> engine;
    for (const SceneObject& o : scene->objects) {
        engine.push_back(engineCopy(ctx.device(), o.mesh));
        REQUIRE((*world)->addGpuMesh(engine.back().desc, o.options));
    }
    REQUIRE((*world)->detect(fixed()));  // pipelines and buffers; the next one is timed
    auto clean = (*world)->detect(fixed());
    REQUIRE(clean);
    CHECK(clean->excluded.empty());
    CHECK(clean->pairs == pairsWithout(ctx, *scene, {}));

    // sphere-c (id 2): an index out of range in triangle 2.
    const std::uint32_t saved_index = engine[2].index()[7];
    engine[2].index()[7] = engine[2].desc.vertex_count + 5;
    engine[2].flush();
    auto one = (*world)->detect(fixed());
    REQUIRE(one);
    REQUIRE(one->excluded.size() == 1);
    CHECK(one->excluded[0].object == 2);
    CHECK(one->excluded[0].error.code() == ErrorCode::InvalidMesh);
    CHECK(mentions(one->excluded[0].error, "sphere-c"));
    CHECK(mentions(one->excluded[0].error, "triangle 2 "));
    CHECK(one->stats.objects == 3);
    CHECK(one->pairs == pairsWithout(ctx, *scene, {2}));
    std::printf("faults | clean frame %.1f ms, frame with a bad object left out %.1f ms\n", clean->stats.total_ms,
                one->stats.total_ms);

    // And sphere-a (id 0): a NaN position. Both go in one detection, each with its own problem.
    const float saved_position = engine[0].positions()[engine[0].index()[0] * 3 + 1];
    engine[0].positions()[engine[0].index()[0] * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
    engine[0].flush();
    auto two = (*world)->detect(fixed());
    REQUIRE(two);
    REQUIRE(two->excluded.size() == 2);
    for (const ExcludedObject& e : two->excluded) {
        INFO(e.error.message());
        CHECK(((e.object == 0 && mentions(e.error, "sphere-a") && mentions(e.error, "NaN or infinite")) ||
               (e.object == 2 && mentions(e.error, "sphere-c") && mentions(e.error, "index"))));
    }
    CHECK(two->pairs == pairsWithout(ctx, *scene, {0, 2}));

    // Found in the asynchronous form too: the whole submission ran, then collect() runs
    // again without them.
    REQUIRE((*world)->submit(fixed()));
    auto async = (*world)->collect();
    REQUIRE(async);
    CHECK(async->excluded.size() == 2);
    CHECK(async->pairs == two->pairs);
    std::printf("faults | submit/collect with two bad objects %.1f ms\n", async->stats.total_ms);

    // The strict policy fails instead, naming the first.
    DetectSettings strict = fixed();
    strict.bad_objects = BadObjectPolicy::Fail;
    auto failed = (*world)->detect(strict);
    REQUIRE_FALSE(failed);
    CHECK(failed.error().code() == ErrorCode::InvalidMesh);

    // Repaired buffers: nothing left out, the clean pairs again.
    engine[2].index()[7] = saved_index;
    engine[0].positions()[engine[0].index()[0] * 3 + 1] = saved_position;
    engine[0].flush();
    engine[2].flush();
    auto repaired = (*world)->detect(fixed());
    REQUIRE(repaired);
    CHECK(repaired->excluded.empty());
    CHECK(repaired->pairs == clean->pairs);
    REQUIRE((*world)->submit(fixed()));
    auto clean_async = (*world)->collect();
    REQUIRE(clean_async);
    CHECK(clean_async->pairs == clean->pairs);
    std::printf("faults | submit/collect, clean %.1f ms\n", clean_async->stats.total_ms);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("when every object is bad the detection fails, naming one", "[stability][gpu][faults]") {
    ValidatedContext ctx;
    auto sphere = uvSphere(1.0f, 12, 6);
    REQUIRE(sphere);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    EngineMesh e = engineCopy(ctx.device(), *sphere);
    REQUIRE((*world)->addGpuMesh(e.desc, {.name = "only"}));
    e.positions()[4] = std::numeric_limits<float>::infinity();
    e.flush();
    auto r = (*world)->detect(fixed());
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(r.error(), "no object left"));
    CHECK(mentions(r.error(), "'only'"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("refused input names the object and the problem and leaves the other objects alone", "[stability][gpu][faults]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox();
    REQUIRE(scene);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    auto before = (*world)->detect(fixed());
    REQUIRE(before);

    auto sphere = uvSphere(0.5f, 12, 6);
    REQUIRE(sphere);
    HostMesh inf = *sphere;
    inf.positions[3].x = -std::numeric_limits<float>::infinity();
    auto r = (*world)->addMesh(inf, {.name = "exploded"});
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(r.error(), "exploded"));

    EngineMesh e = engineCopy(ctx.device(), *sphere);
    struct Bad {
        const char* what;
        void (*spoil)(GpuMeshDesc&);
        ErrorCode code;
        const char* says;
    };
    const Bad bad[] = {
        {"index count", [](GpuMeshDesc& d) { d.index_count -= 2; }, ErrorCode::InvalidMesh, "not a multiple of 3"},
        {"empty", [](GpuMeshDesc& d) { d.index_count = 0; }, ErrorCode::InvalidMesh, "empty mesh"},
        {"no vertices", [](GpuMeshDesc& d) { d.vertex_count = 0; }, ErrorCode::InvalidMesh, "empty mesh"},
        {"null buffer", [](GpuMeshDesc& d) { d.vertex_buffer = VK_NULL_HANDLE; }, ErrorCode::InvalidArgument, "VK_NULL_HANDLE"},
        {"stride", [](GpuMeshDesc& d) { d.vertex_stride = 10; }, ErrorCode::InvalidArgument, "vertex stride 10"},
        {"offset", [](GpuMeshDesc& d) { d.vertex_offset = 2; }, ErrorCode::InvalidArgument, "multiples of 4"},
        {"short vertex buffer", [](GpuMeshDesc& d) { d.vertex_count *= 2; }, ErrorCode::BufferTooSmall, "vertex buffer of"},
        {"short index buffer", [](GpuMeshDesc& d) { d.index_count += 3; }, ErrorCode::BufferTooSmall, "index buffer of"},
        {"declared larger", [](GpuMeshDesc& d) { d.index_buffer_size *= 8; }, ErrorCode::BufferTooSmall, "holds at most"},
        {"format", [](GpuMeshDesc& d) { d.position_format = VK_FORMAT_R16G16B16A16_SFLOAT; }, ErrorCode::UnsupportedFeature, "position format"},
        {"index type", [](GpuMeshDesc& d) { d.index_type = VK_INDEX_TYPE_UINT8_EXT; }, ErrorCode::UnsupportedFeature, "index type"},
    };
    for (const Bad& b : bad) {
        GpuMeshDesc d = e.desc;
        b.spoil(d);
        auto added = (*world)->addGpuMesh(d, {.name = "engine-ball"});
        INFO(b.what);
        REQUIRE_FALSE(added);
        CHECK(added.error().code() == b.code);
        CHECK(mentions(added.error(), "engine-ball"));
        CHECK(mentions(added.error(), b.says));
    }
    CHECK((*world)->objectCount() == scene->objects.size());
    auto after = (*world)->detect(fixed());
    REQUIRE(after);
    CHECK(after->pairs == before->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a scene too large for the device is OutOfMemory, the world and a new Context still work", "[stability][gpu][faults]") {
    ValidatedContext ctx;
    auto scene = torusThroughBox();
    REQUIRE(scene);
    auto world = CollisionWorld::create(ctx.context(), {.threads = 2});
    REQUIRE(world);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    auto before = (*world)->detect(fixed(64));
    REQUIRE(before);

    const vk::Device& dev = ctx.device();
    VkDeviceSize largest_heap = 0;
    for (std::uint32_t h = 0; h < dev.memory.memoryHeapCount; ++h) largest_heap = std::max(largest_heap, dev.memory.memoryHeaps[h].size);
    const auto triangles = static_cast<std::uint32_t>((*world)->triangleCount());
    bool refused_any = false;
    for (std::uint32_t resolution : {8192u, 16384u}) {
        const VkDeviceSize need = passes::broadPhaseMemory(resolution, triangles, 2);
        if (need <= largest_heap / 2) {
            WARN("this device could hold resolution " << resolution << " (" << need << " bytes): not refused here");
            continue;
        }
        auto huge = (*world)->detect(fixed(resolution));
        INFO("resolution " << resolution);
        REQUIRE_FALSE(huge);
        CHECK(huge.error().code() == ErrorCode::OutOfMemory);
        CHECK(mentions(huge.error(), "resolution " + std::to_string(resolution)));
        CHECK(mentions(huge.error(), "lower the resolution"));
        std::printf("faults | %s\n", huge.error().message().c_str());
        // The asynchronous form refuses it at submit(), with nothing left in flight.
        REQUIRE_FALSE((*world)->submit(fixed(resolution)));
        CHECK_FALSE((*world)->pending());
        refused_any = true;
    }
    if (refused_any) {
        auto again = (*world)->detect(fixed(64));
        REQUIRE(again);
        CHECK(again->pairs == before->pairs);

        // A second Context (and world) on the same machine works after the failure.
        ValidatedContext fresh;
        auto w2 = CollisionWorld::create(fresh.context(), {.threads = 2});
        REQUIRE(w2);
        for (const SceneObject& o : scene->objects) REQUIRE((*w2)->addMesh(o.mesh, o.options));
        auto r2 = (*w2)->detect(fixed(64));
        REQUIRE(r2);
        CHECK(r2->pairs == before->pairs);
        REQUIRE_NO_VALIDATION_MESSAGES(fresh);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("Vulkan's device loss and out-of-memory results map to their error codes", "[stability][faults]") {
    CHECK(vk::vulkanError(VK_ERROR_DEVICE_LOST, "vkQueueSubmit").code() == ErrorCode::DeviceLost);
    CHECK(vk::vulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory").code() == ErrorCode::OutOfMemory);
    CHECK(vk::vulkanError(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateBuffer").code() == ErrorCode::OutOfMemory);
    const Error e = vk::vulkanError(VK_ERROR_DEVICE_LOST, "vkWaitForFences");
    CHECK(e.vkResult() == VK_ERROR_DEVICE_LOST);
    CHECK(mentions(e, "vkWaitForFences"));
}
