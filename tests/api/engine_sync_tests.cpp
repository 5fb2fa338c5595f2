// CollisionWorld's engine seams on the device, validation on: submit() with the engine's
// semaphores, record() into its command buffer, polling, two detections in flight,
// setGpuMeshBuffers, the guards for work in flight and for two threads, the engine's
// executor, and gpu_memory_bytes against the device's counter.
#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <thread>

#include "api/engine_copy.hpp"
#include "support/engine_commands.hpp"
#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/world_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vk/semaphore.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

constexpr std::uint64_t kForever = UINT64_MAX;

using test::mentions;

DetectSettings peeling() {
    DetectSettings s;
    s.method = DetectMethod::Peeling;
    s.resolution = 128;
    s.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    return s;
}

// The fixed direction of peeling(), with `method` at a resolution that suits it here.
DetectSettings withMethod(DetectMethod method) {
    DetectSettings s = peeling();
    s.method = method;
    s.resolution = method == DetectMethod::Reliable ? 64u : 128u;
    return s;
}

Transform3x4 translated(float x) {
    Transform3x4 t = kIdentity3x4;
    t[3] = x;
    return t;
}

}  // namespace

TEST_CASE("submit() waits for and signals the engine's timeline, ready() and tryCollect() never block", "[api][gpu][sync]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    addScene(*world, *scene);
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling}) {
        const DetectSettings s = withMethod(method);
        auto expected = world->detect(s);
        REQUIRE(expected);
        REQUIRE_FALSE(expected->pairs.empty());
        auto timeline = vk::Semaphore::createTimeline(ctx.device(), 0, "engine-timeline");
        REQUIRE(timeline);
        // The engine's deformation signals 1 (later, from the host here); the detection
        // waits for it and signals 2.
        const SemaphoreSubmit wait[] = {{timeline->handle(), 1}};
        const SemaphoreSubmit signal[] = {{timeline->handle(), 2}};
        REQUIRE(world->submit(s, {.wait = wait, .signal = signal}));
        for (int poll = 0; poll < 3; ++poll) {
            auto ready = world->ready();
            REQUIRE(ready);
            CHECK_FALSE(*ready);  // held by the wait: nothing can have run
            auto early = world->tryCollect();
            REQUIRE(early);
            CHECK_FALSE(early->has_value());
            CHECK(world->pending());
        }
        REQUIRE(timeline->signal(1));
        auto reached = timeline->wait(2, kForever);  // the engine waits on the GPU's signal
        REQUIRE(reached);
        CHECK(*reached);
        std::optional<DetectResult> got;
        while (!got) {
            auto r = world->tryCollect();
            REQUIRE(r);
            got = std::move(*r);
        }
        CHECK(got->pairs == expected->pairs);
        CHECK_FALSE(world->pending());
        auto none = world->ready();
        REQUIRE_FALSE(none);
        CHECK(mentions(none.error(), "without a detection in flight"));
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a submit() that fails still signals what it promised, a bad SubmitSync is refused before anything runs",
          "[api][gpu][sync]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    addScene(*world, *scene);
    auto timeline = vk::Semaphore::createTimeline(ctx.device(), 0, "engine-timeline");
    REQUIRE(timeline);
    const SemaphoreSubmit signal[] = {{timeline->handle(), 5}};
    DetectSettings bad = peeling();
    bad.resolution = 100;  // not a power of two
    auto refused = world->submit(bad, {.signal = signal});
    REQUIRE_FALSE(refused);
    CHECK(mentions(refused.error(), "power of two"));
    auto reached = timeline->wait(5, kForever);  // a batch of only the signal was submitted
    REQUIRE(reached);
    CHECK(*reached);
    CHECK_FALSE(world->pending());

    const SemaphoreSubmit null_wait[] = {{VK_NULL_HANDLE, 1}};
    auto null = world->submit({}, {.wait = null_wait});
    REQUIRE_FALSE(null);
    CHECK(mentions(null.error(), "SubmitSync::wait[0] has a null semaphore"));
    const SemaphoreSubmit no_stage[] = {{timeline->handle(), 6, 0}};
    auto stage = world->submit({}, {.signal = no_stage});
    REQUIRE_FALSE(stage);
    CHECK(mentions(stage.error(), "SubmitSync::signal[0] has stage mask 0"));
    CHECK_FALSE(world->pending());
    auto value = timeline->value();
    REQUIRE(value);
    CHECK(*value == 5);  // nothing submitted for the refused syncs
    auto expected = world->detect();
    REQUIRE(expected);

    // Binary semaphores: one detection signals, the next (in flight at the same time) waits.
    auto binary = vk::Semaphore::createBinary(ctx.device(), "engine-binary");
    REQUIRE(binary);
    const SemaphoreSubmit handoff[] = {{binary->handle()}};
    REQUIRE(world->submit({}, {.signal = handoff}));
    REQUIRE(world->submit({}, {.wait = handoff}));
    for (int k = 0; k < 2; ++k) {
        auto r = world->collect();
        REQUIRE(r);
        CHECK(r->pairs == expected->pairs);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("record() puts the detection into the engine's command buffer, where it needs two submissions it is refused by name",
          "[api][gpu][sync]") {
    ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    addScene(*world, *scene);
    auto expected = world->detect();
    REQUIRE(expected);
    auto timeline = vk::Semaphore::createTimeline(dev, 0, "engine-timeline");
    REQUIRE(timeline);
    {
        EngineCommands engine(dev);
        REQUIRE(world->record({engine.cmd, timeline->handle(), 1}));
        CHECK(world->pending());
        auto ready = world->ready();
        REQUIRE(ready);
        CHECK_FALSE(*ready);  // not submitted by the engine yet
        engine.submit(timeline->handle(), 1);
        auto r = world->collect();
        REQUIRE(r);
        CHECK(r->pairs == expected->pairs);
    }
    // Peeling must measure first (objects just changed): two submissions and a host wait.
    auto extra = world->addMesh(scene->objects[0].mesh, {.name = "extra", .transform = translated(20)});
    REQUIRE(extra);
    {
        EngineCommands engine(dev);
        auto refused = world->record({engine.cmd, timeline->handle(), 2}, peeling());
        REQUIRE_FALSE(refused);
        CHECK(mentions(refused.error(), "record: the peeling method measures the depth complexity first"));
        DetectSettings three = peeling();
        three.peeling.axes = 3;
        auto axes = world->record({engine.cmd, timeline->handle(), 2}, three);
        REQUIRE_FALSE(axes);
        CHECK(mentions(axes.error(), "three sampling directions make three submissions"));
        CHECK_FALSE(world->pending());
        // Once measured, peeling records too.
        auto measured = world->detect(peeling());
        REQUIRE(measured);
        REQUIRE(world->record({engine.cmd, timeline->handle(), 2}, peeling()));
        engine.submit(timeline->handle(), 2);
        auto r = world->collect();
        REQUIRE(r);
        CHECK(r->pairs == measured->pairs);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("two detections in flight: each keeps the transforms it was submitted with, results come in order", "[api][gpu][sync]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    const Transform3x4 start = scene->objects[0].options.transform;
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling}) {
        const DetectSettings s = withMethod(method);
        REQUIRE(world->setTransform(ids[0], start));
        auto touching = world->detect(s);
        REQUIRE(touching);
        REQUIRE_FALSE(touching->pairs.empty());
        REQUIRE(world->setTransform(ids[0], translated(30)));
        auto apart = world->detect(s);
        REQUIRE(apart);

        REQUIRE(world->setTransform(ids[0], start));
        REQUIRE(world->submit(s));                          // frame N: touching
        REQUIRE(world->setTransform(ids[0], translated(30)));  // allowed in flight
        REQUIRE(world->submit(s));                          // frame N+1: apart
        CHECK(world->inFlight() == 2);
        auto n = world->collect();  // N's narrow phase while N+1's GPU work may run
        REQUIRE(n);
        CHECK(n->pairs == touching->pairs);
        REQUIRE(world->setTransform(ids[0], start));
        REQUIRE(world->submit(s));  // frame N+2 into the slot N left
        auto n1 = world->collect();
        REQUIRE(n1);
        CHECK(n1->pairs == apart->pairs);
        auto n2 = world->collect();
        REQUIRE(n2);
        CHECK(n2->pairs == touching->pairs);
        CHECK_FALSE(world->pending());
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("updateVertices in flight: each detection reads the vertices it was submitted with, on the GPU and in the narrow phase",
          "[api][gpu][sync]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    const std::vector<Float3> near = scene->objects[0].mesh.positions;
    std::vector<Float3> far = near, bad = near;
    for (Float3& p : far) p.x += 30;
    bad[5].z = std::numeric_limits<float>::infinity();
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling}) {
        INFO(toString(method));
        const DetectSettings s = withMethod(method);
        REQUIRE(world->updateVertices(ids[0], near));
        auto touching = world->detect(s);
        REQUIRE(touching);
        REQUIRE_FALSE(touching->pairs.empty());
        REQUIRE(world->updateVertices(ids[0], far));
        auto apart = world->detect(s);
        REQUIRE(apart);
        REQUIRE(apart->pairs.size() < touching->pairs.size());  // object 0's pairs are gone

        REQUIRE(world->updateVertices(ids[0], near));
        REQUIRE(world->submit(s));                        // frame N: touching
        REQUIRE(world->updateVertices(ids[0], far));      // N reads the other copy
        auto refused = world->updateVertices(ids[0], bad);  // in flight too: changes nothing
        REQUIRE_FALSE(refused);
        CHECK(mentions(refused.error(), "vertex 5 is NaN or infinite"));
        REQUIRE(world->submit(s));                        // frame N+1: apart
        REQUIRE(world->updateVertices(ids[0], near));     // both read a copy: a third one
        auto n = world->collect();
        REQUIRE(n);
        CHECK(n->pairs == touching->pairs);
        REQUIRE(world->submit(s));                        // frame N+2: touching
        REQUIRE(world->updateVertices(ids[0], far));      // into the copy N read
        auto n1 = world->collect();
        REQUIRE(n1);
        CHECK(n1->pairs == apart->pairs);
        auto n2 = world->collect();
        REQUIRE(n2);
        CHECK(n2->pairs == touching->pairs);
        CHECK(n2->stats.gpu_memory_bytes == ctx.context().deviceMemoryInUse());
        auto now = world->detect(s);  // the last update
        REQUIRE(now);
        CHECK(now->pairs == apart->pairs);
        CHECK(now->stats.gpu_memory_bytes == n2->stats.gpu_memory_bytes);  // no further copy
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("setGpuMeshBuffers re-points an engine mesh, keeps its id, and refuses another topology by name", "[api][gpu]") {
    ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    HostMesh moved = scene->objects[1].mesh;
    for (Float3& p : moved.positions) p.x += 30;
    EngineMesh a = engineCopy(dev, scene->objects[1].mesh);
    EngineMesh b = engineCopy(dev, moved, 16, VK_FORMAT_R32G32B32_SFLOAT);  // another stride: fine
    auto host = world->addMesh(scene->objects[0].mesh, scene->objects[0].options);
    REQUIRE(host);
    auto id = world->addGpuMesh(a.desc, {.name = "skin", .transform = scene->objects[1].options.transform});
    REQUIRE(id);
    auto with_a = world->detect(peeling());
    REQUIRE(with_a);
    REQUIRE_FALSE(with_a->pairs.empty());
    REQUIRE(world->submit(peeling()));
    REQUIRE(world->setGpuMeshBuffers(*id, b.desc));  // in flight: the detection keeps A
    auto still_a = world->collect();
    REQUIRE(still_a);
    CHECK(still_a->pairs == with_a->pairs);
    auto with_b = world->detect(peeling());
    REQUIRE(with_b);
    CHECK(with_b->pairs.empty());
    REQUIRE(world->setGpuMeshBuffers(*id, a.desc));
    auto back = world->detect(peeling());
    REQUIRE(back);
    CHECK(back->pairs == with_a->pairs);
    CHECK(world->objectCount() == 2);

    GpuMeshDesc other = a.desc;
    other.index_count -= 3;
    auto topology = world->setGpuMeshBuffers(*id, other);
    REQUIRE_FALSE(topology);
    CHECK(mentions(topology.error(), "object 1 ('skin'): setGpuMeshBuffers keeps the topology: index count"));
    auto on_host = world->setGpuMeshBuffers(*host, a.desc);
    REQUIRE_FALSE(on_host);
    CHECK(mentions(on_host.error(), "is a host mesh"));
    GpuMeshDesc no_address = b.desc;
    no_address.vertex_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto usage = world->setGpuMeshBuffers(*id, no_address);
    REQUIRE_FALSE(usage);
    CHECK(mentions(usage.error(), "object 1 ('skin'): vertex buffer was not declared with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT"));
    auto added = world->addGpuMesh(no_address, {.name = "plain"});
    REQUIRE_FALSE(added);
    CHECK(mentions(added.error(), "('plain'): vertex buffer was not declared"));
    auto after = world->detect(peeling());  // nothing changed by the refusals
    REQUIRE(after);
    CHECK(after->pairs == with_a->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("calls that change what work in flight reads fail by name, so do calls from a second thread or a callback",
          "[api][gpu]") {
    ValidatedContext ctx;
    // The engine's job system: runs the loops on the caller, and in its first loop tries the
    // world from inside (re-entered) and from another thread (used from two threads).
    struct Jobs final : Executor {
        int loops = 0;
        std::vector<Error> refusals;
        CollisionWorld* target = nullptr;
        unsigned threadCount() const noexcept override { return 4; }
        void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) override {
            if (loops++ == 0 && target) {
                auto inside = target->setTransform(0, kIdentity3x4);
                if (!inside) refusals.push_back(inside.error());
                std::thread other([&] {
                    auto from_other = target->detect();
                    if (!from_other) refusals.push_back(from_other.error());
                });
                other.join();
            }
            const std::size_t step = std::max<std::size_t>(grain, 1);
            for (std::size_t b = 0; b < count; b += step) body(b, std::min(count, b + step));
        }
    } jobs;
    std::vector<Error>& refusals = jobs.refusals;
    CollisionWorld*& target = jobs.target;
    int& loops = jobs.loops;
    auto world = makeWorld(ctx, {.executor = &jobs});
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    // The CPU decides (exact Cpu): few pairs the GPU decided would run on the calling thread
    // without the executor (narrow::kSerialDecidedBelow).
    DetectSettings cpu_decides;
    cpu_decides.reliable.exact = ExactDecision::Cpu;
    auto plain = world->detect(cpu_decides);
    REQUIRE(plain);
    target = world.get();
    loops = 0;
    auto watched = world->detect(cpu_decides);
    REQUIRE(watched);
    CHECK(watched->pairs == plain->pairs);
    CHECK(watched->stats.host.narrow_threads == 4);  // the engine's executor ran the narrow phase
    REQUIRE(refusals.size() == 2);
    CHECK(mentions(refusals[0], "CollisionWorld::setTransform was called from inside CollisionWorld::detect on the same thread"));
    CHECK(mentions(refusals[1], "CollisionWorld::detect was called on thread"));
    CHECK(mentions(refusals[1], "used from one thread at a time"));
    target = nullptr;
    // Where the GPU decides (shaderFloat64: lavapipe, the H200), the scene's few hundred
    // pairs run on the calling thread: the engine's executor is not called, and the stats
    // say one thread.
    loops = 0;
    auto decided = world->detect();
    REQUIRE(decided);
    CHECK(decided->pairs == plain->pairs);
    if (decided->stats.gpu_exact_tests > 0) {
        CHECK(loops == 0);
        CHECK(decided->stats.host.narrow_threads == 1);
    }

    REQUIRE(world->submit());
    std::vector<std::pair<std::string, Result<void>>> in_flight;
    in_flight.emplace_back("setSelfCollision", world->setSelfCollision(ids[0], true));
    in_flight.emplace_back("setPairFilter", world->setPairFilter({}));
    in_flight.emplace_back("removeObject", world->removeObject(ids[1]));
    auto added = world->addMesh(scene->objects[0].mesh);
    in_flight.emplace_back("addMesh", added ? Result<void>() : Result<void>(added.error()));
    for (const auto& [call, r] : in_flight) {
        INFO(call);
        REQUIRE_FALSE(r);
        CHECK(mentions(r.error(), call + " while a detection is in flight"));
    }
    auto detect = world->detect();
    REQUIRE_FALSE(detect);
    CHECK(mentions(detect.error(), "detect while a detection is in flight"));
    auto r = world->collect();
    REQUIRE(r);
    CHECK(r->pairs == plain->pairs);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("gpu_memory_bytes is every byte the world holds: the device's own counter with one world", "[api][gpu]") {
    ValidatedContext ctx;
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling}) {
        auto world = makeWorld(ctx);
        addScene(*world, *scene);
        const DetectSettings s = withMethod(method);
        auto r = world->detect(s);
        REQUIRE(r);
        CHECK(r->stats.gpu_memory_bytes == ctx.context().deviceMemoryInUse());
        REQUIRE(world->submit(s));
        REQUIRE(world->submit(s));  // the second slot's buffers count too
        REQUIRE(world->collect());
        auto second = world->collect();
        REQUIRE(second);
        CHECK(second->stats.gpu_memory_bytes == ctx.context().deviceMemoryInUse());
        CHECK(second->stats.gpu_memory_bytes > r->stats.gpu_memory_bytes);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("updateVertices refuses a NaN and changes nothing, a good update moves the pairs", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    const auto ids = addScene(*world, *scene);
    auto before = world->detect();
    REQUIRE(before);
    REQUIRE_FALSE(before->pairs.empty());
    std::vector<Float3> bad = scene->objects[0].mesh.positions;
    for (Float3& p : bad) p.x += 30;
    bad[7].y = std::numeric_limits<float>::quiet_NaN();
    auto refused = world->updateVertices(ids[0], bad);
    REQUIRE_FALSE(refused);
    CHECK(mentions(refused.error(), "vertex 7 is NaN or infinite"));
    auto same = world->detect();
    REQUIRE(same);
    CHECK(same->pairs == before->pairs);
    bad[7] = scene->objects[0].mesh.positions[7];
    bad[7].x += 30;
    REQUIRE(world->updateVertices(ids[0], bad));
    auto apart = world->detect();
    REQUIRE(apart);
    for (const TrianglePair& p : apart->pairs) CHECK((p.object_a != ids[0] && p.object_b != ids[0]));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
