// vkcollide command-line tool.
//   vkcollide info                       list the Vulkan devices and what each supports or lacks
//   vkcollide detect SCENE... [options]  find the intersecting triangle pairs of the scene
//
// detect reads Wavefront OBJ, OFF and PLY files; each OBJ `o`/`g` group, or each OFF/PLY
// file, is one object, in command-line then file order. Triangles are numbered globally
// from 0 in that order. Pairs are written as CSV lines `a,b` (a < b, sorted).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "vkcollide/context.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

constexpr const char* kUsage =
    "usage: vkcollide info\n"
    "       vkcollide detect SCENE... [--method reliable|peeling] [--resolution N] [--pairs out.csv] [--stats out.json]\n"
    "                        [--direction x,y,z] [--cap L] [--dual] [--paper-packing] [--backend raster|compute|auto]\n"
    "                        [--no-self-collision] [--open] [--frames K] [--threads T] [--device NAME]\n"
    "                        [--no-robust-access]\n"
    "  SCENE: .obj (each o/g group is an object), .off or .ply (each file is an object)\n"
    "  --method M          reliable (default: every intersecting pair, cells and pairs on the GPU) or\n"
    "                      peeling (the paper's depth peeling; --cap, --dual, --paper-packing, --backend apply to it)\n"
    "  --resolution N      cells per side (reliable, any count up to 16384) or rays per image side (peeling, a\n"
    "                      power of two); default: chosen from the scene\n"
    "  --pairs FILE        write the colliding pairs as CSV lines a,b (global triangle indices, a<b)\n"
    "  --stats FILE        write the statistics (the paper's Table 1, settings, stage times) as JSON\n"
    "  --direction x,y,z   projection direction; default: the world axis most triangle area faces\n"
    "  --cap L             peel at most L layers (deeper rays count as colliding)\n"
    "  --dual              peel from the front and the back at once\n"
    "  --paper-packing     the paper's count/shift/move packing instead of the scan\n"
    "  --backend B         object sampling: raster, compute or auto (default: chosen per device and scene)\n"
    "  --no-self-collision skip pairs inside one object (default: tested)\n"
    "  --open              treat every object as an open surface\n"
    "  --frames K          run K detections (timings of the last; the first allocates)\n"
    "  --threads T         narrow-phase threads, 1 to 1024 (default: all hardware threads)\n"
    "  --device NAME       use the Vulkan device whose name contains NAME\n"
    "  --no-robust-access  create the device without robustBufferAccess(2), to measure its cost\n"
    "  -h, --help          print this help\n";

// More narrow-phase threads than any machine has cores for only costs memory and start-up
// time; an absurd count (4294967295) would not even fit the thread table.
constexpr std::uint32_t kMaxThreads = 1024;

int usage() {
    std::fputs(kUsage, stderr);
    return 2;
}

int help() {
    std::fputs(kUsage, stdout);
    return 0;
}

int fail(const std::string& what) {
    std::fprintf(stderr, "vkcollide: %s\n", what.c_str());
    return 1;
}

int info() {
    auto devices = Context::listDevices();
    if (!devices) return fail(devices.error().message());
    if (devices->empty()) std::printf("no Vulkan devices\n");
    for (const DeviceInfo& d : *devices) {
        std::printf("%s\n  type: %s\n  Vulkan %u.%u.%u, driver %s\n  timestamp period: %.3f ns, subgroup size: %u\n",
                    d.name.c_str(), toString(d.type), VK_API_VERSION_MAJOR(d.api_version), VK_API_VERSION_MINOR(d.api_version),
                    VK_API_VERSION_PATCH(d.api_version), d.driver.c_str(), d.timestamp_period_ns, d.subgroup_size);
        const auto yes = [](bool b) { return b ? "yes" : "no"; };
        std::printf("  optional: conservative rasterization %s, push descriptors %s, robustness2 %s, shaderFloat64 %s\n",
                    yes(d.conservative_rasterization), yes(d.push_descriptor), yes(d.robustness2), yes(d.shader_float64));
        if (d.missing.empty()) {
            std::printf("  usable by vkcollide: yes\n");
        } else {
            std::printf("  usable by vkcollide: no, lacks:");
            for (const auto& m : d.missing) std::printf(" %s", m.c_str());
            std::printf("\n");
        }
    }
    return 0;
}

bool parseUint(const char* s, std::uint32_t& out) {
    errno = 0;
    char* end = nullptr;
    const unsigned long v = std::strtoul(s, &end, 10);
    if (errno || end == s || *end || v > 0xFFFFFFFFul || s[0] == '-') return false;
    out = static_cast<std::uint32_t>(v);
    return true;
}

bool parseDirection(const char* s, std::array<float, 3>& out) {
    char* end = nullptr;
    for (int i = 0; i < 3; ++i) {
        out[i] = std::strtof(s, &end);
        if (end == s) return false;
        s = end;
        if (i < 2) {
            if (*s != ',') return false;
            ++s;
        }
    }
    return *s == '\0';
}

std::string jsonEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\', o += c;
        else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
        else o += c;
    }
    return o;
}

