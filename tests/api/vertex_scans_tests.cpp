// The world's passes over host positions (src/api/vertex_scans.cpp), host only: the one
// pass of updateVertices split over executors gives a plain loop's copy, box and first bad
// vertex on every thread count and write order, and the shape measurement does not depend
// on the executor.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "api/vertex_scans.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using vertex_scans::UploadWrites;

namespace {

// Positions with every coordinate's sign and a spread of magnitudes; the extremes sit at
// known vertices so the box is not found by accident at index 0.
std::vector<Float3> randomPositions(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-100.0f, 100.0f);
    std::vector<Float3> p(n);
    for (Float3& v : p) v = {u(rng), u(rng) * 0.5f, u(rng) * 2.0f};
    return p;
}

struct Reference {
    std::array<float, 6> box{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    float max_abs = 0;
    std::size_t first_bad = SIZE_MAX;
};

Reference reference(const std::vector<Float3>& p) {
    Reference r;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const float c[3] = {p[i].x, p[i].y, p[i].z};
        bool ok = true;
        for (int a = 0; a < 3; ++a) ok = ok && std::isfinite(c[a]);
        if (!ok) {
            if (r.first_bad == SIZE_MAX) r.first_bad = i;
            continue;
        }
        for (int a = 0; a < 3; ++a)
            r.box[a] = std::min(r.box[a], c[a]), r.box[a + 3] = std::max(r.box[a + 3], c[a]), r.max_abs = std::max(r.max_abs, std::fabs(c[a]));
    }
    return r;
}

// Executors of 1, 3 and 4 threads, and an engine's job system that runs its tasks in
// reverse order (results must not depend on the order chunks run in).
std::vector<std::unique_ptr<Executor>> executors() {
    std::vector<std::unique_ptr<Executor>> out;
    out.push_back(std::make_unique<ThreadPool>(1));
    out.push_back(std::make_unique<ThreadPool>(3));
    out.push_back(std::make_unique<ThreadPool>(4));
    out.push_back(std::make_unique<CallbackExecutor>(8, [](std::size_t n, const std::function<void(std::size_t)>& task) {
        for (std::size_t k = n; k-- > 0;) task(k);
    }));
    return out;
}

bool sameBits(const std::vector<Float3>& a, const std::vector<Float3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Float3)) == 0;
}

// A grid of n x n quads with a bump: edges of several lengths, normals of every sign.
void grid(std::uint32_t n, std::vector<Float3>& p, std::vector<std::uint32_t>& idx) {
    p.clear(), idx.clear();
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) {
            const float x = float(i) / float(n), y = float(j) / float(n) * 1.5f;
            p.push_back({x, y, 0.2f * std::sin(6 * x) * std::cos(4 * y)});
        }
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            idx.insert(idx.end(), {a, b, d, a, d, c});
        }
}

}  // namespace

TEST_CASE("updateVertices' pass copies and boxes exactly on every executor and size", "[api][host]") {
    const auto pool = executors();
    // Around the chunk and block sizes: 1 vertex, tails of 1-3 vertices after blocks of
    // four, one chunk exactly, one vertex more, and many chunks.
    const std::size_t k = vertex_scans::kMinChunkVertices;
    for (std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{5}, std::size_t{17}, k - 1, k, k + 1, 4 * k + 7, std::size_t{300001}}) {
        const std::vector<Float3> in = randomPositions(n, std::uint32_t(n));
        const Reference want = reference(in);
        for (const auto& ex : pool)
            for (UploadWrites writes : {UploadWrites::Fused, UploadWrites::Staged})
                for (bool with_upload : {true, false}) {
                    INFO("vertices " << n << ", threads " << ex->threadCount() << ", staged " << (writes == UploadWrites::Staged)
                                     << ", upload " << with_upload);
                    std::vector<Float3> out(n, Float3{7, 7, 7}), upload(n, Float3{9, 9, 9});
                    const auto got = vertex_scans::copyAndScan(*ex, in, out, with_upload ? upload.data() : nullptr, writes);
                    CHECK(got.finite);
                    CHECK(got.box == want.box);
                    CHECK(got.max_abs == want.max_abs);
                    CHECK(sameBits(out, in));
                    if (with_upload) CHECK(sameBits(upload, in));
                    else CHECK(sameBits(upload, std::vector<Float3>(n, Float3{9, 9, 9})));
                }
    }
}

