// The main job: collision detection on a bundled, generated scene (two interpenetrating
// spheres, a torus threaded on a box, a separate sphere) on the device vkcollide finds
// (lavapipe where no GPU is present). Prints the device, the paper's Table 1 statistics,
// each GPU pass's time and the narrow phase's time.
//   vkcollide_demo [--resolution N] [--dual] [--paper-packing] [--cap L] [--backend raster|compute|auto]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "narrow/thread_pool.hpp"
#include "passes/broad_phase.hpp"
#include "passes/mesh_upload.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "vkcollide_demo: %s\n", what.c_str());
    return 1;
}

Result<HostMesh> moved(Result<HostMesh> mesh, float angle, Float3 t) {
    if (!mesh) return mesh;
    const float c = std::cos(angle), s = std::sin(angle);
    Transform3x4 tr = {c, 0, s, t.x, 0, 1, 0, t.y, -s, 0, c, t.z};
    if (auto ok = transformMesh(*mesh, tr); !ok) return ok.error();
    return mesh;
}

}  // namespace

int main(int argc, char** argv) {
    passes::BroadPhaseSettings settings;
    settings.resolution = 512;
    settings.direction = {0.15f, -0.2f, 1.0f};
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--resolution" && i + 1 < argc) settings.resolution = static_cast<std::uint32_t>(std::atoi(argv[++i]));
        else if (a == "--cap" && i + 1 < argc) settings.layer_cap = static_cast<std::uint32_t>(std::atoi(argv[++i]));
        else if (a == "--dual") settings.dual = true;
        else if (a == "--paper-packing") settings.packing = passes::PackingMethod::Paper;
        else if (a == "--backend" && i + 1 < argc) {
            const std::string b = argv[++i];
            if (b == "raster") settings.backend = passes::SamplingBackend::Raster;
            else if (b == "compute") settings.backend = passes::SamplingBackend::Compute;
            else if (b == "auto") settings.backend = passes::SamplingBackend::Auto;
            else return fail("unknown backend " + b + " (use raster, compute or auto)");
        } else return fail("unknown argument " + a + " (use --resolution N, --dual, --paper-packing, --cap L, --backend B)");
    }

    auto ctx = Context::create();
    if (!ctx) return fail(ctx.error().message());
    vk::Device& dev = (*ctx)->device();
    std::printf("device: %s (%s), %s\n", dev.info.name.c_str(), toString(dev.info.type), dev.info.driver.c_str());

    Result<HostMesh> parts[] = {moved(uvSphere(1.0f, 96, 48), 0.3f, {-0.6f, 0.05f, 0.0f}),
                                moved(uvSphere(0.9f, 96, 48), 0.7f, {0.55f, -0.1f, 0.2f}),
                                moved(torus(0.9f, 0.25f, 128, 32), 0.2f, {0.1f, 1.6f, 0.0f}),
                                moved(box({0.3f, 0.3f, 1.4f}, 16), 0.1f, {0.1f + 0.9f, 1.6f, 0.0f}),
                                moved(uvSphere(0.5f, 48, 24), 0.0f, {-2.2f, -1.5f, 0.0f})};
    std::vector<HostMesh> meshes;
    std::vector<const HostMesh*> mesh_ptrs;
    std::size_t triangles = 0;
    for (auto& p : parts) {
        if (!p) return fail(p.error().message());
        triangles += p->triangleCount();
        meshes.push_back(std::move(*p));
    }
    for (const HostMesh& m : meshes) mesh_ptrs.push_back(&m);
    // Upload: the broad phase reads GPU buffers (as it would an engine's vertex buffers).
    auto uploaded = passes::uploadMeshes(dev, mesh_ptrs);
    if (!uploaded) return fail(uploaded.error().message());
    const auto& gpu_meshes = uploaded->meshes;

    auto bp = passes::BroadPhase::create(dev);
    if (!bp) return fail(bp.error().message());
    auto broad = (*bp)->run(gpu_meshes, settings);  // first run: pipelines warm up, buffers allocated
    if (broad) broad = (*bp)->run(gpu_meshes, settings);
    if (!broad) return fail(broad.error().message());

    ThreadPool pool(0);
    NarrowOptions options;
    const auto t0 = std::chrono::steady_clock::now();
    auto narrow = runNarrowPhase(broad->records, options, pool);
    const double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!narrow) return fail(narrow.error().message());

    const auto& st = narrow->stats;
    std::printf("scene: %zu objects, %zu triangles; resolution %u, depth complexity %u, %u layers in %u peeling passes%s\n",
                meshes.size(), triangles, settings.resolution, broad->depth_complexity, broad->layers, broad->peel_steps,
                settings.dual ? " (dual)" : "");
    std::printf("Table 1: # tri's %zu | # coll. rays %u | # tri's downl. %zu | # pot. coll. tri's %zu | # tri-tri tests %zu | # pos. tests %zu\n",
                triangles, broad->collision_rays, broad->records.size(), st.potentially_colliding_triangles,
                st.triangle_tests, st.positive_tests);
    std::printf("sampling backend: %s (%s)\n", passes::toString(broad->backend), broad->backend_reason.c_str());
    std::printf("colliding triangle pairs: %zu\n", narrow->pairs.size());
    std::printf("GPU passes (ms):");
    for (const auto& p : broad->passes) std::printf(" %s %.3f;", p.name.c_str(), p.gpu_ms);
    std::printf("\nstages (ms): sampling %.3f, merging %.3f, separation %.3f, packing %.3f, readback %.3f, CPU narrow phase %.3f (%u threads)\n",
                broad->sampling_ms, broad->merging_ms, broad->separation_ms, broad->packing_ms, broad->readback_ms, cpu_ms,
                pool.threadCount());
    return narrow->pairs.empty() ? fail("expected collisions in the bundled scene, found none") : 0;
}