std::string statsJson(const DetectStats& st, const std::vector<std::string>& names, std::size_t pairs) {
    std::string j = "{\n";
    auto num = [&](const char* k, double v, bool last = false) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "  \"%s\": %.17g%s\n", k, v, last ? "" : ",");
        j += buf;
    };
    j += "  \"objects\": [";
    for (std::size_t i = 0; i < names.size(); ++i) j += (i ? ", \"" : "\"") + jsonEscape(names[i]) + "\"";
    j += "],\n";
    num("triangles", double(st.triangles));
    num("collision_rays", double(st.collision_rays));
    num("triangles_downloaded", double(st.triangles_downloaded));
    num("potentially_colliding_triangles", double(st.potentially_colliding_triangles));
    num("triangle_tests", double(st.triangle_tests));
    num("positive_tests", double(st.positive_tests));
    num("pairs", double(pairs));
    j += "  \"method\": \"" + std::string(toString(st.method)) + "\",\n";
    num("resolution", st.resolution);
    j += "  \"direction\": [" + std::to_string(st.direction[0]) + ", " + std::to_string(st.direction[1]) + ", " +
         std::to_string(st.direction[2]) + "],\n";
    num("depth_complexity", st.depth_complexity);
    num("layers", st.layers);
    num("peel_passes", st.peel_passes);
    j += std::string("  \"dual\": ") + (st.dual ? "true" : "false") + ",\n";
    j += "  \"backend\": \"" + std::string(toString(st.backend)) + "\",\n";
    j += "  \"backend_reason\": \"" + jsonEscape(st.backend_reason) + "\",\n";
    j += "  \"settings_note\": \"" + jsonEscape(st.settings_note) + "\",\n";
    num("sampling_ms", st.sampling_ms);
    num("merging_ms", st.merging_ms);
    num("separation_ms", st.separation_ms);
    num("packing_ms", st.packing_ms);
    num("footprints_ms", st.footprints_ms);
    num("pairing_ms", st.pairing_ms);
    num("filtering_ms", st.filtering_ms);
    num("cell_entries", double(st.cells.entries));
    num("cell_candidates", double(st.cells.candidates));
    num("cell_survivors", double(st.cells.survivors));
    num("readback_ms", st.readback_ms);
    num("narrow_ms", st.narrow_ms);
    num("narrow_threads", st.narrow_threads);
    num("total_ms", st.total_ms);
    j += "  \"gpu_passes\": [";
    for (std::size_t i = 0; i < st.gpu_passes.size(); ++i) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s{\"name\": \"%s\", \"gpu_ms\": %.6f}", i ? ", " : "", jsonEscape(st.gpu_passes[i].name).c_str(),
                      st.gpu_passes[i].gpu_ms);
        j += buf;
    }
    j += "]\n}\n";
    return j;
}

bool writeFile(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    return static_cast<bool>(f.flush());
}