TEST_CASE("updateVertices' pass names the first NaN or infinite vertex whichever chunk holds it", "[api][host]") {
    const auto pool = executors();
    const std::size_t n = 5 * vertex_scans::kMinChunkVertices + 3;
    const std::vector<Float3> clean = randomPositions(n, 11);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Case {
        std::vector<std::size_t> bad;  // vertices spoilt, in any order
        int component;
        float value;
    };
    // The first vertex, the last (the tail after the last block of four, in the last
    // chunk), both ends of a chunk boundary, two bad vertices in different chunks, and
    // every component, NaN and both infinities.
    const std::size_t k = vertex_scans::kMinChunkVertices;
    const Case cases[] = {{{0}, 0, nan},          {{n - 1}, 2, nan},          {{n - 2, n - 1}, 1, -inf},
                          {{k - 1}, 1, inf},      {{k}, 0, nan},              {{4 * k + 9, 2 * k + 5}, 2, -inf},
                          {{3 * k + 2, n - 1}, 0, inf}};
    for (const Case& c : cases) {
        std::vector<Float3> in = clean;
        std::size_t first = SIZE_MAX;
        for (std::size_t i : c.bad) {
            (c.component == 0 ? in[i].x : c.component == 1 ? in[i].y : in[i].z) = c.value;
            first = std::min(first, i);
        }
        REQUIRE(reference(in).first_bad == first);
        for (const auto& ex : pool)
            for (UploadWrites writes : {UploadWrites::Fused, UploadWrites::Staged}) {
                INFO("first bad " << first << ", threads " << ex->threadCount() << ", staged " << (writes == UploadWrites::Staged));
                std::vector<Float3> out(n), upload(n);
                const auto got = vertex_scans::copyAndScan(*ex, in, out, upload.data(), writes);
                CHECK_FALSE(got.finite);
                CHECK(got.first_bad == first);
                CHECK(sameBits(out, in));  // still copied: the caller decides (updateVertices restores the upload)
                CHECK(sameBits(upload, in));
            }
    }
}

TEST_CASE("copy, scan and shape in one loop: the copy and scan of copyAndScan, the shape of measureShape, bit for bit",
          "[api][host]") {
    const auto pool = executors();
    std::vector<Float3> p;
    std::vector<std::uint32_t> idx;
    for (std::uint32_t n : {1u, 16u, 45u, 300u}) {  // 2 to 180,000 triangles: one run to eight, one chunk to many
        grid(n, p, idx);
        for (const auto& ex : pool) {
            INFO("grid " << n << ", threads " << ex->threadCount());
            std::vector<Float3> out(p.size()), upload(p.size()), plain_out(p.size()), plain_upload(p.size());
            vertex_scans::Shape shape;
            const auto got = vertex_scans::copyScanAndMeasure(*ex, p, out, upload.data(), idx, shape);
            const auto want = vertex_scans::copyAndScan(*ex, p, plain_out, plain_upload.data());
            CHECK(got.finite);
            CHECK(got.box == want.box);
            CHECK(got.max_abs == want.max_abs);
            CHECK(sameBits(out, p));
            CHECK(sameBits(upload, p));
            const auto alone = vertex_scans::measureShape(*ex, out, idx);
            CHECK(shape.edge_length == alone.edge_length);
            CHECK(shape.area_moment == alone.area_moment);
        }
    }
    // A non-finite vertex: named as copyAndScan names it, the shape left as it was.
    grid(45, p, idx);
    p[1000].y = std::numeric_limits<float>::quiet_NaN();
    for (const auto& ex : pool) {
        std::vector<Float3> out(p.size());
        vertex_scans::Shape shape;
        shape.edge_length = 7.0f;
        const auto got = vertex_scans::copyScanAndMeasure(*ex, p, out, nullptr, idx, shape);
        CHECK_FALSE(got.finite);
        CHECK(got.first_bad == 1000u);
        CHECK(shape.edge_length == 7.0f);
    }
}

