// Rigid bodies (paper section 8, Figure 10): 60 bunnies, half a million triangles, fall
// under gravity into a box and pile up.
//
// What it shows: many rigid objects that move only by setTransform (the vertices are
// uploaded once), and a minimal rigid-body integrator driven by DetectResult: the pairs
// say which bodies touch and where, the per-triangle response vectors say which way to
// push them apart. The box is one static object made of five slabs.
//
//   vkcollide_rigid_bunnies [--frames 240] [--bunnies 60] [--bunny-triangles 8300] [--out rigid_bunnies] (--help)
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

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

// Five slabs (floor and four walls) with small gaps between them, so the static box is
// one object made of closed parts that do not touch each other.
Result<HostMesh> openBox(float inner, float height, float wall) {
    HostMesh box;
    box.name = "box";
    const float h = inner / 2, gap = 0.01f;
    const struct {
        Float3 half, centre;
    } slabs[] = {{{h + wall, wall / 2, h + wall}, {0, -wall / 2, 0}},
                 {{wall / 2, height / 2, h}, {-h - wall / 2, height / 2 + gap, 0}},
                 {{wall / 2, height / 2, h}, {h + wall / 2, height / 2 + gap, 0}},
                 {{h - gap, height / 2, wall / 2}, {0, height / 2 + gap, -h - wall / 2}},
                 {{h - gap, height / 2, wall / 2}, {0, height / 2 + gap, h + wall / 2}}};
    for (const auto& s : slabs) {
        auto slab = vkcollide::box(s.half, 8);
        if (!slab) return slab.error();
        for (Float3& p : slab->positions) p = {p.x + s.centre.x, p.y + s.centre.y, p.z + s.centre.z};
        appendMesh(box, *slab);
    }
    return box;
}

}  // namespace

