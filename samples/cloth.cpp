// Cloth (paper section 8.2, Figure 11): an open cloth patch of 2K triangles falls onto a
// sphere standing on the floor, drapes and folds onto itself.
//
// With --proximity the cloth is driven by proximity pairs instead (DetectSettings::proximity,
// docs/proximity.md): every cloth vertex and edge closer than twice the cloth's thickness
// to an obstacle or to another part of the cloth becomes a contact plane the next steps
// enforce, so surfaces are held apart before they meet; the sample counts the intersecting
// pairs vkcollide finds in the same detections and says whether any frame had one.
//
// What it shows: an open surface (ObjectOptions::open: collision rays come from two hits
// close in depth, not from inside/outside), self-collision, new vertices every frame
// (updateVertices), and a response built from the pairs themselves. The response vectors
// of DetectResult assume closed, outward-facing surfaces; a cloth has no outside, so the
// cloth is kept in front of the obstacle triangles it touches, and pushed back from a
// cloth triangle it touches to the side it came from.
//
// With --ball (cloth_ball.cpp) the scene is README's ball and cloth instead: a ball thrown
// onto a cloth pinned at its edges, the cloth stopping it through proximity pairs.
//
//   vkcollide_cloth [--frames 400] [--cells 32] [--drop 0.2] [--proximity | --ball] [--out cloth] (--help for all)
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <cmath>
#include <cstdio>
#include <vector>

#include "cloth_ball.hpp"
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

namespace {

Vec3 triangleNormal(const std::vector<Float3>& p, const std::vector<std::uint32_t>& idx, std::uint32_t t) {
    const Vec3 a = toVec(p[idx[t * 3]]), b = toVec(p[idx[t * 3 + 1]]), c = toVec(p[idx[t * 3 + 2]]);
    return (b - a).cross(c - a).normalized();
}

Vec3 triangleCentre(const std::vector<Float3>& p, const std::vector<std::uint32_t>& idx, std::uint32_t t) {
    return (toVec(p[idx[t * 3]]) + toVec(p[idx[t * 3 + 1]]) + toVec(p[idx[t * 3 + 2]])) / 3.0f;
}

}  // namespace

