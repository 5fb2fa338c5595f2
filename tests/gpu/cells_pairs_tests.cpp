// The cell stage against the exact reference (tests/support/exact_reference.cpp) on
// lavapipe with validation on: every reference pair, touching included, must survive
// (100 % recall) on adversarial scenes and at resolutions from 1 to 1024 cells per side.
#include <catch2/catch.hpp>

#include <random>

#include "gpu/cells_test_support.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

Transform rotation(double ax, double ay, double az, double angle, Float3 t) {
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    ax /= len, ay /= len, az /= len;
    const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    return transformFrom3x4({float(c + ax * ax * k), float(ax * ay * k - az * s), float(ax * az * k + ay * s), t.x,
                             float(ay * ax * k + az * s), float(c + ay * ay * k), float(ay * az * k - ax * s), t.y,
                             float(az * ax * k - ay * s), float(az * ay * k + ax * s), float(c + az * az * k), t.z});
}

CellScene twoSpheres() {
    CellScene s;
    s.meshes.push_back(generated(uvSphere(1.0f, 24, 12), "a"));
    s.meshes.push_back(generated(uvSphere(0.8f, 20, 10), "b"));
    s.transforms = {kIdentityTransform, translation(0.7f, 0.35f, 0.2f)};
    return s;
}

}  // namespace

TEST_CASE("cells: two overlapping spheres, every pair at every resolution", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    const CellScene scene = twoSpheres();
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 20);
    for (std::uint32_t n : {1u, 4u, 7u, 16u, 64u, 100u, 256u, 1024u}) {
        INFO("resolution " << n);
        CellRunOptions opt;
        opt.resolution = n;
        const CellRun run = runCells(ctx, **stage, scene, opt);
        requireAllFound(run, reference);
        CHECK(run.result.stats.entries >= 2 * 24 * 11 + 2 * 20 * 9);
        CHECK(run.result.stats.runs >= 1);
        CHECK(run.result.stats.filter_ran == ctx.device().shader_float64);
    }
}

TEST_CASE("cells: random sub-cell triangle soups, several objects, self-collision on and off", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(12345);
    CellScene scene;
    scene.meshes.push_back(soup(rng, 1500, 0.0f, 0.25f, 0.004f, "self-on"));
    scene.meshes.push_back(soup(rng, 1500, 0.0f, 0.25f, 0.004f, "self-off"));
    scene.meshes.push_back(soup(rng, 1000, 0.05f, 0.2f, 0.002f, "small"));
    scene.self = {1, 0, 1};
    const auto reference = referencePairs(scene);
    INFO("reference pairs " << reference.size());
    REQUIRE(reference.size() > 10);
    for (std::uint32_t n : {4u, 32u, 256u, 1024u}) {
        for (auto dir : {std::array<double, 3>{0, 0, 1}, std::array<double, 3>{1, 0.3, -0.2}}) {
            INFO("resolution " << n << " direction " << dir[0] << "," << dir[1] << "," << dir[2]);
            CellRunOptions opt;
            opt.resolution = n;
            opt.direction = dir;
            const CellRun run = runCells(ctx, **stage, scene, opt);
            requireAllFound(run, reference);
            for (const TrianglePair& p : run.pairs)
                if (p.object_a == p.object_b) CHECK(p.object_a != 1u);  // self-collision off
        }
    }
}

TEST_CASE("cells: needles, slivers and collinear triangles", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(777);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), sign(-1.0f, 1.0f);
    CellScene scene;
    for (int o = 0; o < 3; ++o) {
        HostMesh m;
        m.name = "needles";
        for (int t = 0; t < 400; ++t) {
            const Float3 a{unit(rng), unit(rng), unit(rng)};
            const Float3 dir{sign(rng), sign(rng), sign(rng)};
            const float len = 0.3f;
            const Float3 b{a.x + len * dir.x, a.y + len * dir.y, a.z + len * dir.z};
            const float w = t % 4 == 0 ? 0.0f : (t % 4 == 1 ? 1e-7f : (t % 4 == 2 ? 1e-4f : 1e-2f));  // 0: collinear
            const Float3 c{0.5f * (a.x + b.x) + w * sign(rng), 0.5f * (a.y + b.y) + w * sign(rng), 0.5f * (a.z + b.z) + w * sign(rng)};
            if (t % 8 == 7) addTriangle(m, a, a, b);  // a repeated vertex
            else addTriangle(m, a, b, c);
        }
        scene.meshes.push_back(std::move(m));
    }
    scene.self = {1, 0, 0};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 10);
    for (std::uint32_t n : {4u, 64u, 512u}) {
        INFO("resolution " << n);
        CellRunOptions opt;
        opt.resolution = n;
        opt.direction = {0.2, 1, 0.1};
        requireAllFound(runCells(ctx, **stage, scene, opt), reference);
    }
}

