// The cloth sample's --ball mode: README's ball and cloth, runnable. A cloth held at its
// four edges like a trampoline, and a rigid ball thrown down onto it. Both are driven by
// proximity pairs only (DetectSettings::proximity): every vertex-triangle pair (either
// way) and edge-edge pair between the ball and the cloth within the distance becomes a
// contact plane that moves with the ball; the cloth vertex is kept `thickness` in front
// of it and the ball takes the opposite correction, shared by mass, so the cloth slows
// the ball as much as the ball stretches the cloth. The cloth's pairs with itself keep it
// from folding through itself, as in --proximity.
//
// Every frame's detection also reports the intersecting pairs, ball-cloth and
// cloth-cloth; the sample says at the end whether any frame had one, and exits with 1 if
// one did: the proximity response must keep the ball from ever touching the cloth.
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cloth_ball.hpp"
#include "common/lent_device.hpp"
#include "common/physics.hpp"
#include "common/picture.hpp"
#include "common/render.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

namespace samples {

using namespace vkcollide;

int runBall(CommonOptions& common, const BallScene& scene) {
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;
    Renderer renderer(*engine, common.width, common.height);

    // The ball: a rigid body in object space, moved by setTransform (translation only: it
    // does not spin, and a sphere looks the same turned).
    auto ball_mesh = icosphere(scene.radius, 3);
    if (!ball_mesh) return fail(ball_mesh.error());
    Cloth::Body ball{.position = Vec3(0.05f * scene.size, scene.radius + scene.drop, 0), .inverse_mass = 1 / scene.ball_mass};
    Vec3 velocity(0, -scene.speed, 0);
    const auto translation = [&] {
        const Vec3& p = ball.position;
        return Transform3x4{1, 0, 0, p.x(), 0, 1, 0, p.y(), 0, 0, 1, p.z()};
    };
    auto ball_id = world->addMesh(*ball_mesh, {.name = "ball"});
    if (!ball_id) return fail(ball_id.error());
    std::vector<Float3> ball_world(ball_mesh->positions.size());  // where the detection saw it
    const auto placeBall = [&] {
        for (std::size_t i = 0; i < ball_world.size(); ++i) ball_world[i] = toFloat3(toVec(ball_mesh->positions[i]) + ball.position);
    };
    placeBall();
    const DrawId ball_draw = renderer.addMesh(*ball_mesh, objectColour(0), /*dynamic=*/true);

    // The cloth: flat at y = 0, every border vertex pinned.
    const std::uint32_t n = scene.cells;
    auto grid = clothGrid(scene.size, scene.size, n, n);
    if (!grid) return fail(grid.error());
    for (Float3& p : grid->positions) p = {p.x, p.z, p.y};
    Cloth cloth(*grid, n, n, /*friction=*/0.3f);
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i)
            if (i == 0 || j == 0 || i == n || j == n) cloth.pin(j * (n + 1) + i);
    cloth.setMass(scene.cloth_mass);
    auto cloth_id = world->addMesh(*grid, {.name = "cloth", .self_collision = true, .open = true});
    if (!cloth_id) return fail(cloth_id.error());
    const DrawId cloth_draw = renderer.addMesh(*grid, objectColour(3), /*dynamic=*/true);
    Picture picture(renderer, common, "cloth", Camera{.eye = {1.7f, 0.8f, 2.6f}, .target = {0, -0.15f, 0}}, 0.8f);

    // The cloth's thickness, as in --proximity: a quarter of an edge, pairs within twice that.
    const float edge = scene.size / static_cast<float>(n), thickness = 0.25f * edge;
    DetectSettings settings = common.detectSettings();
    settings.proximity.distance = 2 * thickness;
    // Contacts come only from pairs already within the distance: a ball that moves
    // farther in one frame can meet cloth no pair warned of.
    if (scene.speed * scene.dt > settings.proximity.distance)
        std::printf("ball: note: it moves %.3f a frame at the start, more than the proximity distance %.3f; it may reach the cloth "
                    "between detections (lower --dt or --speed, or fewer --cells)\n",
                    scene.speed * scene.dt, settings.proximity.distance);
    FrameLog log(common.out + "/frames.csv",
                 {"ball_height", "ball_speed", "ball_cloth_near", "cloth_self_near", "intersecting_pairs", "cloth_lowest"},
                 common.frames, common.quiet);
    const Vec3 gravity(0, -9.81f, 0);
    const std::vector<std::uint32_t>& cloth_indices = grid->indices;
    const float start_speed = velocity.norm();
    float lowest = ball.position.y() - scene.radius;  // the ball's lowest point over the run
    int frames_intersecting = 0;