int main(int argc, char** argv) {
    CommonOptions common;
    common.frames = 400;
    std::uint32_t cells = 32;  // quads per side: 2 * 32 * 32 = 2048 triangles, the paper's 2K
    float drop = 0.2f;         // height of the cloth above the sphere's top at the start
    float size = 2.6f;         // cloth side; the sphere's radius is 0.5
    std::uint32_t substeps = 4;
    float fold = 1.6f;         // radians: the cloth starts folded over, one half above the other
    float dt = 0.005f;  // small: the cloth moves a fraction of an edge between detections
    bool proximity = false, ball = false;
    BallScene ball_scene;
    Args args("vkcollide_cloth", "an open cloth falls onto a sphere (paper section 8.2)");
    args.option("cells", cells, "cloth quads per side (2 triangles each)");
    args.option("drop", drop, "start height of the cloth above the sphere");
    args.option("size", size, "cloth side length (sphere radius 0.5)");
    args.option("substeps", substeps, "cloth simulation steps per frame");
    args.option("fold", fold, "how far one half of the cloth is turned over the other at the start, radians");
    args.option("dt", dt, "simulated seconds per frame (one detection per frame)");
    args.flag("proximity", proximity, "drive the cloth by proximity pairs (within twice its thickness), not by intersecting pairs");
    args.flag("ball", ball, "a ball thrown onto a cloth pinned at its edges, stopped by proximity pairs (implies --proximity)");
    args.option("speed", ball_scene.speed, "--ball: the ball's speed when thrown, m/s");
    args.option("ball-mass", ball_scene.ball_mass, "--ball: the ball's mass (the cloth's: --cloth-mass), kg");
    args.option("cloth-mass", ball_scene.cloth_mass, "--ball: the cloth's mass, kg");
    addCommonOptions(args, common);
    args.parse(argc, argv);
    finishCommonOptions(args, common, "cloth");
    refuseOtherMethod(args, common, "--proximity", DetectMethod::Reliable);
    refuseOtherMethod(args, common, "--ball", DetectMethod::Reliable);
    if (cells < 2 || substeps < 1) die("--cells must be at least 2 and --substeps at least 1");
    if (ball) {
        if (!(ball_scene.ball_mass > 0 && ball_scene.cloth_mass > 0)) die("--ball-mass and --cloth-mass must be positive");
        ball_scene.cells = cells, ball_scene.size = size, ball_scene.drop = drop;
        ball_scene.substeps = substeps, ball_scene.dt = dt;
        return runBall(common, ball_scene);
    }

    // The engine's device, lent to vkcollide.
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;

    // Two closed obstacles that never move: the sphere, and the floor it stands on.
    constexpr float kRadius = 0.35f;
    struct Obstacle {
        HostMesh mesh;  // world space
        ObjectId id;
        DrawId draw;
    };
    std::vector<Obstacle> obstacles;
    Renderer renderer(*engine, common.width, common.height);
    for (auto part : {uvSphere(kRadius, 48, 24), box({2.5f, 0.05f, 2.5f}, 16)}) {
        if (!part) return fail(part.error());
        const bool floor = !obstacles.empty();
        if (auto ok = transformMesh(*part, Transform3x4{1, 0, 0, 0, 0, 1, 0, floor ? -kRadius - 0.05f : 0, 0, 0, 1, 0}); !ok)
            return fail(ok.error());
        auto id = world->addMesh(*part, {.name = floor ? "floor" : "sphere"});
        if (!id) return fail(id.error());
        const DrawId draw = renderer.addMesh(*part, objectColour(floor ? 6 : 0));
        obstacles.push_back({std::move(*part), *id, draw});
    }

    // The sphere stands on the floor: they touch, and that is of no interest. Only pairs
    // with the cloth (itself included) are tested.
    if (auto ok = world->setPairFilter([&](ObjectId a, ObjectId b) { return !(a == obstacles[0].id && b == obstacles[1].id); }); !ok)
        return fail(ok.error());

    // The cloth: a grid folded like a page being turned, one half above the other, laid
    // horizontally above the sphere and turned a little, so the halves land on each other.
    auto grid = clothGrid(size, size, cells, cells, {.fold_angle = fold});
    if (!grid) return fail(grid.error());
    const float turn = 0.35f, height = kRadius + drop;
    for (Float3& p : grid->positions) {
        const float x = p.x * std::cos(turn) - p.y * std::sin(turn), z = p.x * std::sin(turn) + p.y * std::cos(turn);
        p = {x + 0.22f * size, height + p.z, z};
    }
    Cloth cloth(*grid, cells, cells, /*friction=*/0.3f);
    auto cloth_id = world->addMesh(*grid, {.name = "cloth", .self_collision = true, .open = true});
    if (!cloth_id) return fail(cloth_id.error());
    const DrawId cloth_draw = renderer.addMesh(*grid, objectColour(3), /*dynamic=*/true);
    Picture picture(renderer, common, "cloth", Camera{.eye = {2.2f, 1.9f, 3.2f}, .target = {0, -0.1f, 0}}, 1.1f);

    DetectSettings settings = common.detectSettings();
    FrameLog log(common.out + "/frames.csv",
                 {"cloth_sphere_pairs", "cloth_floor_pairs", "cloth_self_pairs", "max_penetration", "proximity_pairs"}, common.frames,
                 common.quiet);
    const float edge = size / static_cast<float>(cells);
    const float thickness = 0.25f * edge;
    if (proximity) settings.proximity.distance = 2 * thickness;
    int frames_intersecting = 0;
    const Vec3 gravity(0, -9.81f, 0);
    const std::vector<std::uint32_t>& cloth_indices = grid->indices;

    for (int frame = 0; frame < common.frames; ++frame) {
        const auto sim_start = std::chrono::steady_clock::now();
        const std::vector<Float3> before = cloth.positions();  // which side each triangle came from
        for (std::uint32_t s = 0; s < substeps; ++s) cloth.step(dt / static_cast<float>(substeps), gravity, 8);
        double sim_ms = msSince(sim_start);

        // New vertices, then one detection: every intersecting pair of triangles.
        if (auto ok = world->updateVertices(*cloth_id, cloth.positions()); !ok) return fail(ok.error());
        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());

        // Response, per pair. Against an obstacle: contact planes that the next steps
        // enforce (each corner of the cloth triangle stays in front of the obstacle
        // triangle's plane, and an obstacle corner poking through the cloth triangle lifts
        // it). Against itself: a one-off push of each triangle back to the side of the
        // other's plane it came from.
        const auto response_start = std::chrono::steady_clock::now();
        const std::vector<Float3> now = cloth.positions();  // as detected (and rendered)
        std::vector<Cloth::Contact> contacts;
        auto keepOut = [&](std::uint32_t t, const Vec3& plane_point, const Vec3& normal) {
            for (int k = 0; k < 3; ++k) contacts.push_back({cloth_indices[t * 3 + k], plane_point, normal, thickness, 2 * edge});
        };
        std::vector<Vec3> push(now.size(), Vec3::Zero());
        std::vector<int> pushes(now.size(), 0);
        int sphere_pairs = 0, floor_pairs = 0, self_pairs = 0;
        renderer.clearHighlights();
        for (const TrianglePair& p : hits->pairs) {
            if (p.object_a == p.object_b) {  // the cloth with itself
                renderer.highlight(cloth_draw, p.triangle_a);
                renderer.highlight(cloth_draw, p.triangle_b);
                // Once, not as a contact plane kept inside the solver: that would fight the
                // stretching of a fold and crumple the cloth.
                for (auto [t, other] : {std::pair{p.triangle_a, p.triangle_b}, std::pair{p.triangle_b, p.triangle_a}}) {
                    Vec3 n = triangleNormal(now, cloth_indices, other);
                    if (triangleNormal(before, cloth_indices, other)
                            .dot(triangleCentre(before, cloth_indices, t) - triangleCentre(before, cloth_indices, other)) < 0)
                        n = -n;
                    const Vec3 plane = toVec(now[cloth_indices[other * 3]]);
                    for (int k = 0; k < 3; ++k) {
                        const std::uint32_t v = cloth_indices[t * 3 + k];
                        const float depth = n.dot(toVec(now[v]) - plane);
                        if (depth < thickness && depth > -2 * edge) {
                            push[v] += 0.5f * (thickness - depth) * n;
                            ++pushes[v];
                        }
                    }
                }
                ++self_pairs;
                continue;
            }
            // The cloth's id is the larger: it was added after the obstacles.
            const Obstacle& o = p.object_a == obstacles[0].id ? obstacles[0] : obstacles[1];
            const std::uint32_t s = p.triangle_a, c = p.triangle_b;
            renderer.highlight(o.draw, s);
            renderer.highlight(cloth_draw, c);
            const Vec3 n = triangleNormal(o.mesh.positions, o.mesh.indices, s);
            keepOut(c, toVec(o.mesh.positions[o.mesh.indices[s * 3]]), n);
            Vec3 up = triangleNormal(now, cloth_indices, c);
            if (up.dot(n) < 0) up = -up;
            const Vec3 centre = triangleCentre(now, cloth_indices, c);
            for (int k = 0; k < 3; ++k) {
                const Vec3 corner = toVec(o.mesh.positions[o.mesh.indices[s * 3 + k]]);
                if ((corner - centre).norm() < 2 * edge && up.dot(corner - centre) > -thickness) keepOut(c, corner, up);
            }
            ++(&o == &obstacles[0] ? sphere_pairs : floor_pairs);
        }
        if (proximity) {
            // Every pair within the distance: the cloth's side keeps `thickness` in front of
            // the other primitive's closest point, along the pair's normal (from b towards a,
            // so a stays on its side; the cloth as b takes the opposite normal).
            // The intersection response above stays as a fallback should a pair ever intersect.
            if (!hits->pairs.empty()) ++frames_intersecting;
            const ObjectId cid = *cloth_id;
            for (const ProximityPair& q : hits->proximity) {
                const Vec3 n(q.normal[0], q.normal[1], q.normal[2]);
                const auto& pa = q.object_a == cid ? now : obstacles[q.object_a == obstacles[0].id ? 0 : 1].mesh.positions;
                const auto& pb = q.object_b == cid ? now : obstacles[q.object_b == obstacles[0].id ? 0 : 1].mesh.positions;
                const auto& ib = q.object_b == cid ? cloth_indices : obstacles[q.object_b == obstacles[0].id ? 0 : 1].mesh.indices;
                Vec3 on_a = toVec(pa[q.a0]), on_b = Vec3::Zero();
                std::uint32_t a_vertices[2] = {q.a0, q.a1}, b_vertices[3] = {q.b0, q.b1, q.b1};
                if (q.kind == ProximityKind::EdgeEdge) on_a = (1 - q.weight_a) * on_a + q.weight_a * toVec(pa[q.a1]);
                else b_vertices[0] = ib[3 * q.b0], b_vertices[1] = ib[3 * q.b0 + 1], b_vertices[2] = ib[3 * q.b0 + 2];
                for (int k = 0; k < 3; ++k) on_b += q.weights_b[k] * toVec(pb[b_vertices[k]]);
                const int a_count = q.kind == ProximityKind::EdgeEdge ? 2 : 1, b_count = q.kind == ProximityKind::EdgeEdge ? 2 : 3;
                if (q.object_a == cid)
                    for (int k = 0; k < a_count; ++k) contacts.push_back({a_vertices[k], on_b, n, thickness, 2 * edge});
                if (q.object_b == cid)
                    for (int k = 0; k < b_count; ++k) contacts.push_back({b_vertices[k], on_a, -n, thickness, 2 * edge});
                if (q.kind == ProximityKind::VertexTriangle && q.object_b == cid) renderer.highlight(cloth_draw, q.b0);
            }
        }
        cloth.setContacts(std::move(contacts));
        for (std::size_t v = 0; v < now.size(); ++v)
            if (pushes[v]) cloth.push(static_cast<std::uint32_t>(v), push[v] / static_cast<float>(pushes[v]));
        sim_ms += msSince(response_start);

        // How deep the cloth is inside the sphere (what the response must keep small).
        float max_penetration = 0;
        for (const Float3& p : now) max_penetration = std::max(max_penetration, kRadius - toVec(p).norm());

        // Render what was tested, with the colliding triangles highlighted.
        const auto render_start = std::chrono::steady_clock::now();
        renderer.updateVertices(cloth_draw, now);
        picture.write(frame, *hits,
                      "cloth pairs: " + std::to_string(sphere_pairs) + " sphere, " + std::to_string(floor_pairs) + " floor, " +
                          std::to_string(self_pairs) + " self" +
                          (proximity ? "; " + std::to_string(hits->proximity.size()) + " near" : std::string()));
        const double values[] = {double(sphere_pairs), double(floor_pairs), double(self_pairs), double(max_penetration),
                                 double(hits->proximity.size())};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("cloth");
    if (proximity) {
        if (frames_intersecting == 0)
            std::printf("proximity: no intersecting pair in any of the %d frames (checked by vkcollide's intersection detection)\n",
                        common.frames);
        else
            std::printf("proximity: %d of the %d frames had intersecting pairs\n", frames_intersecting, common.frames);
    }
    return exitStatus(*engine);
}