TEST_CASE("cells: edge-on contacts along each axis, crossing and touching", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int axis = 0; axis < 3; ++axis) {
        // Triangles in planes that contain the viewing axis: every projection is a
        // segment. Coordinates are dyadic, so touching contacts are exact.
        auto put = [axis](float along, float p, float q) {
            Float3 v;
            float* c = &v.x;
            c[axis] = along;
            c[(axis + 1) % 3] = p;
            c[(axis + 2) % 3] = q;
            return v;
        };
        CellScene scene;
        HostMesh walls, others;
        walls.name = "walls";
        others.name = "others";
        for (int t = 0; t < 200; ++t) {
            const float p = std::round(unit(rng) * 64) / 64, q = std::round(unit(rng) * 64) / 64;
            const float dp = std::round(unit(rng) * 32) / 64, dq = std::round(unit(rng) * 32) / 64;
            const float z0 = std::round(unit(rng) * 64) / 64, z1 = z0 + 0.25f;
            addTriangle(walls, put(z0, p - dp, q - dq), put(z0, p + dp, q + dq), put(z1, p, q));
            // Another wall through the midpoint of this one's base (touching or crossing),
            // and a triangle whose vertex sits exactly on the wall's base edge.
            addTriangle(others, put(z0 - 0.125f, p - dq, q + dp), put(z0 + 0.125f, p + dq, q - dp), put(z0, p, q));
            addTriangle(others, put(z0, p + dp / 2, q + dq / 2), put(z0 - 0.25f, p + 0.5f, q), put(z0 - 0.25f, p, q + 0.5f));
        }
        scene.meshes = {walls, others};
        const auto reference = referencePairs(scene);
        INFO("axis " << axis << ", reference " << reference.size());
        REQUIRE(reference.size() > 100);
        std::array<double, 3> dir{0, 0, 0};
        dir[axis] = 1;
        for (std::uint32_t n : {4u, 64u, 1024u}) {
            INFO("resolution " << n);
            CellRunOptions opt;
            opt.resolution = n;
            opt.direction = dir;
            requireAllFound(runCells(ctx, **stage, scene, opt), reference);
        }
    }
}

TEST_CASE("cells: nearly coplanar crossings and shared-edge touching between objects", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), tiny(-1e-6f, 1e-6f);
    CellScene scene;
    HostMesh a, b;
    a.name = "a";
    b.name = "b";
    auto near = [&](Float3 c) { return Float3{c.x + 0.05f * unit(rng), c.y + 0.05f * unit(rng), c.z + 0.02f * unit(rng)}; };
    for (int t = 0; t < 300; ++t) {
        const Float3 c{unit(rng), unit(rng), unit(rng)};
        const Float3 p = near(c), q = near(c), r = near(c);
        addTriangle(a, p, q, r);
        // Nearly the same plane, tilted by about 1e-6 (crossing or just missing).
        addTriangle(b, {p.x + tiny(rng), p.y, p.z + tiny(rng)}, {q.x, q.y + tiny(rng), q.z - tiny(rng)},
                    {r.x, r.y, r.z + tiny(rng)});
        // Shares an edge exactly with a's triangle (touching along it).
        addTriangle(b, p, q, {p.x + 0.01f, p.y - 0.02f, p.z + 0.03f});
    }
    scene.meshes = {a, b};
    const auto reference = referencePairs(scene);
    REQUIRE(reference.size() > 300);
    for (std::uint32_t n : {4u, 128u, 1024u}) {
        for (auto dir : {std::array<double, 3>{0, 0, 1}, std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0.3, 0.4, 0.5}}) {
            INFO("resolution " << n << " direction " << dir[0] << "," << dir[1] << "," << dir[2]);
            CellRunOptions opt;
            opt.resolution = n;
            opt.direction = dir;
            requireAllFound(runCells(ctx, **stage, scene, opt), reference);
        }
    }
}

