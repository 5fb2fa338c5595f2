// Frame loops as an engine runs them, one CSV row per case:
//  * update: CollisionWorld::updateVertices on a host mesh of about --vertices vertices
//    (a UV sphere), milliseconds per call and per million vertices (median of --frames),
//    on a world of --threads threads; then where that time goes, one row each (update_ms):
//      update-1t         the same on a world of one thread;
//      update-resolve    resolveSettings() after each update: the shape measurement that
//                        updateVertices leaves to the automatic settings, plus resolving;
//      update-pair-idle  a deforming pair's host frame: two meshes of --vertices updated
//                        and the settings resolved, after 0.5 ms idle (the executor's
//                        threads asleep, as after a detection's wait);
//      upload-memory     the memory type upload buffers get (method column: its flags);
//      part:<name>       the pieces alone, on a thread pool of --threads (or 1: -1t) and a
//                        mapped upload buffer as the world's (its memory type):
//        memcpy-host       a plain copy of the positions into host memory (parallel);
//        memcpy-upload     a plain copy into the upload buffer: the bus's write rate;
//        scan-host         updateVertices' pass without the upload buffer;
//        fused / staged    updateVertices' pass, both ways of writing the upload buffer
//                          (vertex_scans::UploadWrites; the world uses fused);
//  * detect / submit / pipelined: a deforming pair of engine meshes (two spheres of about
//    --triangles triangles each, written by the host into host-visible buffers, double
//    buffered with setGpuMeshBuffers), per frame the host wall time from writing the
//    vertices to having the result, median over --frames after two warm-up frames:
//      detect     detect() every frame;
//      submit     submit() then collect() every frame;
//      pipelined  submit() of frame N, then collect() of frame N - 1 (the narrow phase of
//                 N - 1 runs while N's GPU work runs); latency one frame.
//      alternating  detect() and submit() + collect() on alternate frames of one world:
//                 two rows (detect-alternating, submit-alternating), frame medians only,
//                 the fairest comparison of the two (same world, same clocks).
//    with the GPU stage times of the detection collected that frame.
//
//   vkcollide_bench_frames [--vertices 1000000] [--triangles 100000] [--frames 30]
//                          [--methods reliable,peeling|none] [--threads 0] [--warmup-ms 300]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "api/context_access.hpp"
#include "api/vertex_scans.hpp"
#include "vk/device.hpp"
#include "vk/resources.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

[[noreturn]] void die(const std::string& what) {
    std::fprintf(stderr, "vkcollide_bench_frames: %s\n", what.c_str());
    std::exit(1);
}

// A sphere with about `triangles` triangles (2 * segments * rings).
HostMesh sphere(float radius, std::uint64_t triangles) {
    const auto rings = static_cast<std::uint32_t>(std::max(4.0, std::sqrt(double(triangles) / 4)));
    auto m = uvSphere(radius, 2 * rings, rings);
    if (!m) die(m.error().message());
    return std::move(*m);
}

// Frame f's positions: the rest shape breathing and sliding along x (the two overlap).
void pose(const HostMesh& rest, int frame, float dx, std::vector<Float3>& out) {
    const float s = 1.0f + 0.05f * std::sin(0.3f * float(frame));
    out.resize(rest.positions.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Float3 p = rest.positions[i];
        out[i] = {p.x * s + dx, p.y * s, p.z * s};
    }
}

struct EngineMesh {
    vk::Buffer vertices[2], indices;
    GpuMeshDesc desc(int slot) const {
        GpuMeshDesc d;
        d.vertex_buffer = vertices[slot].handle();
        d.vertex_buffer_size = vertices[slot].size();
        d.vertex_count = static_cast<std::uint32_t>(vertices[slot].size() / sizeof(Float3));
        d.index_buffer = indices.handle();
        d.index_buffer_size = indices.size();
        d.index_count = static_cast<std::uint32_t>(indices.size() / 4);
        return d;
    }
};

EngineMesh engineMesh(vk::Device& dev, const HostMesh& m) {
    EngineMesh e;
    for (vk::Buffer& b : e.vertices) {
        auto vb = vk::Buffer::create(dev, m.positions.size() * sizeof(Float3), 0, vk::MemoryKind::Upload, "bench-vertices");
        if (!vb) die(vb.error().message());
        b = std::move(*vb);
    }
    auto ib = vk::Buffer::create(dev, m.indices.size() * 4, 0, vk::MemoryKind::Upload, "bench-indices");
    if (!ib) die(ib.error().message());
    std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
    ib->flush();
    e.indices = std::move(*ib);
    return e;
}