int detect(int argc, char** argv) {
    std::vector<std::string> files;
    DetectSettings settings;
    std::string pairs_path, stats_path, device;
    bool self_collision = true, open = false, robust_access = true;
    std::uint32_t frames = 1, threads = 0;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        std::uint32_t u = 0;
        if (a == "--method") {
            const char* v = value();
            const std::string m = v ? v : "";
            if (m == "reliable") settings.method = DetectMethod::Reliable;
            else if (m == "peeling") settings.method = DetectMethod::Peeling;
            else return fail("--method needs reliable or peeling");
        } else if (a == "--resolution") {
            const char* v = value();
            if (!v || !parseUint(v, u)) return fail("--resolution needs a number");
            settings.resolution = u;
        } else if (a == "--pairs") {
            const char* v = value();
            if (!v) return fail("--pairs needs a file");
            pairs_path = v;
        } else if (a == "--stats") {
            const char* v = value();
            if (!v) return fail("--stats needs a file");
            stats_path = v;
        } else if (a == "--direction") {
            const char* v = value();
            std::array<float, 3> d{};
            if (!v || !parseDirection(v, d)) return fail("--direction needs x,y,z");
            settings.direction = d;
        } else if (a == "--cap") {
            const char* v = value();
            if (!v || !parseUint(v, u)) return fail("--cap needs a number");
            settings.layer_cap = u;
        } else if (a == "--frames") {
            const char* v = value();
            if (!v || !parseUint(v, frames) || frames == 0) return fail("--frames needs a positive number");
        } else if (a == "--threads") {
            const char* v = value();
            if (!v || !parseUint(v, threads) || threads == 0 || threads > kMaxThreads)
                return fail("--threads needs a number from 1 to " + std::to_string(kMaxThreads) +
                            " (leave it out to use every hardware thread)");
        } else if (a == "--device") {
            const char* v = value();
            if (!v) return fail("--device needs a name");
            device = v;
        } else if (a == "--backend") {
            const char* v = value();
            const std::string b = v ? v : "";
            if (b == "raster") settings.backend = SamplingBackend::Raster;
            else if (b == "compute") settings.backend = SamplingBackend::Compute;
            else if (b == "auto") settings.backend = SamplingBackend::Auto;
            else return fail("--backend needs raster, compute or auto");
        } else if (a == "--help" || a == "-h") {
            return help();
        } else if (a == "--dual") {
            settings.dual = true;
        } else if (a == "--paper-packing") {
            settings.packing = PackingMethod::Paper;
        } else if (a == "--no-self-collision") {
            self_collision = false;
        } else if (a == "--open") {
            open = true;
        } else if (a == "--no-robust-access") {
            robust_access = false;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "vkcollide: unknown option %s\n", a.c_str());
            return usage();
        } else {
            files.push_back(a);
        }
    }
    if (files.empty()) {
        std::fprintf(stderr, "vkcollide: detect needs at least one scene file\n");
        return usage();
    }

    std::vector<HostMesh> meshes;
    for (const std::string& f : files) {
        auto m = readMeshFile(f);
        if (!m) return fail(m.error().message());
        for (HostMesh& h : *m) meshes.push_back(std::move(h));
    }
    ContextCreateInfo ci;
    ci.device_name = device;
    ci.robust_buffer_access = robust_access;
    auto ctx = Context::create(ci);
    if (!ctx) return fail(ctx.error().message());
    auto world = CollisionWorld::create(**ctx, {.threads = threads});
    if (!world) return fail(world.error().message());
    std::vector<std::uint64_t> base;  // global index of each object's triangle 0
    std::vector<std::string> names;
    std::uint64_t total = 0;
    for (const HostMesh& m : meshes) {
        ObjectOptions o;
        o.name = m.name;
        o.self_collision = self_collision;
        o.open = open;
        auto id = (*world)->addMesh(m, o);
        if (!id) return fail(id.error().message());
        base.push_back(total);
        names.push_back(m.name);
        total += m.triangleCount();
    }
    Result<DetectResult> result = Error(ErrorCode::InvalidArgument, "no frames");
    for (std::uint32_t f = 0; f < frames; ++f) {
        result = (*world)->detect(settings);
        if (!result) return fail(result.error().message());
    }
    const DetectStats& st = result->stats;
    std::printf("device: %s\n", (*ctx)->deviceInfo().name.c_str());
    const bool reliable = st.method == DetectMethod::Reliable;
    if (reliable)
        std::printf("scene: %zu objects, %zu triangles; method reliable, %u cells per side, %llu footprints, %llu candidate pairs, %llu read back\n",
                    meshes.size(), st.triangles, st.resolution, (unsigned long long)st.cells.entries, (unsigned long long)st.cells.candidates,
                    (unsigned long long)st.cells.survivors);
    else
        std::printf("scene: %zu objects, %zu triangles; method peeling, resolution %u, depth complexity %u, %u layers in %u passes%s\n",
                    meshes.size(), st.triangles, st.resolution, st.depth_complexity, st.layers, st.peel_passes, st.dual ? " (dual)" : "");
    if (!st.settings_note.empty()) std::printf("automatic settings: %s\n", st.settings_note.c_str());
    if (!reliable) std::printf("sampling backend: %s (%s)\n", toString(st.backend), st.backend_reason.c_str());
    std::printf("Table 1: # tri's %zu | # coll. rays %zu | # tri's downl. %zu | # pot. coll. tri's %zu | # tri-tri tests %zu | # pos. tests %zu\n",
                st.triangles, st.collision_rays, st.triangles_downloaded, st.potentially_colliding_triangles, st.triangle_tests,
                st.positive_tests);
    std::printf("colliding triangle pairs: %zu\n", result->pairs.size());
    if (reliable)
        std::printf("times (ms): front %.3f, footprints %.3f, pairing %.3f, filtering %.3f (GPU); readback %.3f, narrow phase %.3f (%u threads), total %.3f\n",
                    st.sampling_ms, st.footprints_ms, st.pairing_ms, st.filtering_ms, st.readback_ms, st.narrow_ms, st.narrow_threads,
                    st.total_ms);
    else
        std::printf("times (ms): sampling %.3f, merging %.3f, separation %.3f, packing %.3f (GPU); readback %.3f, narrow phase %.3f (%u threads), total %.3f\n",
                    st.sampling_ms, st.merging_ms, st.separation_ms, st.packing_ms, st.readback_ms, st.narrow_ms, st.narrow_threads,
                    st.total_ms);
    if (!pairs_path.empty()) {
        std::string csv;
        csv.reserve(result->pairs.size() * 16);
        for (const TrianglePair& p : result->pairs) {
            // (object, triangle) order equals global order: the lower one comes first.
            csv += std::to_string(base[p.object_a] + p.triangle_a) + "," + std::to_string(base[p.object_b] + p.triangle_b) + "\n";
        }
        if (!writeFile(pairs_path, csv)) return fail("cannot write " + pairs_path);
    }
    if (!stats_path.empty() && !writeFile(stats_path, statsJson(st, names, result->pairs.size())))
        return fail("cannot write " + stats_path);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    if (std::strcmp(argv[1], "info") == 0) return info();
    if (std::strcmp(argv[1], "detect") == 0) return detect(argc, argv);
    if (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) return help();
    return usage();
}
