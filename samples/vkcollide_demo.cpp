// The main job: collision detection on a bundled, generated scene (two interpenetrating
// spheres, a torus threaded on a box, a separate sphere) on the device vkcollide finds
// (lavapipe where no GPU is present), through the public API. Prints the device, the
// paper's Table 1 statistics, each GPU pass's time and the narrow phase's time.
//   vkcollide_demo [--resolution N] [--dual] [--paper-packing] [--cap L] [--frames K] [--backend raster|compute|auto]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "vkcollide/context.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "vkcollide_demo: %s\n", what.c_str());
    return 1;
}

ObjectOptions placed(const char* name, float angle, Float3 t) {
    const float c = std::cos(angle), s = std::sin(angle);
    ObjectOptions o;
    o.name = name;
    o.transform = {c, 0, s, t.x, 0, 1, 0, t.y, -s, 0, c, t.z};
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    DetectSettings settings;
    settings.resolution = 512;
    settings.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    int frames = 2;  // the first allocates and warms the pipelines
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--resolution" && i + 1 < argc) settings.resolution = static_cast<std::uint32_t>(std::atoi(argv[++i]));
        else if (a == "--cap" && i + 1 < argc) settings.peeling.layer_cap = static_cast<std::uint32_t>(std::atoi(argv[++i]));
        else if (a == "--frames" && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
        else if (a == "--backend" && i + 1 < argc) {
            const std::string b = argv[++i];
            if (b == "raster") settings.peeling.backend = SamplingBackend::Raster;
            else if (b == "compute") settings.peeling.backend = SamplingBackend::Compute;
            else if (b == "auto") settings.peeling.backend = SamplingBackend::Auto;
            else return fail("--backend takes raster, compute or auto");
        } else if (a == "--dual") settings.peeling.dual = true;
        else if (a == "--paper-packing") settings.peeling.packing = PackingMethod::Paper;
        else return fail("unknown argument " + a + " (use --resolution N, --dual, --paper-packing, --cap L, --frames K, --backend B)");
    }

    auto ctx = Context::create();
    if (!ctx) return fail(ctx.error().message());
    const DeviceInfo& dev = (*ctx)->deviceInfo();
    std::printf("device: %s (%s), %s\n", dev.name.c_str(), toString(dev.type), dev.driver.c_str());
    auto world = CollisionWorld::create(**ctx);
    if (!world) return fail(world.error().message());

    struct Part {
        Result<HostMesh> mesh;
        ObjectOptions options;
    } parts[] = {{uvSphere(1.0f, 96, 48), placed("sphere-a", 0.3f, {-0.6f, 0.05f, 0.0f})},
                 {uvSphere(0.9f, 96, 48), placed("sphere-b", 0.7f, {0.55f, -0.1f, 0.2f})},
                 {torus(0.9f, 0.25f, 128, 32), placed("torus", 0.2f, {0.1f, 1.6f, 0.0f})},
                 {box({0.3f, 0.3f, 1.4f}, 16), placed("bar", 0.1f, {1.0f, 1.6f, 0.0f})},
                 {uvSphere(0.5f, 48, 24), placed("far sphere", 0.0f, {-2.2f, -1.5f, 0.0f})}};
    for (auto& p : parts) {
        if (!p.mesh) return fail(p.mesh.error().message());
        if (auto id = (*world)->addMesh(*p.mesh, p.options); !id) return fail(id.error().message());
    }

    Result<DetectResult> result = Error(ErrorCode::InvalidArgument, "no frames");
    for (int f = 0; f < frames; ++f)
        if (result = (*world)->detect(settings); !result) return fail(result.error().message());

    const DetectStats& st = result->stats;
    if (st.method == DetectMethod::Reliable) {
        std::printf("method: reliable (every intersecting pair; cells and pairs on the GPU)\n");
        std::printf("scene: %u objects, %zu triangles; %u cells per side, %llu footprints, %llu candidate pairs, %llu read back\n",
                    st.objects, st.triangles, st.resolution, static_cast<unsigned long long>(st.cells.entries),
                    static_cast<unsigned long long>(st.cells.candidates), static_cast<unsigned long long>(st.cells.survivors));
    } else {
        std::printf("method: peeling; sampling backend: %s (%s)\n", toString(st.peeling.backend), st.peeling.backend_reason.c_str());
        std::printf("scene: %u objects, %zu triangles; resolution %u, depth complexity %u, %u layers in %u peeling passes%s\n",
                    st.objects, st.triangles, st.resolution, st.peeling.depth_complexity, st.peeling.layers, st.peeling.peel_passes, st.peeling.dual ? " (dual)" : "");
    }
    std::printf("Table 1: # tri's %zu | # coll. rays %zu | # tri's downl. %zu | # pot. coll. tri's %zu | # tri-tri tests %zu | # pos. tests %zu\n",
                st.triangles, st.collision_rays, st.triangles_downloaded, st.potentially_colliding_triangles, st.triangle_tests,
                st.positive_tests);
    std::printf("colliding triangle pairs: %zu\n", result->pairs.size());
    std::printf("GPU passes (ms):");
    for (const auto& p : st.gpu_passes) std::printf(" %s %.3f;", p.name.c_str(), p.gpu_ms);
    if (st.method == DetectMethod::Reliable) {
        // Where the pairs were decided and sorted, and so what the host's part did.
        const char* sorted = st.reliable.pairs_sorted_in_one_pass ? "in one GPU pass" : st.reliable.pairs_sorted_on_gpu ? "on the GPU" : "on the host";
        const char* host = !st.reliable.pairs_sorted_on_gpu   ? "CPU narrow phase"
                           : st.reliable.responses_on_gpu ? "host naming and copying"
                                                          : "host naming and responses";
        std::printf("\nexact decision: %s; pairs sorted %s, responses computed %s\n", st.cpu_exact_tests > 0 ? "CPU" : "GPU", sorted,
                    st.reliable.responses_on_gpu ? "on the GPU" : "on the host");
        std::printf("stages (ms): footprints %.3f, pairing %.3f, filtering %.3f, sorting %.3f (GPU), readback %.3f, %s %.3f (%u thread%s), total %.3f\n",
                    st.reliable.footprints_ms, st.reliable.pairing_ms, st.reliable.filtering_ms, st.reliable.sorting_ms, st.readback_ms, host,
                    st.narrow_ms, st.host.narrow_threads, st.host.narrow_threads == 1 ? "" : "s", st.total_ms);
    } else
        std::printf("\nstages (ms): sampling %.3f, merging %.3f, separation %.3f, packing %.3f, readback %.3f, CPU narrow phase %.3f (%u thread%s), total %.3f\n",
                    st.sampling_ms, st.peeling.merging_ms, st.peeling.separation_ms, st.peeling.packing_ms, st.readback_ms, st.narrow_ms, st.host.narrow_threads,
                    st.host.narrow_threads == 1 ? "" : "s", st.total_ms);
    return result->pairs.empty() ? fail("expected collisions in the bundled scene, found none") : 0;
}
