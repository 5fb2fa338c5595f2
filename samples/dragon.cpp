// Large meshes (paper section 8, last example of Figure 10): a dragon of about 800K
// triangles with a bunny passing through it.
//
// The CGAL data has no dragon that large: its ChineseDragon-10kv (20K triangles, six
// boundary edges) is closed (closeHoles) and subdivided (Loop, then sqrt(3) steps: the mix
// closest to --triangles, 720K by default) and the bunny (75K) makes up the rest.
//
// What it shows: a big static mesh uploaded once, a small object moved by setTransform
// through it, and what the detection costs at this size (the Table 1 columns).
//
//   vkcollide_dragon [--frames 120] [--triangles 800000] [--passer-triangles 80000] [--out dragon] (--help)
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <cmath>
#include <cstdio>
#include <string>

#include "common/lent_device.hpp"
#include "common/meshes.hpp"
#include "common/options.hpp"
#include "common/physics.hpp"
#include "common/picture.hpp"
#include "common/render.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace samples;

int main(int argc, char** argv) {
    CommonOptions common;
    common.frames = 120;
    std::uint32_t triangles = 800000;         // subdivision target for the dragon
    std::uint32_t passer_triangles = 80000;   // the bunny (at most its 75K)
    Args args("vkcollide_dragon", "a bunny passes through a subdivided dragon (paper section 8)");
    args.option("triangles", triangles, "the dragon is subdivided to about this many triangles");
    args.option("passer-triangles", passer_triangles, "triangles of the bunny that passes through (simplified if fewer)");
    addCommonOptions(args, common);
    args.parse(argc, argv);
    finishCommonOptions(args, common, "dragon");

    // The engine's device, lent to vkcollide.
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;

    // The dragon: closed, subdivided, 4 units long; it never moves.
    constexpr float kSize = 4.0f;
    HostMesh dragon = loadSceneMesh(common, "ChineseDragon-10kv.off", StandIn::Ring, kSize);
    const std::size_t holes = closeHoles(dragon);
    std::string steps;
    dragon = subdivideTo(dragon, triangles, &steps);
    auto stats = computeMeshStats(dragon);
    if (!stats) return fail(stats.error());
    std::printf("dragon: %zu holes closed, subdivided (%s) to %zu triangles, %s\n", holes, steps.c_str(), dragon.triangleCount(),
                stats->closed ? "closed" : "not closed");
    auto dragon_id = world->addMesh(dragon, {.name = "dragon"});
    if (!dragon_id) return fail(dragon_id.error());

    // The bunny that passes through from side to side, just behind the dragon's front so
    // that it shows where it cuts the surface.
    const HostMesh bunny = simplifyMesh(loadSceneMesh(common, "bunny00.off", StandIn::Blob, 1.2f), passer_triangles);
    Vec3 lo = toVec(dragon.positions[0]), hi = lo;
    for (const Float3& p : dragon.positions) {
        lo = lo.cwiseMin(toVec(p));
        hi = hi.cwiseMax(toVec(p));
    }
    const Vec3 middle = (lo + hi) / 2;
    auto bunnyAt = [&](int frame) {
        RigidBody pose;
        const float s = common.frames > 1 ? float(frame) / float(common.frames - 1) : 0.5f;
        pose.position = middle + Vec3((s - 0.5f) * 1.2f * (hi.x() - lo.x() + 1.2f), 0.1f * (hi.y() - lo.y()), 0.25f * (hi.z() - lo.z()));
        pose.orientation = Eigen::AngleAxisf(2.0f * s, Vec3(0.3f, 1.0f, 0.2f).normalized());
        return pose.transform();
    };
    auto bunny_id = world->addMesh(bunny, {.name = "bunny", .transform = bunnyAt(0)});
    if (!bunny_id) return fail(bunny_id.error());
    std::printf("scene: %zu triangles\n", world->triangleCount());

    Renderer renderer(*engine, common.width, common.height);
    const DrawId dragon_draw = renderer.addMesh(dragon, objectColour(3));
    const DrawId bunny_draw = renderer.addMesh(bunny, objectColour(0));
    Picture picture(renderer, common, "dragon",
                    Camera{.eye = {middle.x() + 2.5f, middle.y() + 2.0f, middle.z() + 7.5f}, .target = toFloat3(middle)}, 0.8f);

    const DetectSettings settings = common.detectSettings();
    FrameLog log(common.out + "/frames.csv", {"dragon_bunny_pairs"}, common.frames, common.quiet);
    for (int frame = 0; frame < common.frames; ++frame) {
        const auto sim_start = std::chrono::steady_clock::now();
        const Transform3x4 pose = bunnyAt(frame);
        if (auto ok = world->setTransform(*bunny_id, pose); !ok) return fail(ok.error());
        renderer.setTransform(bunny_draw, pose);
        const double sim_ms = msSince(sim_start);

        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());

        const auto render_start = std::chrono::steady_clock::now();
        renderer.clearHighlights();
        for (const TrianglePair& p : hits->pairs) {  // the dragon was added first: always object a
            renderer.highlight(dragon_draw, p.triangle_a);
            renderer.highlight(bunny_draw, p.triangle_b);
        }
        picture.write(frame, *hits, "the bunny passes through the dragon");
        const double values[] = {double(hits->pairs.size())};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("dragon");
    return exitStatus(*engine);
}