TEST_CASE("cells: coordinates around 1e6, rotated objects, GPU world rounding", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    SECTION("translated by transforms") {
        CellScene scene;
        scene.meshes.push_back(generated(uvSphere(40.0f, 24, 12), "a"));
        scene.meshes.push_back(generated(torus(40.0f, 12.0f, 32, 12), "b"));
        scene.transforms = {rotation(1, 2, 3, 0.7, {1e6f, -1e6f, 1e6f}), rotation(-2, 1, 0.5, 1.1, {1e6f + 30, -1e6f + 10, 1e6f})};
        scene.self = {0, 1};
        const auto reference = referencePairs(scene);
        REQUIRE(reference.size() > 20);
        for (std::uint32_t n : {8u, 256u}) {
            CellRunOptions opt;
            opt.resolution = n;
            opt.direction = {0.3, -0.5, 1};
            requireAllFound(runCells(ctx, **stage, scene, opt), reference);
        }
    }
    SECTION("positions baked at 1e6") {
        CellScene scene;
        HostMesh a = generated(uvSphere(40.0f, 24, 12), "a"), b = generated(uvSphere(30.0f, 20, 10), "b");
        REQUIRE(transformMesh(a, Transform3x4{1, 0, 0, 1e6f, 0, 1, 0, 2e6f, 0, 0, 1, -1e6f}));
        REQUIRE(transformMesh(b, Transform3x4{1, 0, 0, 1e6f + 50, 0, 1, 0, 2e6f + 10, 0, 0, 1, -1e6f}));
        scene.meshes = {a, b};
        const auto reference = referencePairs(scene);
        REQUIRE(reference.size() > 20);
        CellRunOptions opt;
        opt.resolution = 64;
        requireAllFound(runCells(ctx, **stage, scene, opt), reference);
    }
    SECTION("small rotated objects near the origin") {
        CellScene scene;
        scene.meshes.push_back(generated(torus(1.0f, 0.3f, 48, 16), "a"));
        scene.meshes.push_back(generated(box({0.5f, 0.7f, 0.2f}, 6), "b"));
        scene.meshes.push_back(generated(twistedTube(1.0f, 0.2f, 64, 10, 1.0f), "c"));
        scene.transforms = {rotation(1, 1, 0, 0.3, {0, 0, 0}), rotation(0, 1, 1, 0.9, {0.6f, 0.1f, 0}),
                            rotation(1, 0, 0, 0.2, {-0.2f, 0.3f, 0.1f})};
        scene.self = {0, 0, 1};
        const auto reference = referencePairs(scene);
        REQUIRE(reference.size() > 50);
        for (std::uint32_t n : {16u, 200u}) {
            CellRunOptions opt;
            opt.resolution = n;
            opt.direction = {0.1, 0.2, 1};
            requireAllFound(runCells(ctx, **stage, scene, opt), reference);
        }
    }
}

TEST_CASE("cells: self-collision, the object pair mask and 16-bit indices", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    CellScene scene;
    scene.meshes.push_back(generated(twistedTube(1.0f, 0.2f, 96, 12, 1.5f), "tube"));
    scene.meshes.push_back(generated(uvSphere(0.4f, 16, 8), "ball"));
    scene.meshes.push_back(generated(uvSphere(0.35f, 16, 8), "ball2"));
    scene.transforms = {kIdentityTransform, translation(0.0f, 0.1f, 0.1f), translation(0.2f, 0.0f, 0.0f)};
    for (bool self : {true, false}) {
        scene.self = {std::uint8_t(self ? 1 : 0), 0, 0};
        const auto reference = referencePairs(scene);
        CellRunOptions opt;
        opt.resolution = 96;
        const CellRun run = runCells(ctx, **stage, scene, opt);
        requireAllFound(run, reference);
        bool tube_self = false;
        for (const TrianglePair& p : run.pairs) tube_self = tube_self || (p.object_a == 0 && p.object_b == 0);
        CHECK(tube_self == self);
        opt.index16 = true;
        requireAllFound(runCells(ctx, **stage, scene, opt), reference);
    }
    // Objects 1 and 2 may not collide: no survivor between them, the others all found.
    auto mask = [](std::uint32_t a, std::uint32_t b) { return !(a == 1 && b == 2); };
    scene.self = {1, 0, 0};
    const auto reference = referencePairs(scene, mask);
    const auto unmasked = referencePairs(scene);
    REQUIRE(unmasked.size() > reference.size());
    CellRunOptions opt;
    opt.resolution = 64;
    opt.may_collide = mask;
    const CellRun run = runCells(ctx, **stage, scene, opt);
    requireAllFound(run, reference);
    for (const TrianglePair& p : run.pairs) CHECK(!(p.object_a == 1 && p.object_b == 2));
}

