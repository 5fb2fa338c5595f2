#include "cli/detect.hpp"

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/devices.hpp"
#include "cli/picture.hpp"
#include "cli/report.hpp"
#include "cli/scene.hpp"
#include "render/output.hpp"
#include "vkcollide/world.hpp"

namespace cli {
namespace {

using Clock = std::chrono::steady_clock;

int fail(const std::string& what) {
    std::fprintf(stderr, "vkcollide: %s\n", what.c_str());
    return 1;
}

// "1 object", "2 objects".
std::string counted(std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// Which objects test their own triangles (ObjectOptions::self_collision; off unless --self).
std::string selfCollision(const Scene& scene) {
    std::size_t on = 0;
    for (const SceneObject& o : scene.objects) on += o.options.self_collision ? 1 : 0;
    if (on == 0) return "self-collision off (--self FILES turns it on)";
    if (on == scene.objects.size()) return "self-collision on for every object";
    return "self-collision on for " + counted(on, "object", "objects");
}

// The reliable method: where the pairs were decided, sorted and their responses computed
// (DetectStats: gpu_exact_tests, cpu_exact_tests, reliable.*), with the GPU's sorting time.
std::string whereDecided(const vkcollide::DetectStats& st) {
    std::string out = "exact decision: ";
    if (st.gpu_exact_tests > 0 || st.cpu_exact_tests == 0) out += "GPU (" + counted(st.gpu_exact_tests, "test", "tests") + ")";
    if (st.cpu_exact_tests > 0) out += std::string(st.gpu_exact_tests > 0 ? " and " : "") + "CPU (" + counted(st.cpu_exact_tests, "test", "tests") + ")";
    const vkcollide::ReliableStats& rs = st.reliable;
    out += "; pairs sorted ";
    out += rs.pairs_sorted_in_one_pass ? "in one GPU pass" : rs.pairs_sorted_on_gpu ? "on the GPU" : "on the host";
    out += std::string(", responses computed ") + (rs.responses_on_gpu ? "on the GPU" : "on the host");
    if (rs.sorting_ms > 0) {
        char ms[32];
        std::snprintf(ms, sizeof ms, "%.3f", rs.sorting_ms);
        out += std::string(" (GPU sorting ") + ms + " ms)";
    }
    return out;
}

void printSummary(const std::string& device, const Scene& scene, const vkcollide::DetectResult& r) {
    const vkcollide::DetectStats& st = r.stats;
    std::printf("device: %s\n", device.c_str());
    const std::string objects = counted(scene.objects.size(), "object", "objects") + ", " + counted(st.triangles, "triangle", "triangles") +
                                ", " + selfCollision(scene);
    if (st.method == vkcollide::DetectMethod::Reliable) {
        std::printf("scene: %s; method reliable, %u cells per side, %s, %s, %llu read back\n", objects.c_str(), st.resolution,
                    counted(st.cells.entries, "footprint", "footprints").c_str(),
                    counted(st.cells.candidates, "candidate pair", "candidate pairs").c_str(),
                    static_cast<unsigned long long>(st.cells.survivors));
        if (!st.settings_note.empty()) std::printf("automatic settings: %s\n", st.settings_note.c_str());
    } else {
        std::printf("scene: %s; method peeling, resolution %u, depth complexity %u, %s in %s%s%s\n", objects.c_str(), st.resolution,
                    st.peeling.depth_complexity, counted(st.peeling.layers, "layer", "layers").c_str(), counted(st.peeling.peel_passes, "pass", "passes").c_str(),
                    st.peeling.dual ? " (dual)" : "", st.peeling.axes > 1 ? ", 3 directions" : "");
        if (!st.settings_note.empty()) std::printf("automatic settings: %s\n", st.settings_note.c_str());
        std::printf("sampling backend: %s (%s), coverage %s\n", vkcollide::toString(st.peeling.backend), st.peeling.backend_reason.c_str(),
                    vkcollide::toString(st.peeling.coverage));
    }
    std::printf("Table 1: # tri's %zu | # coll. rays %zu | # tri's downl. %zu | # pot. coll. tri's %zu | # tri-tri tests %zu | # pos. tests %zu\n",
                st.triangles, st.collision_rays, st.triangles_downloaded, st.potentially_colliding_triangles, st.triangle_tests,
                st.positive_tests);
    std::printf("colliding triangle pairs: %zu\n", r.pairs.size());
    if (st.method == vkcollide::DetectMethod::Reliable) std::printf("%s\n", whereDecided(st).c_str());
    for (const vkcollide::ObjectContact& c : r.contacts)
        std::printf("contact %s - %s: volume %.6g, normal (%.4f, %.4f, %.4f), depth %.6g, at (%.6g, %.6g, %.6g)%s\n",
                    scene.objects.at(c.object_a).options.name.c_str(), scene.objects.at(c.object_b).options.name.c_str(), c.volume,
                    c.normal.x, c.normal.y, c.normal.z, c.depth, c.point.x, c.point.y, c.point.z, c.contained ? ", contained" : "");
    if (st.contacts.rays_x)
        std::printf("contacts: %u x %u rays, %u candidate object pairs, %.3f ms (GPU %.3f)\n", st.contacts.rays_x, st.contacts.rays_y,
                    st.contacts.candidate_pairs, st.contacts.host_ms, st.contacts.gpu_ms);
    if (st.peeling.deep_rays) std::printf("deep rays (more surfaces than the peeling range, collision rays without peeling): %u\n", st.peeling.deep_rays);
    if (r.incomplete) std::printf("incomplete: %s\n", r.incomplete->message().c_str());
    for (const vkcollide::ExcludedObject& e : r.excluded) std::printf("excluded: %s\n", e.error.message().c_str());
    // The GPU figure is the method's own stages (render::gpuMs, as in the lines and --csv).
    const std::string threads = counted(st.host.narrow_threads, "thread", "threads");
    if (st.method == vkcollide::DetectMethod::Reliable)
        std::printf(
            "times (ms): GPU %.3f = front %.3f + footprints %.3f + pairing %.3f + filtering %.3f; readback %.3f, narrow phase %.3f (%s), "
            "total %.3f\n",
            render::gpuMs(st), st.sampling_ms, st.reliable.footprints_ms, st.reliable.pairing_ms, st.reliable.filtering_ms, st.readback_ms, st.narrow_ms,
            threads.c_str(), st.total_ms);
    else
        std::printf(
            "times (ms): GPU %.3f = sampling %.3f + merging %.3f + separation %.3f, packing %.3f (GPU); readback %.3f, narrow phase "
            "%.3f (%s), total %.3f\n",
            render::gpuMs(st), st.sampling_ms, st.peeling.merging_ms, st.peeling.separation_ms, st.peeling.packing_ms, st.readback_ms, st.narrow_ms,
            threads.c_str(), st.total_ms);
    std::printf("GPU memory: %.1f MiB\n", static_cast<double>(st.gpu_memory_bytes) / (1024.0 * 1024.0));
}

}  // namespace

int runDetect(const CommandLine& line) {
    render::setProgramName("vkcollide");
    auto scene = readScene(line);
    if (!scene) return fail(scene.error().message());
    bool gpu_meshes = false;
    for (const SceneObject& o : scene->objects) gpu_meshes = gpu_meshes || o.gpu_mesh;

    auto devices = openDevices(line, gpu_meshes, !line.png_path.empty());
    if (!devices) return fail(devices.error().message());
    vkcollide::Context& context = *devices->context;
    const std::string device = context.deviceInfo().name;
    std::unique_ptr<EngineMeshes> engine_meshes;
    if (gpu_meshes) engine_meshes = std::make_unique<EngineMeshes>(*devices->engine);

    auto world = vkcollide::CollisionWorld::create(context, {.threads = line.threads});
    if (!world) return fail(world.error().message());
    std::vector<vkcollide::ObjectId> ids;
    std::vector<std::size_t> engine_index(scene->objects.size(), 0);  // per --gpu-mesh object: its EngineMeshes index
    std::size_t engine_count = 0;
    for (std::size_t i = 0; i < scene->objects.size(); ++i) {
        const SceneObject& o = scene->objects[i];
        vkcollide::Result<vkcollide::ObjectId> id = vkcollide::ObjectId{0};
        if (o.gpu_mesh) {
            engine_index[i] = engine_count++;
            id = (*world)->addGpuMesh(engine_meshes->add(o.mesh), o.options);
        } else {
            id = (*world)->addMesh(o.mesh, o.options);
        }
        if (!id) return fail(id.error().message());
        ids.push_back(*id);
    }
    auto used = (*world)->resolveSettings(line.settings);
    if (!used) return fail(nameSettingOptions(line, used.error().message()));

    auto report = Report::open(line, *scene, device, *used);
    if (!report) return fail(report.error().message());
    std::optional<Picture> picture;
    if (!line.png_path.empty()) picture.emplace(*devices->engine, line, *scene, engine_meshes.get());
    // The per-frame lines, progress line and CSV (as the samples write them). FrameLog ends
    // the program on a file it cannot write; the tool names its option first.
    if (!line.csv_path.empty()) {
        std::FILE* probe = std::fopen(line.csv_path.c_str(), "w");
        if (!probe) return fail("--csv: cannot write " + line.csv_path);
        std::fclose(probe);
    }
    std::optional<render::FrameLog> log;
    const std::size_t frames = line.frameCount();
    if (line.sequence || !line.csv_path.empty())
        log.emplace(line.csv_path, std::vector<std::string>{}, static_cast<int>(frames), line.quiet,
                    render::HostTimeColumns{"read_ms", "png_ms"});
    if (line.sequence)
        std::printf("device: %s\nsequence: %s of %s, %s, %s\n", device.c_str(), counted(frames, "frame", "frames").c_str(),
                    counted(scene->objects.size(), "object", "objects").c_str(), counted(scene->triangles, "triangle", "triangles").c_str(),
                    selfCollision(*scene).c_str());

    vkcollide::Result<vkcollide::DetectResult> result = vkcollide::Error(vkcollide::ErrorCode::InvalidArgument, "no frames");
    std::size_t total_pairs = 0;
    std::vector<std::string> warned;
    for (std::size_t f = 0; f < frames; ++f) {
        const auto read_start = Clock::now();
        if (line.sequence && f > 0) {
            if (auto ok = readFrame(line, f, *scene); !ok) return fail(ok.error().message());
            for (std::size_t i = 0; i < scene->objects.size(); ++i) {
                const SceneObject& o = scene->objects[i];
                if (o.gpu_mesh) engine_meshes->update(engine_index[i], o.mesh.positions);
                else if (auto ok = (*world)->updateVertices(ids[i], o.mesh.positions); !ok) return fail(ok.error().message());
            }
        }
        const double read_ms = render::msSince(read_start);
        // --rays: the frames that are drawn also return where their collision rays were.
        vkcollide::DetectSettings frame_settings = line.settings;
        frame_settings.peeling.collision_rays = line.rays && picture && (line.sequence || f + 1 == frames);
        result = (*world)->detect(frame_settings);
        if (!result) return fail(nameSettingOptions(line, result.error().message()));
        total_pairs += result->pairs.size();
        // Closed objects that are inside out or holed: said once, and again when that changes.
        std::vector<std::string> warnings;
        for (const vkcollide::MeshWarning& w : result->stats.mesh_warnings) warnings.push_back(w.message);
        if (warnings != warned)
            for (const std::string& w : warnings) std::fprintf(stderr, "vkcollide: warning: frame %zu: %s\n", f, w.c_str());
        warned = std::move(warnings);
        const bool last = f + 1 == frames;
        double png_ms = 0;
        if (picture && (line.sequence || last)) {
            const auto png_start = Clock::now();
            const vkcollide::CollisionRays* rays = result->collision_rays ? &*result->collision_rays : nullptr;
            const std::string path = line.sequence ? Picture::framePath(line.png_path, f) : line.png_path;
            if (auto ok = picture->write(path, *scene, *result, rays); !ok) return fail(ok.error().message());
            png_ms = render::msSince(png_start);
            if (!line.sequence)
                std::printf("png: %s%s\n", path.c_str(),
                            rays ? (" (" + counted(rays->segments.size(), "collision ray", "collision rays") + " drawn)").c_str() : "");
        }
        if (log) log->record(static_cast<int>(f), *result, {}, read_ms, png_ms);
        if (line.sequence || last) (*report)->frame(f, *scene, *result);
    }
    if (auto ok = (*report)->close(); !ok) return fail(ok.error().message());
    if (!line.stats_path.empty())
        if (auto ok = writeStatsFile(line.stats_path, *scene, *result); !ok) return fail(ok.error().message());

    if (line.sequence) {
        log->finish("sequence");
        std::printf("colliding triangle pairs: %zu over %s, %zu in the last\n", total_pairs, counted(frames, "frame", "frames").c_str(),
                    result->pairs.size());
        if (picture)
            std::printf("png: %s ... %s\n", Picture::framePath(line.png_path, 0).c_str(), Picture::framePath(line.png_path, frames - 1).c_str());
    } else {
        if (log) log->finish("scene");
        printSummary(device, *scene, *result);
    }
    if (line.validation && devices->messages() > 0) {
        std::fprintf(stderr, "vkcollide: %s (see above)\n",
                     counted(devices->messages(), "validation or library message", "validation or library messages").c_str());
        return 3;
    }
    return 0;
}

}  // namespace cli