TEST_CASE("the shape measure is the same on every executor, and a plain loop's on small meshes", "[api][host]") {
    const auto pool = executors();
    std::vector<Float3> p;
    std::vector<std::uint32_t> idx;
    SECTION("small: one run of triangles, the plain loop's sums bit for bit") {
        grid(16, p, idx);  // 512 triangles (one run of kShapeChunk), all sampled
        double sum = 0;
        std::array<double, 6> m{};
        std::array<double, 3> axis_area{};
        for (std::size_t t = 0; t < idx.size(); t += 3) {
            const Float3 q[3] = {p[idx[t]], p[idx[t + 1]], p[idx[t + 2]]};
            auto d = [](const Float3& a, const Float3& b) {
                const double x = double(a.x) - b.x, y = double(a.y) - b.y, z = double(a.z) - b.z;
                return std::sqrt(x * x + y * y + z * z);
            };
            sum += d(q[0], q[1]) + d(q[1], q[2]) + d(q[2], q[0]);
            const double u[3] = {double(q[1].x) - q[0].x, double(q[1].y) - q[0].y, double(q[1].z) - q[0].z};
            const double v[3] = {double(q[2].x) - q[0].x, double(q[2].y) - q[0].y, double(q[2].z) - q[0].z};
            const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
            const double w = 0.5 / std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            m[0] += w * c[0] * c[0], m[1] += w * c[1] * c[1], m[2] += w * c[2] * c[2];
            m[3] += w * c[0] * c[1], m[4] += w * c[0] * c[2], m[5] += w * c[1] * c[2];
            for (int a = 0; a < 3; ++a)
                if (std::fabs(c[a]) >= vertex_scans::kAxisFaceCos * (0.5 / w)) axis_area[a] += 0.25 / w;
        }
        for (const auto& ex : pool) {
            const auto s = vertex_scans::measureShape(*ex, p, idx);
            CHECK(s.edge_length == static_cast<float>(sum / double(idx.size())));
            CHECK(s.area_moment == m);
            CHECK(s.axis_area == axis_area);
        }
    }
    SECTION("large: sampled in runs, the same on every executor") {
        grid(300, p, idx);  // 180,000 triangles: 128 blocks of 32 consecutive ones sampled, 4,096 in 8 runs
        const auto first = vertex_scans::measureShape(*pool[0], p, idx);
        CHECK(first.edge_length > 0.003f);
        CHECK(first.edge_length < 0.006f);
        // The moment's trace is the area: the sample, scaled, estimates all triangles' area.
        double area = 0;
        for (std::size_t t = 0; t < idx.size(); t += 3) {
            const Float3 a = p[idx[t]], b = p[idx[t + 1]], c = p[idx[t + 2]];
            const double u[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
            const double v[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
            area += 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                                    std::pow(u[0] * v[1] - u[1] * v[0], 2));
        }
        const auto& m = first.area_moment;
        CHECK(m[0] + m[1] + m[2] == Approx(area).epsilon(0.01));
        CHECK(m[2] > m[0]);  // mostly facing z
        CHECK(m[2] > m[1]);
        for (const auto& ex : pool) {
            const auto s = vertex_scans::measureShape(*ex, p, idx);
            CHECK(s.edge_length == first.edge_length);
            CHECK(s.area_moment == first.area_moment);
        }
    }
}

TEST_CASE("the area facing each axis: a box's faces, none of a sphere's, a turned box's by its own axes", "[api][host]") {
    ThreadPool pool(2);
    // A box of half extents (1, 2, 3): faces of area 4 x 6 (normal x), 2 x 6 (y), 2 x 4 (z).
    auto b = box({1, 2, 3}, 4);
    REQUIRE(b);
    const auto s = vertex_scans::measureShape(pool, b->positions, b->indices);
    CHECK(s.axis_area[0] == Approx(2 * 24.0));
    CHECK(s.axis_area[1] == Approx(2 * 12.0));
    CHECK(s.axis_area[2] == Approx(2 * 8.0));
    // Turned by 30 degrees about z: only the z faces still face an axis.
    HostMesh turned = *b;
    const float c = std::cos(0.5236f), sn = std::sin(0.5236f);
    for (Float3& v : turned.positions) v = {c * v.x - sn * v.y, sn * v.x + c * v.y, v.z};
    const auto t = vertex_scans::measureShape(pool, turned.positions, turned.indices);
    CHECK(t.axis_area[0] == 0);
    CHECK(t.axis_area[1] == 0);
    CHECK(t.axis_area[2] == Approx(2 * 8.0).epsilon(1e-5));
    // A sphere's triangles face no axis to within a degree, but for a few at the poles.
    auto sphere = icosphere(1.0f, 4);
    REQUIRE(sphere);
    const auto q = vertex_scans::measureShape(pool, sphere->positions, sphere->indices);
    const double area = q.area_moment[0] + q.area_moment[1] + q.area_moment[2];
    CHECK(q.axis_area[0] + q.axis_area[1] + q.axis_area[2] < 0.01 * area);
}

TEST_CASE("several shapes measured in one loop are each mesh's own measure, exactly", "[api][host]") {
    const auto pool = executors();
    // Sizes around the sampling limit and the run length, and a mesh without triangles
    // between two others (it owns no run).
    std::vector<std::vector<Float3>> positions;
    std::vector<std::vector<std::uint32_t>> indices;
    for (std::uint32_t n : {300u, 0u, 20u, 1u, 100u}) {
        std::vector<Float3> p;
        std::vector<std::uint32_t> idx;
        if (n > 0) grid(n, p, idx);
        else p = randomPositions(3, 1);
        positions.push_back(std::move(p));
        indices.push_back(std::move(idx));
    }
    std::vector<vertex_scans::ShapeMesh> meshes;
    for (std::size_t i = 0; i < positions.size(); ++i) meshes.push_back({positions[i], indices[i]});
    for (const auto& ex : pool) {
        std::vector<vertex_scans::Shape> shapes(meshes.size());
        vertex_scans::measureShapes(*ex, meshes, shapes);
        for (std::size_t i = 0; i < meshes.size(); ++i) {
            INFO("mesh " << i);
            const auto alone = vertex_scans::measureShape(*ex, positions[i], indices[i]);
            CHECK(shapes[i].edge_length == alone.edge_length);
            CHECK(shapes[i].area_moment == alone.area_moment);
            CHECK(shapes[i].axis_area == alone.axis_area);
        }
        CHECK(shapes[1].edge_length == 0.0f);
    }
}