// Touching contacts whose point lies within an ulp of a cell border under an oblique,
// non-dyadic projection: one triangle has the point as a vertex, the other on an edge
// (the exact midpoint of two float vertices), so the two footprints come from different
// roundings of the same place. Without the padding and the error bounds some of these
// pairs share no cell.
TEST_CASE("cells: contacts within an ulp of cell borders", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::array<double, 3> d = {0.3 / 1.0677078, 0.2 / 1.0677078, 1.0 / 1.0677078};
    std::array<double, 3> u = {1 - d[0] * d[0], -d[0] * d[1], -d[0] * d[2]};
    const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= ul;
    const std::array<double, 3> v = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    const double size = 0.61;
    auto row = [&](const std::array<double, 3>& b, double scale) {
        const double c = b[0] * 0.75 + b[1] * 0.75 + b[2] * 0.75;
        return gpu::vec4{float(b[0] / scale), float(b[1] / scale), float(b[2] / scale), float(0.5 - c / scale)};
    };
    gpu::Projection pr{};
    pr.row[0] = row(u, size);
    pr.row[1] = row(v, size);
    pr.row[2] = row(d, size);
    auto dyadic = [&](double lo, double hi) { return float(std::ldexp(std::floor(std::ldexp(lo + (hi - lo) * unit(rng), 24)), -24)); };
    for (std::uint32_t n : {16u, 64u, 100u}) {
        CellScene scene;
        HostMesh a, b;
        a.name = "vertex-side";
        b.name = "edge-side";
        for (int k = 0; k < 1500; ++k) {
            // P with x chosen so that N * sampling x is an integer (in double): within an
            // ulp of a cell border once rounded to float.
            const double target = std::floor(2 + (n - 4) * unit(rng)) / n;
            Float3 p{0, dyadic(0.6, 0.9), dyadic(0.6, 0.9)};
            const double sx = target - pr.row[0].w - double(pr.row[0].y) * p.y - double(pr.row[0].z) * p.z;
            p.x = float(sx / pr.row[0].x);
            if (!(p.x > 0.51f && p.x < 0.99f)) continue;
            // Edge through P (exact midpoint), roughly along the projected y axis; B on the
            // lower-x side, A on the upper-x side.
            // w nearly perpendicular to the image x axis (rounded to multiples of 2^-24, so
            // that p +- w are exact and p is exactly their midpoint).
            const double alpha = 0.01 + 0.02 * unit(rng), beta = 0.02 * (unit(rng) - 0.5);
            auto snap = [](double x) { return float(std::ldexp(std::round(std::ldexp(x, 24)), -24)); };
            const Float3 w{snap(alpha * v[0] + beta * d[0]), snap(alpha * v[1] + beta * d[1]), snap(alpha * v[2] + beta * d[2])};
            const Float3 q1{p.x + w.x, p.y + w.y, p.z + w.z}, q2{p.x - w.x, p.y - w.y, p.z - w.z};
            const double s = (k % 3 == 0) ? 1 : -1;  // which side each is on
            addTriangle(b, q1, q2, {p.x - float(s * 0.03 * u[0]), p.y - float(s * 0.03 * u[1]), p.z - float(s * 0.03 * u[2])});
            addTriangle(a, p, {p.x + float(s * 0.03 * u[0]) + 0.01f, p.y + float(s * 0.02), p.z}, {p.x + float(s * 0.03 * u[0]), p.y - 0.01f, p.z + 0.02f});
        }
        scene.meshes = {a, b};
        const auto reference = referencePairs(scene);
        INFO("resolution " << n << ", reference " << reference.size());
        REQUIRE(reference.size() > 500);
        CellRunOptions opt;
        opt.resolution = n;
        opt.projection = pr;
        requireAllFound(runCells(ctx, **stage, scene, opt), reference);
    }
}