// Median milliseconds of `frames` calls of f(frame).
template <typename F>
double timeMedian(int frames, F&& f) {
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) {
        const auto t0 = Clock::now();
        f(i);
        times.push_back(msSince(t0));
    }
    return median(times);
}

std::string memoryFlags(VkMemoryPropertyFlags f) {
    std::string out;
    auto add = [&](VkMemoryPropertyFlags bit, const char* name) {
        if (f & bit) out += (out.empty() ? "" : "+") + std::string(name);
    };
    add(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "device-local");
    add(VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, "host-visible");
    add(VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, "coherent");
    add(VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "cached");
    return out;
}

// The update's pieces alone (see the top of the file), on the device's upload memory.
void updateParts(vk::Device& dev, const HostMesh& big, int frames, unsigned threads, const std::string& device) {
    const std::size_t n = big.positions.size();
    const double per_1m = 1e6 / double(n);
    auto row = [&](const std::string& name, double ms) {
        std::printf("%s,-,%zu,%zu,%d,%.3f,%.3f,,,,,,,%s\n", name.c_str(), big.triangleCount(), n, frames, ms, ms * per_1m, device.c_str());
    };
    const auto type = dev.findMemoryType(~0u, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    std::printf("upload-memory,%s,,,,,,,,,,,,%s\n", type ? memoryFlags(dev.memory.memoryTypes[*type].propertyFlags).c_str() : "none",
                device.c_str());
    auto buffer = vk::Buffer::create(dev, n * sizeof(Float3), 0, vk::MemoryKind::Upload, "bench-upload");
    if (!buffer) die(buffer.error().message());
    auto* upload = static_cast<Float3*>(buffer->mapped());
    std::vector<Float3> host(n), next;
    pose(big, 1, 0, next);
    ThreadPool one(1), many(threads);
    for (ThreadPool* pool : {&many, &one}) {
        const std::string suffix = pool == &one ? "-1t" : "";
        const std::size_t grain = std::max<std::size_t>(vertex_scans::kMinChunkVertices, (n / (4 * pool->threadCount()) + 15) / 16 * 16);
        auto copyTo = [&](Float3* dst) {
            pool->parallelFor(n, grain, [&](std::size_t b, std::size_t e) { std::memcpy(dst + b, next.data() + b, (e - b) * sizeof(Float3)); });
        };
        row("part:memcpy-host" + suffix, timeMedian(frames, [&](int) { copyTo(host.data()); }));
        row("part:memcpy-upload" + suffix, timeMedian(frames, [&](int) { copyTo(upload); }));
        row("part:scan-host" + suffix, timeMedian(frames, [&](int) { (void)vertex_scans::copyAndScan(*pool, next, host, nullptr); }));
        for (auto writes : {vertex_scans::UploadWrites::Fused, vertex_scans::UploadWrites::Staged})
            row(std::string(writes == vertex_scans::UploadWrites::Fused ? "part:fused" : "part:staged") + suffix,
                timeMedian(frames, [&](int) { (void)vertex_scans::copyAndScan(*pool, next, host, upload, writes); }));
    }
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (std::size_t comma; (comma = s.find(',', start)) != std::string::npos; start = comma + 1) out.push_back(s.substr(start, comma - start));
    out.push_back(s.substr(start));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::uint64_t vertices = 1000000, triangles = 100000;
    int frames = 30;
    double warmup_ms = 300;
    unsigned threads = 0;
    std::vector<std::string> methods = {"reliable", "peeling"};
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--vertices") vertices = std::stoull(value);
        else if (key == "--triangles") triangles = std::stoull(value);
        else if (key == "--frames") frames = std::max(3, std::stoi(value));
        else if (key == "--threads") threads = static_cast<unsigned>(std::stoul(value));
        else if (key == "--warmup-ms") warmup_ms = std::stod(value);
        else if (key == "--methods") methods = split(value);
        else die("unknown option " + key);
    }
    for (const std::string& method : methods)
        if (method != "reliable" && method != "peeling" && method != "none") die("unknown method " + method);
    auto ctx = Context::create();
    if (!ctx) die(ctx.error().message());
    std::printf("case,method,triangles,vertices,frames,update_ms,update_ms_per_1M_vertices,frame_ms,gpu_ms,readback_ms,narrow_ms,"
                "submit_to_result_ms,pairs,device\n");
    const std::string device = (*ctx)->deviceInfo().name;

    {  // updateVertices alone, then its parts.
        const HostMesh big = sphere(1.0f, 2 * vertices);  // a UV sphere has about half as many vertices as triangles
        const double n = double(big.positions.size());
        const std::vector<unsigned> thread_counts = threads == 1 ? std::vector<unsigned>{1} : std::vector<unsigned>{threads, 1};
        for (unsigned world_threads : thread_counts) {
            auto world = CollisionWorld::create(**ctx, {.threads = world_threads});
            if (!world) die(world.error().message());
            auto id = (*world)->addMesh(big, {.name = "big"});
            if (!id) die(id.error().message());
            std::vector<Float3> next;
            std::vector<double> times, resolve;
            for (int f = 0; f < frames; ++f) {
                pose(big, f, 0, next);
                const auto t0 = Clock::now();
                if (auto ok = (*world)->updateVertices(*id, next); !ok) die(ok.error().message());
                times.push_back(msSince(t0));
                if (world_threads != threads) continue;
                const auto t1 = Clock::now();
                if (auto s = (*world)->resolveSettings(); !s) die(s.error().message());
                resolve.push_back(msSince(t1));
            }
            const char* name = world_threads == threads ? "update" : "update-1t";
            std::printf("%s,-,%zu,%zu,%d,%.3f,%.3f,,,,,,,%s\n", name, big.triangleCount(), big.positions.size(), frames, median(times),
                        median(times) * 1e6 / n, device.c_str());
            if (!resolve.empty())
                std::printf("update-resolve,-,%zu,%zu,%d,%.3f,%.3f,,,,,,,%s\n", big.triangleCount(), big.positions.size(), frames,
                            median(resolve), median(resolve) * 1e6 / n, device.c_str());
        }
        updateParts(ContextAccess::device(**ctx), big, frames, threads == 0 ? std::thread::hardware_concurrency() : threads, device);
    }
    {  // A deforming pair's frame on the host: both meshes updated, then the settings resolved.
        const HostMesh a = sphere(1.0f, 2 * vertices), b = sphere(0.8f, 2 * vertices);
        auto world = CollisionWorld::create(**ctx, {.threads = threads});
        if (!world) die(world.error().message());
        auto ia = (*world)->addMesh(a, {.name = "a"});
        auto ib = (*world)->addMesh(b, {.name = "b"});
        if (!ia || !ib) die((ia ? ib : ia).error().message());
        std::vector<Float3> pa, pb;
        std::vector<double> times;
        for (int f = 0; f < frames; ++f) {
            pose(a, f, -0.8f, pa);
            pose(b, f, 0.8f, pb);
            // Idle first, as during a detection's GPU wait: the executor's threads stop polling and sleep.
            std::this_thread::sleep_for(std::chrono::microseconds(500));
            const auto t0 = Clock::now();
            if (auto ok = (*world)->updateVertices(*ia, pa); !ok) die(ok.error().message());
            if (auto ok = (*world)->updateVertices(*ib, pb); !ok) die(ok.error().message());
            if (auto r = (*world)->resolveSettings(); !r) die(r.error().message());
            times.push_back(msSince(t0));
        }
        const double n = double(a.positions.size() + b.positions.size());
        std::printf("update-pair-idle,-,%zu,%zu,%d,%.3f,%.3f,,,,,,,%s\n", a.triangleCount() + b.triangleCount(), a.positions.size() + b.positions.size(),
                    frames, median(times), median(times) * 1e6 / n, device.c_str());
    }

    const HostMesh a = sphere(1.0f, triangles), b = sphere(0.8f, triangles);
    for (const std::string& method : methods) {
        if (method == "none") continue;
        DetectSettings settings;
        settings.method = method == "peeling" ? DetectMethod::Peeling : DetectMethod::Reliable;
        for (const char* mode : {"detect", "submit", "pipelined", "alternating"}) {
            auto world = CollisionWorld::create(**ctx, {.threads = threads});
            if (!world) die(world.error().message());
            CollisionWorld& w = **world;
            EngineMesh ea = engineMesh(ContextAccess::device(**ctx), a), eb = engineMesh(ContextAccess::device(**ctx), b);
            auto ia = w.addGpuMesh(ea.desc(0), {.name = "a"});
            auto ib = w.addGpuMesh(eb.desc(0), {.name = "b"});
            if (!ia || !ib) die((ia ? ib : ia).error().message());
            std::vector<Float3> pa, pb;
            std::vector<double> frame_ms, gpu_ms, narrow_ms, total_ms, readback_ms;
            std::size_t pairs = 0;
            const bool pipelined = std::string(mode) == "pipelined";
            const bool alternating = std::string(mode) == "alternating";
            std::vector<double> submit_frame_ms;  // alternating: the submit() + collect() frames
            auto record = [&](const Result<DetectResult>& r, double ms) {
                if (!r) die(r.error().message());
                frame_ms.push_back(ms);
                gpu_ms.push_back(r->stats.sampling_ms + r->stats.peeling.merging_ms + r->stats.peeling.separation_ms + r->stats.peeling.packing_ms +
                                 r->stats.reliable.footprints_ms + r->stats.reliable.pairing_ms + r->stats.reliable.filtering_ms);
                narrow_ms.push_back(r->stats.narrow_ms);
                total_ms.push_back(r->stats.total_ms);
                readback_ms.push_back(r->stats.readback_ms);
                pairs = r->pairs.size();
            };
            // Frame `f`'s poses written by the host into vertex buffer `buffer` of both meshes.
            auto writeFrame = [&](int f, int buffer) {
                pose(a, f, -0.8f, pa);
                pose(b, f, 0.8f, pb);
                std::memcpy(ea.vertices[buffer].mapped(), pa.data(), pa.size() * sizeof(Float3));
                std::memcpy(eb.vertices[buffer].mapped(), pb.data(), pb.size() * sizeof(Float3));
                ea.vertices[buffer].flush();
                eb.vertices[buffer].flush();
                if (auto ok = w.setGpuMeshBuffers(*ia, ea.desc(buffer)); !ok) die(ok.error().message());
                if (auto ok = w.setGpuMeshBuffers(*ib, eb.desc(buffer)); !ok) die(ok.error().message());
            };
            // The GPU's clocks drop while it idles (building this world): detect until it
            // has been busy for --warmup-ms, so every mode starts at the same clocks.
            writeFrame(0, 1);
            for (const auto w0 = Clock::now(); msSince(w0) < warmup_ms;)
                if (!w.detect(settings)) break;
            for (int f = 0; f < frames + 2; ++f) {
                const auto t0 = Clock::now();
                // Buffer f % 2: the detection that read it (frame f - 2) has been collected.
                writeFrame(f, f % 2);
                Result<DetectResult> r = Error(ErrorCode::InvalidArgument, "none");
                const bool by_submit = alternating && f % 2 == 1;
                if (std::string(mode) == "detect" || (alternating && !by_submit)) {
                    r = w.detect(settings);
                } else {
                    if (auto ok = w.submit(settings); !ok) die(ok.error().message());
                    if (pipelined && f == 0) continue;
                    r = w.collect();
                }
                if (f >= 2 && by_submit) {
                    if (!r) die(r.error().message());
                    submit_frame_ms.push_back(msSince(t0));
                } else if (f >= 2) {
                    record(r, msSince(t0));
                }
            }
            if (pipelined) (void)w.collect();
            if (alternating) {  // the same world and clocks, detect() and submit() + collect() frame by frame
                std::printf("detect-alternating,%s,%zu,,%zu,,,%.3f,,,,,%zu,%s\n", method.c_str(), a.triangleCount() + b.triangleCount(),
                            frame_ms.size(), median(frame_ms), pairs, device.c_str());
                std::printf("submit-alternating,%s,%zu,,%zu,,,%.3f,,,,,%zu,%s\n", method.c_str(), a.triangleCount() + b.triangleCount(),
                            submit_frame_ms.size(), median(submit_frame_ms), pairs, device.c_str());
                continue;
            }
            std::printf("%s,%s,%zu,,%d,,,%.3f,%.3f,%.3f,%.3f,%.3f,%zu,%s\n", mode, method.c_str(), a.triangleCount() + b.triangleCount(),
                        frames, median(frame_ms), median(gpu_ms), median(readback_ms), median(narrow_ms), median(total_ms), pairs,
                        device.c_str());
        }
    }
    return 0;
}
