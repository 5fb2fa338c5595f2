// Object-level contacts (DetectSettings::contacts.objects) through the public API, validation on,
// against closed forms: two overlapping spheres (lens volume, centroid, normal along the
// centre line, depth r1 + r2 - d), a box inside a box (containment, the inner box's
// volume), a sphere half sunk into a box (half the sphere mesh's volume, the face's
// normal, depth r); then what must hold whatever the scene: both methods give the same
// contacts, filtered pairs and open objects get none, nested objects grow the ray lists,
// bad settings are named.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "contacts/contacts.h"
#include "graph/executor.hpp"
#include "shaders/all.hpp"
#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/record_dispatch.hpp"
#include "support/test_scenes.hpp"
#include "support/world_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

constexpr double kPi = std::numbers::pi;

Transform3x4 translation(double x, double y, double z) {
    return {1, 0, 0, float(x), 0, 1, 0, float(y), 0, 0, 1, float(z)};
}

// The mesh's exact volume (divergence theorem), in object units.
double meshVolume(const HostMesh& m) {
    double v = 0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const Float3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]], &c = m.positions[m.indices[t + 2]];
        v += (double(a.x) * (double(b.y) * c.z - double(b.z) * c.y) - double(a.y) * (double(b.x) * c.z - double(b.z) * c.x) +
              double(a.z) * (double(b.x) * c.y - double(b.y) * c.x)) / 6.0;
    }
    return v;
}

double angleDegrees(Float3 n, std::array<double, 3> d) {
    const double ld = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double ln = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
    const double c = (n.x * d[0] + n.y * d[1] + n.z * d[2]) / (ld * ln);
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi;
}

double distance(Float3 p, std::array<double, 3> q) {
    return std::sqrt((p.x - q[0]) * (p.x - q[0]) + (p.y - q[1]) * (p.y - q[1]) + (p.z - q[2]) * (p.z - q[2]));
}

// Two spheres r1 (at the origin) and r2 (at distance d along `axis`): the lens.
struct Lens {
    double volume, depth;
    double centroid;  // distance of the lens's centroid from sphere 1's centre along the axis
};
Lens lens(double r1, double r2, double d) {
    const double a = (d * d + r1 * r1 - r2 * r2) / (2 * d);  // plane of the circle of intersection
    const double h1 = r1 - a, h2 = r2 - (d - a);              // cap heights
    auto cap = [](double r, double h) { return kPi * h * h * (3 * r - h) / 3; };
    auto capCentroid = [](double r, double h) { return 3 * (2 * r - h) * (2 * r - h) / (4 * (3 * r - h)); };  // from the centre
    const double v1 = cap(r1, h1), v2 = cap(r2, h2);
    // Cap 1 lies beyond the plane from sphere 1's centre (+axis); cap 2 before it, facing sphere 1.
    const double c1 = capCentroid(r1, h1), c2 = d - capCentroid(r2, h2);
    return {v1 + v2, r1 + r2 - d, (v1 * c1 + v2 * c2) / (v1 + v2)};
}

struct TwoSpheres {
    HostMesh s1, s2;
    double r1 = 1.0, r2 = 0.8, d = 1.2;
    std::array<double, 3> axis{0.8, 0.48, 0.36};  // unit
    Transform3x4 at2() const { return translation(axis[0] * d, axis[1] * d, axis[2] * d); }
};

TwoSpheres twoSpheres() {
    TwoSpheres s;
    // Level 4: 5120 triangles; the faces lie within 0.0006 r inside the sphere, so the
    // meshes' lens is within 0.3 % of the analytic one (the reference here).
    auto a = icosphere(float(s.r1), 4), b = icosphere(float(s.r2), 4);
    REQUIRE(a);
    REQUIRE(b);
    s.s1 = std::move(*a);
    s.s2 = std::move(*b);
    return s;
}

}  // namespace