// Vertex-to-vertex contacts through a transform: the CPU's world position of B's vertex
// (M * p in double, rounded once) is exactly A's vertex P, while the GPU's float dot
// products put it an ulp or two away -- and P lies within an ulp of a cell border. Only the
// world-error padding of the footprints and the filter's ulp margin keep these pairs.
TEST_CASE("cells: contacts through transformed vertices on cell borders", "[cells][gpu]") {
    ValidatedContext ctx;
    auto stage = passes::CellStage::create(ctx.device());
    REQUIRE(stage);
    std::mt19937 rng(31337);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Transform m = rotation(0.4, -0.7, 0.55, 0.9, {0.3125f, -0.1875f, 0.40625f});
    auto cpuWorld = [&](Float3 p) {
        auto r = [&](int i) {
            return float(double(m[4 * i]) * p.x + double(m[4 * i + 1]) * p.y + double(m[4 * i + 2]) * p.z + double(m[4 * i + 3]));
        };
        return Float3{r(0), r(1), r(2)};
    };
    // Local position of a world point (the transpose of the rotation undoes it).
    auto local = [&](const std::array<double, 3>& w) {
        const double d[3] = {w[0] - m[3], w[1] - m[7], w[2] - m[11]};
        return Float3{float(m[0] * d[0] + m[4] * d[1] + m[8] * d[2]), float(m[1] * d[0] + m[5] * d[1] + m[9] * d[2]),
                      float(m[2] * d[0] + m[6] * d[1] + m[10] * d[2])};
    };
    for (std::uint32_t n : {32u, 100u}) {
        const double row_scale = n;  // sampling x = 0.5 + (x - 0.75) / 0.61 along a tilted axis
        gpu::Projection pr{};
        pr.row[0] = {float(0.9 / 0.61), float(0.3 / 0.61), float(0.1 / 0.61), float(0.5 - 1.3 * 0.75 / 0.61)};
        pr.row[1] = {float(-0.2 / 0.61), float(0.95 / 0.61), float(0.05 / 0.61), float(0.5 - 0.8 * 0.75 / 0.61)};
        pr.row[2] = {0.1f, 0.2f, 0.9f, 0.1f};
        CellScene scene;
        HostMesh a, b;
        a.name = "identity";
        b.name = "transformed";
        int made = 0;
        for (int k = 0; k < 4000 && made < 1200; ++k) {
            const double target = std::floor(2 + (row_scale - 4) * unit(rng)) / row_scale;
            Float3 p{0, float(0.6 + 0.3 * unit(rng)), float(0.6 + 0.3 * unit(rng))};
            p.x = float((target - pr.row[0].w - double(pr.row[0].y) * p.y - double(pr.row[0].z) * p.z) / pr.row[0].x);
            if (!(p.x > 0.3f && p.x < 1.2f)) continue;
            // B's vertex: a local point whose CPU world position is exactly p.
            Float3 pb = local({p.x, p.y, p.z});
            bool exact = false;
            for (int t = 0; t < 27 && !exact; ++t) {
                Float3 c = pb;
                c.x = std::nextafter(c.x, t % 3 == 0 ? c.x : (t % 3 == 1 ? 10.0f : -10.0f));
                c.y = std::nextafter(c.y, (t / 3) % 3 == 0 ? c.y : ((t / 3) % 3 == 1 ? 10.0f : -10.0f));
                c.z = std::nextafter(c.z, t / 9 == 0 ? c.z : (t / 9 == 1 ? 10.0f : -10.0f));
                const Float3 w = cpuWorld(c);
                if (w.x == p.x && w.y == p.y && w.z == p.z) {
                    pb = c;
                    exact = true;
                }
            }
            if (!exact) continue;
            ++made;
            const double s = (k % 2 == 0) ? 1 : -1;
            addTriangle(a, p, {p.x + float(s * 0.02), p.y + 0.01f, p.z - 0.005f}, {p.x + float(s * 0.015), p.y - 0.012f, p.z + 0.01f});
            addTriangle(b, pb, local({p.x - s * 0.02, p.y + 0.013, p.z + 0.004}), local({p.x - s * 0.017, p.y - 0.01, p.z - 0.008}));
        }
        REQUIRE(made > 500);
        scene.meshes = {a, b};
        scene.transforms = {kIdentityTransform, m};
        const auto reference = referencePairs(scene);
        INFO("resolution " << n << ", contacts " << made << ", reference " << reference.size());
        REQUIRE(reference.size() >= std::size_t(made));
        CellRunOptions opt;
        opt.resolution = n;
        opt.projection = pr;
        requireAllFound(runCells(ctx, **stage, scene, opt), reference);
    }
}