int main(int argc, char** argv) {
    CommonOptions common;
    common.frames = 240;
    std::uint32_t bunnies = 60;
    std::uint32_t bunny_triangles = 8300;  // 60 x 8.3K = the paper's 500K
    std::uint32_t columns = 4;             // bunnies per row and column of a layer at the start
    float box_size = 5.0f;                 // inner width of the box; a bunny is about 1 across
    float drop = 1.0f;                     // height of the lowest layer above the floor
    float dt = 1.0f / 60.0f;
    std::uint32_t seed = 7;
    Args args("vkcollide_rigid_bunnies", "rigid bunnies fall into a box (paper section 8, Figure 10)");
    args.option("bunnies", bunnies, "number of bunnies");
    args.option("bunny-triangles", bunny_triangles, "triangles per bunny (the CGAL bunny simplified)");
    args.option("columns", columns, "bunnies per row of a layer at the start");
    args.option("box", box_size, "inner width of the box (a bunny is 1 across)");
    args.option("drop", drop, "height of the lowest bunnies above the floor at the start");
    args.option("dt", dt, "simulated seconds per frame");
    args.option("seed", seed, "seed of the random start orientations");
    addCommonOptions(args, common);
    args.parse(argc, argv);
    finishCommonOptions(args, common, "rigid_bunnies");
    if (bunnies < 1 || columns < 1 || bunny_triangles < 16) die("--bunnies and --columns must be at least 1, --bunny-triangles at least 16");

    // The engine's device, lent to vkcollide.
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;
    Renderer renderer(*engine, common.width, common.height);

    // The static box.
    auto box = openBox(box_size, 1.6f, 0.4f);
    if (!box) return fail(box.error());
    auto box_id = world->addMesh(*box, {.name = "box"});
    if (!box_id) return fail(box_id.error());
    const DrawId box_draw = renderer.addMesh(*box, objectColour(6));

    // One bunny mesh, many objects: each addMesh uploads it once; after that a bunny only
    // moves by setTransform.
    const HostMesh bunny = simplifyMesh(loadSceneMesh(common, "bunny00.off", StandIn::Blob, 1.0f), bunny_triangles);
    std::printf("bunny: %zu triangles, %u bunnies: %zu triangles\n", bunny.triangleCount(), bunnies, bunny.triangleCount() * bunnies);
    Vec3 lo = toVec(bunny.positions[0]), hi = lo;
    for (const Float3& p : bunny.positions) {
        lo = lo.cwiseMin(toVec(p));
        hi = hi.cwiseMax(toVec(p));
    }
    const Vec3 half = (hi - lo) / 2;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<RigidBody> bodies;
    std::vector<ObjectId> ids;
    std::map<ObjectId, std::size_t> body_of;
    std::vector<DrawId> draws;
    const DrawId first_draw = renderer.addMesh(bunny, objectColour(0));
    const float spacing = 1.15f;
    for (std::uint32_t i = 0; i < bunnies; ++i) {
        RigidBody b = RigidBody::boxLike(half);
        const float layer = float(i / (columns * columns)), row = float((i / columns) % columns), col = float(i % columns);
        const float middle = float(columns - 1) / 2.0f;
        b.position = Vec3((col - middle) * spacing, drop + half.y() + layer * spacing, (row - middle) * spacing);
        b.orientation = Eigen::Quaternionf(1.0f, 0.3f * unit(rng), unit(rng), 0.3f * unit(rng)).normalized();
        auto id = world->addMesh(bunny, {.name = "bunny " + std::to_string(i), .transform = b.transform()});
        if (!id) return fail(id.error());
        body_of[*id] = bodies.size();
        bodies.push_back(b);
        ids.push_back(*id);
        draws.push_back(i == 0 ? first_draw : renderer.addInstance(first_draw, objectColour(i)));
    }
    const float reach = std::max(float(columns) * spacing, box_size);
    Picture picture(renderer, common, "rigid bunnies",
                    Camera{.eye = {0.9f * reach, 1.1f * reach + 1.5f, 1.4f * reach}, .target = {0, 0.6f, 0}}, 1.0f);

    const DetectSettings settings = common.detectSettings();
    FrameLog log(common.out + "/frames.csv", {"bunny_box_pairs", "bunny_bunny_pairs", "bunnies_in_box", "lowest_centre"},
                 common.frames, common.quiet);
    const Vec3 gravity(0, -9.81f, 0);
    // Corner k of triangle t in world space (the box's mesh is in world space already).
    auto corner = [&](const RigidBody* body, std::uint32_t t, int k) {
        const Vec3 c = toVec((body ? bunny : *box).positions[(body ? bunny : *box).indices[t * 3 + k]]);
        return body ? Vec3(body->orientation * c + body->position) : c;
    };
    double edge_sum = 0;
    for (std::size_t t = 0; t < bunny.triangleCount(); ++t)
        edge_sum += (toVec(bunny.positions[bunny.indices[t * 3]]) - toVec(bunny.positions[bunny.indices[t * 3 + 1]])).norm();
    const float edge = static_cast<float>(edge_sum / double(bunny.triangleCount()));  // typical edge of the bunny

    for (int frame = 0; frame < common.frames; ++frame) {
        const auto sim_start = std::chrono::steady_clock::now();
        for (RigidBody& b : bodies) b.integrate(dt, gravity, 0.002f);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            if (auto ok = world->setTransform(ids[i], bodies[i].transform()); !ok) return fail(ok.error());
            renderer.setTransform(draws[i], bodies[i].transform());  // the picture shows what was detected
        }
        double sim_ms = msSince(sim_start);

        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());

        // Contacts: one per touching pair of objects, at the mean of the colliding
        // triangles' corners, along the difference of the two sides' summed response
        // vectors (each points out of the partner, the way to push its triangle).
        const auto response_start = std::chrono::steady_clock::now();
        struct Touch {
            Vec3 point = Vec3::Zero(), push_a = Vec3::Zero(), push_b = Vec3::Zero();
            int points = 0;
            std::vector<Vec3> corners_a, corners_b;  // of the colliding triangles (overlap depth)
        };
        std::map<std::pair<ObjectId, ObjectId>, Touch> touches;
        renderer.clearHighlights();
        int box_pairs = 0, bunny_pairs = 0;
        for (const TrianglePair& p : hits->pairs) {
            const RigidBody* a = p.object_a == *box_id ? nullptr : &bodies[body_of[p.object_a]];
            const RigidBody* b = &bodies[body_of[p.object_b]];  // the box was added first: never b
            renderer.highlight(a ? draws[body_of[p.object_a]] : box_draw, p.triangle_a);
            renderer.highlight(draws[body_of[p.object_b]], p.triangle_b);
            ++(a ? bunny_pairs : box_pairs);
            Touch& t = touches[{p.object_a, p.object_b}];
            for (int k = 0; k < 3; ++k) {
                t.corners_a.push_back(corner(a, p.triangle_a, k));
                t.corners_b.push_back(corner(b, p.triangle_b, k));
                t.point += t.corners_a.back() + t.corners_b.back();
            }
            t.points += 6;
            if (const TriangleResponse* r = findResponse(hits->responses, p.object_a, p.triangle_a)) t.push_a += toVec(r->direction);
            if (const TriangleResponse* r = findResponse(hits->responses, p.object_b, p.triangle_b)) t.push_b += toVec(r->direction);
        }
        struct Contact {
            RigidBody *a, *b;  // a: null for the box
            Vec3 point, normal;  // normal from a towards b: b is pushed along it, a against it
            float overlap;       // how far the colliding triangles reach past each other along it
        };
        std::vector<Contact> contacts;
        for (auto& [objects, t] : touches) {
            RigidBody* a = objects.first == *box_id ? nullptr : &bodies[body_of[objects.first]];
            RigidBody* b = &bodies[body_of[objects.second]];
            const Vec3 point = t.point / static_cast<float>(t.points);
            Vec3 normal = t.push_b - t.push_a;
            if (normal.norm() < 1e-6f) normal = b->position - (a ? a->position : point);
            normal.normalize();
            float reach_a = -1e30f, reach_b = 1e30f;
            for (const Vec3& c : t.corners_a) reach_a = std::max(reach_a, normal.dot(c));
            for (const Vec3& c : t.corners_b) reach_b = std::min(reach_b, normal.dot(c));
            contacts.push_back({a, b, point, normal, reach_a - reach_b});
        }
        // Sequential impulses: a few passes over all contacts, so a pile can rest; then
        // a push apart for what overlaps more than the triangles that touch can explain.
        for (int pass = 0; pass < 8; ++pass)
            for (const Contact& c : contacts) resolveContact(*c.b, c.a, c.point, c.normal, pass == 0 ? 0.2f : 0.0f, 0.5f);
        for (const Contact& c : contacts) separate(*c.b, c.a, c.normal, std::clamp(0.3f * (c.overlap - edge), 0.0f, edge));
        sim_ms += msSince(response_start);

        int in_box = 0;
        float lowest = bodies[0].position.y();
        for (const RigidBody& b : bodies) lowest = std::min(lowest, b.position.y());
        for (const RigidBody& b : bodies)
            in_box += std::abs(b.position.x()) < box_size / 2 && std::abs(b.position.z()) < box_size / 2 && b.position.y() > 0;

        const auto render_start = std::chrono::steady_clock::now();
        picture.write(frame, *hits,
                      std::to_string(box_pairs) + " bunny-box, " + std::to_string(bunny_pairs) + " bunny-bunny pairs, " +
                          std::to_string(in_box) + " in the box");
        const double values[] = {double(box_pairs), double(bunny_pairs), double(in_box), double(lowest)};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("rigid bunnies");
    return exitStatus(*engine);
}