TEST_CASE("contacts: two spheres give the lens volume, centroid, centre-line normal and depth r1 + r2 - d", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    const TwoSpheres s = twoSpheres();
    auto a = world->addMesh(s.s1, {.name = "one"});
    auto b = world->addMesh(s.s2, {.name = "two", .transform = s.at2()});
    REQUIRE(a);
    REQUIRE(b);
    auto r = world->detect({.contacts = true});
    REQUIRE(r);
    REQUIRE(r->contacts.size() == 1);
    const ObjectContact& c = r->contacts[0];
    const Lens L = lens(s.r1, s.r2, s.d);
    CHECK(c.object_a == *a);
    CHECK(c.object_b == *b);
    CHECK_FALSE(c.contained);
    CHECK(r->stats.contacts.rays_x > 0);
    INFO("volume " << c.volume << " vs " << L.volume << ", depth " << c.depth << " vs " << L.depth);
    CHECK(std::fabs(c.volume - L.volume) < 0.02 * L.volume);
    // From a (sphere 1) into b: along +axis.
    CHECK(angleDegrees(c.normal, s.axis) < 3.0);
    // Depth: within two ray spacings (region side / 128) of the closed form.
    const double spacing = 1.6 / 128;
    CHECK(std::fabs(c.depth - L.depth) < 2 * spacing);
    const std::array<double, 3> centroid{s.axis[0] * L.centroid, s.axis[1] * L.centroid, s.axis[2] * L.centroid};
    CHECK(distance(c.point, centroid) < spacing);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contacts: a box inside a box is contained, with the inner box's volume and no normal", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto outer = box({1, 1, 1}, 2), inner = box({0.3f, 0.2f, 0.4f}, 2);
    REQUIRE(outer);
    REQUIRE(inner);
    auto a = world->addMesh(*outer, {.name = "outer"});
    auto b = world->addMesh(*inner, {.name = "inner", .transform = translation(0.1, -0.2, 0.3)});
    REQUIRE(a);
    REQUIRE(b);
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling}) {
        INFO("method " << toString(method));
        auto r = world->detect({.method = method, .contacts = true});
        REQUIRE(r);
        CHECK(r->pairs.empty());
        REQUIRE(r->contacts.size() == 1);
        const ObjectContact& c = r->contacts[0];
        CHECK(c.contained);
        const double volume = meshVolume(*inner);  // 0.192, exact for a box
        CHECK(std::fabs(c.volume - volume) < 0.02 * volume);
        CHECK(c.normal.x == 0);
        CHECK(c.normal.y == 0);
        CHECK(c.normal.z == 0);
        CHECK(c.depth == 0);
        CHECK(distance(c.point, {0.1, -0.2, 0.3}) < 0.01);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contacts: a sphere half sunk into a box gives half its volume, the face normal and depth r", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto slab = box({1, 1, 0.5f}, 1);
    // Even rings: the equator is a ring of vertices in the plane z = 0, so the mesh below
    // it is exactly half the mesh (the fair reference is the mesh's own volume / 2).
    auto ball = uvSphere(0.4f, 48, 24);
    REQUIRE(slab);
    REQUIRE(ball);
    auto a = world->addMesh(*slab, {.name = "slab"});
    auto b = world->addMesh(*ball, {.name = "ball", .transform = translation(0.1, 0.2, 0.5)});
    REQUIRE(a);
    REQUIRE(b);
    auto r = world->detect({.contacts = true});
    REQUIRE(r);
    REQUIRE(r->contacts.size() == 1);
    const ObjectContact& c = r->contacts[0];
    const double half = meshVolume(*ball) / 2;
    INFO("volume " << c.volume << " vs " << half << ", depth " << c.depth);
    CHECK_FALSE(c.contained);
    CHECK(std::fabs(c.volume - half) < 0.02 * half);
    CHECK(angleDegrees(c.normal, {0, 0, 1}) < 2.0);  // from the slab (a) into the ball (b)
    CHECK(std::fabs(c.depth - 0.4) < 0.02);
    CHECK(distance(c.point, {0.1, 0.2, 0.5 - 3 * 0.4 / 8}) < 0.01);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contacts: the same whatever the method, filtered pairs and open objects get none", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    const TwoSpheres s = twoSpheres();
    auto a = world->addMesh(s.s1, {.name = "one"});
    auto b = world->addMesh(s.s2, {.name = "two", .transform = s.at2()});
    auto cloth = clothGrid(3.0f, 3.0f, 8, 8);
    REQUIRE(cloth);
    auto c = world->addMesh(*cloth, {.name = "cloth", .open = true});
    REQUIRE(a);
    REQUIRE(b);
    REQUIRE(c);
    auto reliable = world->detect({.method = DetectMethod::Reliable, .contacts = true});
    auto peeling = world->detect({.method = DetectMethod::Peeling, .contacts = true});
    REQUIRE(reliable);
    REQUIRE(peeling);
    CHECK(!reliable->pairs.empty());
    REQUIRE(reliable->contacts.size() == 1);  // the cloth is open: pairs only
    REQUIRE(peeling->contacts.size() == 1);
    const ObjectContact &x = reliable->contacts[0], &y = peeling->contacts[0];
    CHECK(x.volume == y.volume);
    CHECK(x.depth == y.depth);
    CHECK((x.normal.x == y.normal.x && x.normal.y == y.normal.y && x.normal.z == y.normal.z));
    CHECK((x.point.x == y.point.x && x.point.y == y.point.y && x.point.z == y.point.z));
    CHECK(x.contained == y.contained);

    REQUIRE(world->setPairFilter([&](ObjectId p, ObjectId q) { return !(p == *a && q == *b); }));
    auto filtered = world->detect({.contacts = true});
    REQUIRE(filtered);
    CHECK(filtered->contacts.empty());
    REQUIRE(world->setPairFilter({}));
    auto off = world->detect();
    REQUIRE(off);
    CHECK(off->contacts.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contacts: nested spheres grow the ray lists and every pair is contained", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    // Nine concentric spheres: 18 hits per central ray, more than the 16 slots a ray starts
    // with, so the first run overflows and the stage runs again with longer lists.
    std::vector<ObjectId> ids;
    std::vector<double> volumes;
    for (int k = 0; k < 9; ++k) {
        auto m = icosphere(0.5f + 0.05f * float(k), 3);
        REQUIRE(m);
        volumes.push_back(meshVolume(*m));
        auto id = world->addMesh(*m, {.name = "shell " + std::to_string(k)});
        REQUIRE(id);
        ids.push_back(*id);
    }
    auto r = world->detect({.contacts = {.objects = true, .resolution = 64}});
    REQUIRE(r);
    CHECK(r->stats.contacts.runs >= 2);
    CHECK(r->stats.contacts.layers >= 18);
    REQUIRE(r->contacts.size() == 36);
    for (const ObjectContact& c : r->contacts) {
        CHECK(c.contained);
        const double inner = volumes[std::min(c.object_a, c.object_b) - ids[0]];
        CHECK(std::fabs(c.volume - inner) < 0.03 * inner);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("contacts: bad settings are named, no closed object gives no contact", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto cloth = clothGrid(2.0f, 2.0f, 4, 4);
    REQUIRE(cloth);
    REQUIRE(world->addMesh(*cloth, {.open = true}));
    REQUIRE(world->addMesh(*cloth, {.open = true, .transform = translation(0.1, 0.1, 0)}));
    auto none = world->detect({.contacts = true});
    REQUIRE(none);
    CHECK(none->contacts.empty());
    for (std::uint32_t bad : {0u, 15u, 4097u}) {
        auto r = world->detect({.contacts = {.objects = true, .resolution = bad}});
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidArgument);
        CHECK(r.error().message().find("contacts.resolution") != std::string::npos);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// Each detection slot runs the stage after its own broad phase, on its buffers: two
// detections in flight give the contacts detect() gives, and the stage's buffers count in
// the world's memory.
TEST_CASE("contacts: two detections in flight each get them, on their slot's buffers", "[contacts][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    const TwoSpheres s = twoSpheres();
    REQUIRE(world->addMesh(s.s1, {.name = "one"}));
    REQUIRE(world->addMesh(s.s2, {.name = "two", .transform = s.at2()}));
    auto plain = world->detect();
    REQUIRE(plain);
    auto one = world->detect({.contacts = true});
    REQUIRE(one);
    REQUIRE(one->contacts.size() == 1);
    CHECK(one->stats.gpu_memory_bytes > plain->stats.gpu_memory_bytes);
    REQUIRE(world->submit({.contacts = true}));
    REQUIRE(world->submit({.contacts = true}));
    for (int k = 0; k < 2; ++k) {
        auto r = world->collect();
        REQUIRE(r);
        REQUIRE(r->contacts.size() == 1);
        CHECK(r->contacts[0].volume == one->contacts[0].volume);
        CHECK(r->contacts[0].depth == one->contacts[0].depth);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// The setup pass alone (contacts_setup.comp): a triangle whose pixel box is bigger than
// kContactsSmallBox is queued as work items of the tile pass, all written by the
// invocation that set it up. Its box here is the whole 4096^2 ray grid: 512^2 = 262,144
// tiles. Before, one work item per tile, one loop iteration each: llvmpipe ends a shader
// invocation's loops past 65,535 iterations without an error (DeviceInfo::
// loop_iteration_limit), so the items past 65,535 were never written and the tile pass drew
// whatever the buffer held instead (a 4096 x 1229 grid, end to end: volume 0.49996 for 0.6).
TEST_CASE("contacts: the setup pass queues every tile of a triangle over a 4096^2 ray grid", "[contacts][gpu][limits]") {
    ValidatedContext ctx;
    vk::Device& device = ctx.device();
    auto pipeline = vk::Pipeline::createCompute(device, shaders::contacts_setup_comp, {}, sizeof(gpu::Push), "contacts-setup-test");
    REQUIRE(pipeline);
    constexpr std::uint32_t kGrid = 4096, kTiles = (kGrid / gpu::kContactsTile) * (kGrid / gpu::kContactsTile);
    constexpr std::uint32_t kCapacity = kTiles + 1024;
    using vk::MemoryKind;
    auto params = vk::Buffer::create(device, sizeof(gpu::ContactsParams), 0, MemoryKind::Upload, "setup-params");
    auto objects = vk::Buffer::create(device, sizeof(gpu::ObjectGpu), 0, MemoryKind::Upload, "setup-objects");
    auto mesh = vk::Buffer::create(device, 64, 0, MemoryKind::Upload, "setup-mesh");  // 3 positions, then 3 indices
    auto active = vk::Buffer::create(device, 4, 0, MemoryKind::Upload, "setup-active");
    auto tris = vk::Buffer::create(device, sizeof(gpu::CtTriangle), 0, MemoryKind::Readback, "setup-triangles");
    auto header = vk::Buffer::create(device, sizeof(gpu::ContactsHeader), 0, MemoryKind::Readback, "setup-header");
    auto items = vk::Buffer::create(device, VkDeviceSize(kCapacity) * 8, 0, MemoryKind::Readback, "setup-items");
    REQUIRE((params && objects && mesh && active && tris && header && items));
    // One triangle in grid units (the grid is the world here), its box past the grid's corners.
    const float positions[9] = {-10.0f, -10.0f, 0.0f, 9000.0f, -10.0f, 0.0f, -10.0f, 9000.0f, 0.0f};
    const std::uint32_t indices[3] = {0, 1, 2};
    std::memcpy(mesh->mapped(), positions, sizeof positions);
    std::memcpy(static_cast<char*>(mesh->mapped()) + 48, indices, sizeof indices);
    mesh->flush();
    gpu::ObjectGpu o{};
    o.vertices = mesh->address();
    o.indices = mesh->address() + 48;
    o.vertex_stride = 12;
    o.vertex_count = 3;
    o.triangle_count = 1;
    o.model[0] = {1, 0, 0, 0};
    o.model[1] = {0, 1, 0, 0};
    o.model[2] = {0, 0, 1, 0};
    std::memcpy(objects->mapped(), &o, sizeof o);
    objects->flush();
    *static_cast<std::uint32_t*>(active->mapped()) = 1;
    active->flush();
    std::memset(header->mapped(), 0, sizeof(gpu::ContactsHeader));
    header->flush();
    std::memset(items->mapped(), 0xFF, VkDeviceSize(kCapacity) * 8);  // unwritten: (~0, ~0)
    items->flush();
    gpu::ContactsParams P{};
    P.objects = objects->address();
    P.object_active = active->address();
    P.triangles = tris->address();
    P.items = items->address();
    P.header = header->address();
    P.grid[0] = {1, 0, 0, 0};
    P.grid[1] = {0, 1, 0, 0};
    P.grid[2] = {0, 0, 1, 0};
    P.width = P.height = kGrid;
    P.layers = 1;
    P.item_capacity = kCapacity;
    P.triangle_count = 1;
    P.object_count = 1;
    P.max_groups_x = 65535;
    P.max_weight = gpu::kContactMaxWeight;
    P.fixed_scale = 1;
    std::memcpy(params->mapped(), &P, sizeof P);
    params->flush();
    graph::Graph g;
    const auto items_id = g.importBuffer("setup-items", *items, true);
    const auto header_id = g.importBuffer("setup-header", *header, true);
    const auto tris_id = g.importBuffer("setup-triangles", *tris, true);
    const VkPipeline handle = pipeline->handle();
    const VkPipelineLayout layout = pipeline->layout();
    const VkDeviceAddress params_address = params->address();
    g.addPass("setup", graph::PassKind::Compute).readWrite(header_id).write(items_id).write(tris_id).record([=](graph::PassContext& pc) {
        gpu::Push push{params_address, 0, 0, 0, 0};
        recordDispatch(pc, handle, layout, push);
    });
    graph::Executor executor(device);
    REQUIRE(executor.run(g));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    header->invalidate();
    items->invalidate();
    tris->invalidate();
    gpu::ContactsHeader h;
    std::memcpy(&h, header->mapped(), sizeof h);
    gpu::CtTriangle t;
    std::memcpy(&t, tris->mapped(), sizeof t);
    CHECK(h.flags == 0);
    CHECK(t.box[0] == 0);
    CHECK(t.box[1] == 0);
    CHECK(t.box[2] == int(kGrid) - 1);
    CHECK(t.box[3] == int(kGrid) - 1);
    REQUIRE(h.item_count >= 1);
    REQUIRE(h.item_count <= kCapacity);
    const auto* out = static_cast<const std::uint32_t*>(items->mapped());
    std::uint32_t wrong = 0, first_wrong = ~0u;
    for (std::uint32_t k = 0; k < h.item_count; ++k)
        if (out[2 * k] != 0 || out[2 * k + 1] != k) {
            first_wrong = std::min(first_wrong, k);
            ++wrong;
        }
    INFO(h.item_count << " items, the first wrong at " << first_wrong);
    CHECK(wrong == 0);
    // Now at most kContactsMaxTriangleItems items, of 64 tiles each here (the tile pass
    // reads them as such: contactTilesPerItem).
    CHECK(h.item_count == gpu::kContactsMaxTriangleItems);
    CHECK(std::uint64_t(h.item_count) * (kTiles / gpu::kContactsMaxTriangleItems) == kTiles);
}

// The tile pass with several tiles per work item: a face of these boxes covers the whole
// 1024 x 307 ray grid, 128 x 39 = 4,992 tiles, more than kContactsMaxTriangleItems: two
// tiles per item, and the overlap is measured in full.
TEST_CASE("contacts: a face whose tiles take several per work item is drawn in full", "[contacts][gpu][limits]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto a_mesh = box({1, 0.3f, 1}, 1), b_mesh = box({1, 0.3f, 1}, 1);
    REQUIRE(a_mesh);
    REQUIRE(b_mesh);
    auto a = world->addMesh(*a_mesh, {.name = "a"});
    auto b = world->addMesh(*b_mesh, {.name = "b", .transform = translation(0, 0, 1.5)});
    REQUIRE(a);
    REQUIRE(b);
    DetectSettings s;
    s.direction = std::array<float, 3>{0, 0, 1};
    s.contacts.objects = true;
    s.contacts.resolution = 1024;
    auto r = world->detect(s);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    REQUIRE(r->contacts.size() == 1);
    const ObjectContact& c = r->contacts[0];
    const double volume = 2.0 * 0.6 * 0.5;  // the boxes' overlap
    INFO("volume " << c.volume);
    CHECK(std::fabs(c.volume - volume) < 0.01 * volume);
    CHECK(std::fabs(c.depth - 0.5) < 0.01);
    CHECK(angleDegrees(c.normal, {0, 0, 1}) < 0.5);
    CHECK(std::max(r->stats.contacts.rays_x, r->stats.contacts.rays_y) == 1024);
    INFO("rays " << r->stats.contacts.rays_x << " x " << r->stats.contacts.rays_y);
    CHECK(std::min(r->stats.contacts.rays_x, r->stats.contacts.rays_y) > 4096 / 128 * 8);  // more than 4,096 tiles
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

namespace {

// `slabs` thin boxes stacked along z inside one big box, the highest first (the first
// triangles drawn are the farthest along the rays, so a ray's list starts in reverse
// depth order: the walk's insertion sort does its most work). Every slab is contained in
// the big box, with its own volume.
struct SlabStack {
    std::unique_ptr<CollisionWorld> world;
    double slab_volume = 0;
};
SlabStack slabStack(ValidatedContext& ctx, int slabs) {
    SlabStack s{makeWorld(ctx), 0};
    auto outer = box({1, 1, 1}, 1), slab = box({0.5f, 0.5f, 0.002f}, 1);
    REQUIRE(outer);
    REQUIRE(slab);
    s.slab_volume = meshVolume(*slab);
    REQUIRE(s.world->addMesh(*outer, {.name = "outer"}));
    for (int i = 0; i < slabs; ++i)
        REQUIRE(s.world->addMesh(*slab, {.name = "slab", .transform = translation(0, 0, -0.9 + 1.8 * (i + 0.5) / slabs)}));
    return s;
}

}  // namespace

// A ray's fragments are sorted in one shader invocation (insertion sort: up to n (n + 1) / 2
// loop iterations for n fragments) and walked there. Through 400 slabs in a box a ray has
// 802 fragments: up to 321,403 iterations, past the 65,535 that llvmpipe runs in one
// shader invocation before it ends the loops without an error (DeviceInfo::
// loop_iteration_limit). Before, the detection succeeded there with no contact at all;
// now it fails naming that limit. On a GPU, and through 60 slabs everywhere, every
// slab's volume.
TEST_CASE("contacts: a ray through 400 stacked slabs gives every slab's volume, or on llvmpipe a named loop limit", "[contacts][gpu][limits]") {
    ValidatedContext ctx;
    const bool llvmpipe = ctx.device().info.loop_iteration_limit != 0;
    for (int slabs : {60, 400}) {
        INFO(slabs << " slabs");
        SlabStack s = slabStack(ctx, slabs);
        DetectSettings settings;
        settings.direction = std::array<float, 3>{0, 0, 1};
        settings.contacts.objects = true;
        settings.contacts.resolution = 16;
        auto r = s.world->detect(settings);
        if (slabs == 400 && llvmpipe) {
            REQUIRE_FALSE(r);
            INFO(r.error().message());
            CHECK(r.error().code() == ErrorCode::LimitExceeded);
            CHECK(mentions(r.error(), "loop"));
            CHECK(mentions(r.error(), "65535"));
            continue;
        }
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        REQUIRE(r->contacts.size() == std::size_t(slabs));
        std::size_t wrong = 0;
        for (const ObjectContact& c : r->contacts)
            if (!c.contained || std::fabs(c.volume - s.slab_volume) > 0.02 * s.slab_volume) ++wrong;
        INFO("first: volume " << r->contacts[0].volume << " for " << s.slab_volume << (r->contacts[0].contained ? ", contained" : ""));
        CHECK(wrong == 0);
        CHECK(r->stats.contacts.layers >= std::uint32_t(2 + 2 * slabs));
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
