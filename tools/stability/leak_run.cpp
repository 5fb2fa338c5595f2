// A long run for leak checking (tools/stability/leak_check.sh runs it under LeakSanitizer
// or valgrind): a small deforming scene detected frame after frame through every path
// that allocates — detect() and submit()/collect(), host vertex updates and engine-owned
// GPU buffers written in place, objects removed and added, three axes and dilation,
// an engine mesh that turns bad and is excluded, a resolution the device refuses, and a
// second Context created and destroyed. Prints the resident set size as it goes; exits
// non-zero on any unexpected error.
//
//   vkcollide_leak_run [frames=1000] [--validation]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <unistd.h>

#include "api/context_access.hpp"
#include "vk/resources.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

long residentKiB() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

[[noreturn]] void fail(const std::string& what, const Error& e) {
    std::fprintf(stderr, "leak_run: %s: %s\n", what.c_str(), e.message().c_str());
    std::exit(1);
}

template <typename T>
T must(Result<T> r, const std::string& what) {
    if (!r) fail(what, r.error());
    return std::move(*r);
}

void must(Result<void> r, const std::string& what) {
    if (!r) fail(what, r.error());
}

Transform3x4 at(float x, float y, float z) { return {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z}; }

}  // namespace

int main(int argc, char** argv) {
    int frames = 1000;
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--validation") == 0) validation = true;
        else frames = std::atoi(argv[i]);
    }
    ContextCreateInfo info;
    info.validation = validation;
    std::size_t messages = 0;
    info.on_message = [&](MessageSeverity s, std::string_view text) {
        if (s == MessageSeverity::Info) return;
        ++messages;
        std::fprintf(stderr, "validation: %.*s\n", int(text.size()), text.data());
    };
    auto ctx = must(Context::create(info), "Context::create");
    auto world = must(CollisionWorld::create(*ctx, {.threads = 2}), "CollisionWorld::create");

    // A cloth deformed on the host, a ball moved by its transform, a torus in engine buffers.
    ClothOptions sag;
    sag.sag = 0.2f;
    const HostMesh cloth = must(clothGrid(2.0f, 2.0f, 20, 20, sag), "cloth");
    const HostMesh ball = must(uvSphere(0.5f, 20, 10), "ball");
    const HostMesh ring = must(torus(0.6f, 0.15f, 24, 8), "torus");
    const ObjectId cloth_id = must(world->addMesh(cloth, {.name = "cloth", .self_collision = true, .open = true}), "add cloth");
    ObjectId ball_id = must(world->addMesh(ball, {.name = "ball"}), "add ball");
    auto vb = must(vk::Buffer::create(ContextAccess::device(*ctx), ring.positions.size() * 12, 0, vk::MemoryKind::Upload, "ring-vertices"), "ring vb");
    auto ib = must(vk::Buffer::create(ContextAccess::device(*ctx), ring.indices.size() * 4, 0, vk::MemoryKind::Upload, "ring-indices"), "ring ib");
    std::memcpy(ib.mapped(), ring.indices.data(), ring.indices.size() * 4);
    ib.flush();
    GpuMeshDesc desc;
    desc.vertex_buffer = vb.handle();
    desc.vertex_buffer_size = vb.size();
    desc.vertex_count = static_cast<std::uint32_t>(ring.positions.size());
    desc.index_buffer = ib.handle();
    desc.index_buffer_size = ib.size();
    desc.index_count = static_cast<std::uint32_t>(ring.indices.size());
    must(world->addGpuMesh(desc, {.name = "ring", .typical_edge_length = 0.15f}), "add ring");

    std::vector<Float3> moved = cloth.positions;
    std::size_t pairs = 0, excluded = 0, refused = 0;
    long rss_first = 0;
    for (int frame = 0; frame < frames; ++frame) {
        const float t = 0.05f * static_cast<float>(frame);
        for (std::size_t i = 0; i < moved.size(); ++i)
            moved[i].z = cloth.positions[i].z + 0.1f * std::sin(t + 3.0f * cloth.positions[i].x);
        must(world->updateVertices(cloth_id, moved), "updateVertices");
        must(world->setTransform(ball_id, at(0.3f * std::sin(t), 0.2f * std::cos(t), 0.0f)), "setTransform");
        auto* p = static_cast<float*>(vb.mapped());
        for (std::size_t i = 0; i < ring.positions.size(); ++i) {
            p[i * 3] = ring.positions[i].x + 0.2f * std::cos(t);
            p[i * 3 + 1] = ring.positions[i].y;
            p[i * 3 + 2] = ring.positions[i].z + 0.1f;
        }
        const bool bad_frame = frame % 97 == 13;
        if (bad_frame) p[4] = std::numeric_limits<float>::quiet_NaN();  // excluded this frame
        vb.flush();

        DetectSettings s;
        s.resolution = 64;
        s.peeling.axes = frame % 50 == 7 ? 3 : 1;
        s.peeling.coverage = frame % 50 == 21 ? Coverage::Dilate : Coverage::Centre;
        s.peeling.closed_epsilon = frame % 2 ? 0.01f : 0.0f;
        if (frame % 250 == 100) {  // refused before anything is allocated
            DetectSettings huge = s;
            huge.resolution = 16384;
            auto r = world->detect(huge);
            if (r || r.error().code() != ErrorCode::OutOfMemory) {
                std::fprintf(stderr, "leak_run: resolution 16384 was not refused as OutOfMemory\n");
                return 1;
            }
            ++refused;
        }
        Result<DetectResult> r = Error(ErrorCode::InvalidArgument, "not run");
        if (frame % 3 == 0) {
            r = world->detect(s);
        } else {
            must(world->submit(s), "submit");
            r = world->collect();
        }
        if (!r) fail("frame " + std::to_string(frame), r.error());
        pairs += r->pairs.size();
        excluded += r->excluded.size();
        if (bad_frame != !r->excluded.empty()) {
            std::fprintf(stderr, "leak_run: frame %d: the bad engine mesh was %s\n", frame, bad_frame ? "not excluded" : "excluded");
            return 1;
        }
        if (frame % 100 == 99) {  // churn: remove the ball and add it again (a new id)
            must(world->removeObject(ball_id), "removeObject");
            ball_id = must(world->addMesh(ball, {.name = "ball"}), "re-add ball");
        }
        if (frame % 250 == 200) {  // a second Context and world, made and destroyed
            auto other = must(Context::create(), "second Context");
            auto w2 = must(CollisionWorld::create(*other, {.threads = 1}), "second world");
            must(w2->addMesh(ball, {.name = "ball"}), "second add");
            must(w2->addMesh(ball, {.name = "ball-2", .transform = at(0.5f, 0, 0)}), "second add 2");
            must(w2->detect(s), "second detect");
        }
        if (frame == std::min(9, frames - 1)) rss_first = residentKiB();
        if (frame == 9 || frame % 100 == 99 || frame + 1 == frames)
            std::printf("frame %4d: resident %ld KiB, %zu pairs so far\n", frame + 1, residentKiB(), pairs);
    }
    std::printf("frames %d, pairs %zu, objects excluded %zu, huge resolutions refused %zu, validation messages %zu\n", frames, pairs,
                excluded, refused, messages);
    std::printf("resident growth from frame %d to the end: %ld KiB\n", std::min(10, frames), residentKiB() - rss_first);
    return messages == 0 ? 0 : 1;
}
