// Deformable bodies (paper section 8, Figure 8): two bunnies and two horse-like animals
// (the CGAL camel and elephant) deformed by shape matching, thrown together, colliding
// with each other and themselves, pushed apart by the response vectors.
//
// What it shows: meshes whose vertices change every frame (updateVertices with world-space
// positions), self-collision on every object, and DetectResult::responses used directly:
// each colliding triangle's vertices are pushed along its response vector, which points
// out of the partner it touches (narrow.hpp). Shape matching then restores the shape.
//
//   vkcollide_deformable [--frames 240] [--bodies all|bunnies|horses] [--out deformable] (--help)
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/lent_device.hpp"
#include "common/meshes.hpp"
#include "common/options.hpp"
#include "common/physics.hpp"
#include "common/picture.hpp"
#include "common/render.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace samples;

int main(int argc, char** argv) {
    CommonOptions common;
    common.frames = 240;
    std::string which = "all";              // the paper's rows: "defo bunnies" (12K), "defo horses" (32K)
    std::uint32_t bunny_triangles = 6000;   // two bunnies: the paper's 12K
    std::uint32_t horse_triangles = 20000;  // camel 19.5K, elephant 5.5K (simplified if above)
    float distance = 1.8f;                  // start distance of each body from the middle
    float speed = 3.0f;                     // start speed towards the middle
    float stiffness = 0.5f, softness = 0.2f;
    float dt = 1.0f / 60.0f;
    Args args("vkcollide_deformable", "deformable bunnies, camel and elephant collide (paper section 8, Figure 8)");
    args.option("bodies", which, "all, bunnies (two bunnies) or horses (camel and elephant)");
    args.option("bunny-triangles", bunny_triangles, "triangles per bunny (the CGAL bunny simplified)");
    args.option("horse-triangles", horse_triangles, "at most this many triangles for the camel and the elephant");
    args.option("distance", distance, "start distance of each body from the middle");
    args.option("speed", speed, "start speed towards the middle");
    args.option("stiffness", stiffness, "shape matching: share of the way back to the shape per step, (0, 1]");
    args.option("softness", softness, "shape matching: share of linear (squash and stretch) deformation, [0, 1]");
    args.option("dt", dt, "simulated seconds per frame");
    addCommonOptions(args, common);
    args.parse(argc, argv);
    finishCommonOptions(args, common, "deformable");
    if (which != "all" && which != "bunnies" && which != "horses") die("--bodies takes all, bunnies or horses");

    // The engine's device, lent to vkcollide.
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;
    Renderer renderer(*engine, common.width, common.height);

    // The bodies, on a circle around the middle, each thrown on an arc that reaches the
    // middle in mid-air at the height it started from.
    struct Body {
        HostMesh mesh;  // rest shape (object space); the topology never changes
        std::string name;
        ObjectId id = 0;
        DrawId draw = 0;
        float push = 0;  // how far one response moves a vertex: a third of the mean edge
    };
    std::vector<Body> bodies;
    if (which != "horses") {
        const HostMesh bunny = simplifyMesh(loadSceneMesh(common, "bunny00.off", StandIn::Blob, 1.0f), bunny_triangles);
        bodies.push_back({bunny, "bunny 1"});
        bodies.push_back({bunny, "bunny 2"});
    }
    if (which != "bunnies") {
        bodies.push_back({simplifyMesh(loadSceneMesh(common, "camel.off", StandIn::Long, 1.6f), horse_triangles), "camel"});
        // The CGAL elephant leans back 31 degrees from +y: this up direction (the normal of
        // the plane its four soles touch) puts it on its feet.
        const Float3 elephant_up{-0.092f, 0.855f, 0.510f};
        bodies.push_back(
            {simplifyMesh(loadSceneMesh(common, "elephant.off", StandIn::Ring, 1.4f, elephant_up), horse_triangles), "elephant"});
    }
    std::vector<SoftBody> soft;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        const float angle = 6.2831853f * float(i) / float(bodies.size()) + 0.4f;
        const Vec3 start(distance * std::cos(angle), 1.0f + 0.15f * float(i), distance * std::sin(angle));
        soft.emplace_back(b.mesh.positions, start, stiffness, softness);
        const float flight = distance / speed;
        soft.back().setVelocity(Vec3(-std::cos(angle) * speed, 9.81f * flight / 2, -std::sin(angle) * speed));
        HostMesh placed = b.mesh;
        placed.positions = soft.back().positions();
        auto id = world->addMesh(placed, {.name = b.name, .self_collision = true});
        if (!id) return fail(id.error());
        b.id = *id;
        b.draw = renderer.addMesh(placed, objectColour(i), /*dynamic=*/true);
        double edges = 0;
        for (std::size_t t = 0; t < b.mesh.triangleCount(); ++t)
            edges += (toVec(b.mesh.positions[b.mesh.indices[t * 3]]) - toVec(b.mesh.positions[b.mesh.indices[t * 3 + 1]])).norm();
        b.push = static_cast<float>(edges / double(b.mesh.triangleCount())) / 3.0f;
        std::printf("%s: %zu triangles\n", b.name.c_str(), b.mesh.triangleCount());
    }
    auto bodyOf = [&](ObjectId id) {
        std::size_t i = 0;
        while (bodies[i].id != id) ++i;
        return i;
    };
    // The floor: drawn, not detected (the simulation keeps the bodies above y = 0).
    HostMesh floor;
    floor.positions = {{-6, -0.005f, -6}, {6, -0.005f, -6}, {6, -0.005f, 6}, {-6, -0.005f, 6}};
    floor.indices = {0, 2, 1, 0, 3, 2};
    renderer.addMesh(floor, objectColour(6));
    Picture picture(renderer, common, "deformable " + which, Camera{.eye = {1.5f, 3.5f, 6.5f}, .target = {0, 0.9f, 0}}, 0.8f);

    const DetectSettings settings = common.detectSettings();
    FrameLog log(common.out + "/frames.csv", {"mutual_pairs", "self_pairs", "centre_distance_01"}, common.frames, common.quiet);
    const Vec3 gravity(0, -9.81f, 0);
    for (int frame = 0; frame < common.frames; ++frame) {
        // Simulate (this applies last frame's collision pushes), then hand over the new shapes.
        const auto sim_start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            soft[i].step(dt, gravity, 0.0f);
            if (auto ok = world->updateVertices(bodies[i].id, soft[i].positions()); !ok) return fail(ok.error());
            renderer.updateVertices(bodies[i].draw, soft[i].positions());
        }
        double sim_ms = msSince(sim_start);

        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());

        // Response, locally: every vertex of a colliding triangle moves out along the
        // triangle's response vector (the step averages several pushes on one vertex).
        const auto response_start = std::chrono::steady_clock::now();
        for (const TriangleResponse& r : hits->responses) {
            Body& b = bodies[bodyOf(r.object)];
            for (int k = 0; k < 3; ++k)
                soft[bodyOf(r.object)].push(b.mesh.indices[r.triangle * 3 + k], toVec(r.direction), b.push);
        }
        // And for the whole body: two bodies that touch stop approaching each other along
        // the difference of their summed responses (each sum points out of the other).
        int mutual = 0, self = 0;
        std::vector<std::vector<Vec3>> apart(bodies.size(), std::vector<Vec3>(bodies.size(), Vec3::Zero()));
        renderer.clearHighlights();
        for (const TrianglePair& p : hits->pairs) {
            const std::size_t a = bodyOf(p.object_a), b = bodyOf(p.object_b);
            renderer.highlight(bodies[a].draw, p.triangle_a);
            renderer.highlight(bodies[b].draw, p.triangle_b);
            if (a == b) {
                ++self;
                continue;
            }
            ++mutual;
            if (const TriangleResponse* r = findResponse(hits->responses, p.object_a, p.triangle_a)) apart[a][b] += toVec(r->direction);
            if (const TriangleResponse* r = findResponse(hits->responses, p.object_b, p.triangle_b)) apart[b][a] += toVec(r->direction);
        }
        for (std::size_t a = 0; a < bodies.size(); ++a)
            for (std::size_t b = a + 1; b < bodies.size(); ++b) {
                const Vec3 n = apart[b][a] - apart[a][b];  // from a towards b
                if (n.norm() < 1e-6f) continue;
                const float closing = (soft[b].velocity() - soft[a].velocity()).dot(n.normalized());
                if (closing >= 0) continue;
                const Vec3 dv = -0.5f * (1 + 0.3f) * closing * n.normalized();  // equal masses, restitution 0.3
                soft[b].addVelocity(dv);
                soft[a].addVelocity(-dv);
            }
        sim_ms += msSince(response_start);

        const auto render_start = std::chrono::steady_clock::now();
        picture.write(frame, *hits, std::to_string(mutual) + " pairs between bodies, " + std::to_string(self) + " within one");
        const double values[] = {double(mutual), double(self), double((soft[0].centre() - soft[1].centre()).norm())};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("deformable " + which);
    return exitStatus(*engine);
}