    for (int frame = 0; frame < common.frames; ++frame) {
        const auto sim_start = std::chrono::steady_clock::now();
        const float h = scene.dt / static_cast<float>(scene.substeps);
        for (std::uint32_t s = 0; s < scene.substeps; ++s) {
            // The ball moves first; the cloth's step then pushes it back through the contacts.
            velocity += gravity * h;
            const Vec3 from = ball.position;
            ball.position += velocity * h;
            cloth.step(h, gravity, 8);
            velocity = (ball.position - from) / h;
        }
        placeBall();
        lowest = std::min(lowest, ball.position.y() - scene.radius);
        double sim_ms = msSince(sim_start);

        if (auto ok = world->setTransform(*ball_id, translation()); !ok) return fail(ok.error());
        if (auto ok = world->updateVertices(*cloth_id, cloth.positions()); !ok) return fail(ok.error());
        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());
        if (!hits->pairs.empty()) ++frames_intersecting;

        // Every pair within the distance becomes a contact of the cloth's side against the
        // other side's closest point, along the pair's normal (from b towards a; the cloth
        // as b takes the opposite). A point on the ball is kept relative to the ball, so
        // the plane moves with it and pushes it back.
        const auto response_start = std::chrono::steady_clock::now();
        const std::vector<Float3> now = cloth.positions();  // as detected (and rendered)
        std::vector<Cloth::Contact> contacts;
        int ball_pairs = 0, self_pairs = 0;
        renderer.clearHighlights();
        for (const ProximityPair& q : hits->proximity) {
            const bool a_cloth = q.object_a == *cloth_id, b_cloth = q.object_b == *cloth_id;
            const bool edges = q.kind == ProximityKind::EdgeEdge;
            const auto& pa = a_cloth ? now : ball_world;
            const auto& pb = b_cloth ? now : ball_world;
            const auto& ib = b_cloth ? cloth_indices : ball_mesh->indices;
            Vec3 on_a = toVec(pa[q.a0]), on_b = Vec3::Zero();
            std::uint32_t a_vertices[2] = {q.a0, q.a1}, b_vertices[3] = {q.b0, q.b1, q.b1};
            if (edges) on_a = (1 - q.weight_a) * on_a + q.weight_a * toVec(pa[q.a1]);
            else b_vertices[0] = ib[3 * q.b0], b_vertices[1] = ib[3 * q.b0 + 1], b_vertices[2] = ib[3 * q.b0 + 2];
            for (int k = 0; k < 3; ++k) on_b += q.weights_b[k] * toVec(pb[b_vertices[k]]);
            const Vec3 normal(q.normal[0], q.normal[1], q.normal[2]);
            Cloth::Body* body = a_cloth && b_cloth ? nullptr : &ball;
            const Vec3 origin = body ? ball.position : Vec3(Vec3::Zero());
            if (a_cloth)
                for (int k = 0; k < (edges ? 2 : 1); ++k) contacts.push_back({a_vertices[k], on_b - origin, normal, thickness, 2 * edge, body});
            if (b_cloth)
                for (int k = 0; k < (edges ? 2 : 3); ++k) contacts.push_back({b_vertices[k], on_a - origin, -normal, thickness, 2 * edge, body});
            if (!edges && b_cloth) renderer.highlight(cloth_draw, q.b0);
            if (!edges && !b_cloth) renderer.highlight(ball_draw, q.b0);
            ++(body ? ball_pairs : self_pairs);
        }
        for (const TrianglePair& p : hits->pairs) {  // none, unless the response failed: shown if so
            renderer.highlight(p.object_a == *ball_id ? ball_draw : cloth_draw, p.triangle_a);
            renderer.highlight(p.object_b == *ball_id ? ball_draw : cloth_draw, p.triangle_b);
        }
        cloth.setContacts(std::move(contacts));
        sim_ms += msSince(response_start);

        float cloth_lowest = 0;
        for (const Float3& p : now) cloth_lowest = std::min(cloth_lowest, p.y);
        const auto render_start = std::chrono::steady_clock::now();
        renderer.updateVertices(cloth_draw, now);
        renderer.updateVertices(ball_draw, ball_world);
        char caption[160];
        std::snprintf(caption, sizeof caption, "ball %.2f m/s; near: %d ball, %d self; %zu intersect",
                      velocity.norm(), ball_pairs, self_pairs, hits->pairs.size());
        picture.write(frame, *hits, caption);
        const double values[] = {ball.position.y(), velocity.norm(), double(ball_pairs), double(self_pairs), double(hits->pairs.size()),
                                 cloth_lowest};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("cloth");
    if (frames_intersecting == 0)
        std::printf("ball: no intersecting pair in any of the %d frames (checked by vkcollide's intersection detection)\n", common.frames);
    else
        std::printf("ball: %d of the %d frames had intersecting pairs\n", frames_intersecting, common.frames);
    std::printf("ball: speed %.2f m/s at the start, %.2f at the end; its lowest point %.3f below the cloth's pinned edges\n",
                start_speed, velocity.norm(), -lowest);
    const int status = exitStatus(*engine);
    return status != 0 ? status : frames_intersecting != 0 ? 1 : 0;
}

}  // namespace samples
