// The typed projection module (src/broad/projection.hpp): the basis, the region's and the
// fit's projections, the inverse used by the multi-axis union, and, on the device, that the
// host's repetition of the fit equals what fit.comp.glsl computed.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "broad/broad_phase.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "broad/projection.hpp"
#include "mesh/mesh_upload.hpp"
#include "support/gpu_fixture.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::passes;

namespace {

double dot(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
}

// Distance in units in the last place between two floats of the same sign.
std::int64_t ulps(float a, float b) {
    if (a == b) return 0;
    if (std::signbit(a) != std::signbit(b)) return 1 << 30;
    return std::llabs(std::int64_t(std::bit_cast<std::int32_t>(a)) - std::int64_t(std::bit_cast<std::int32_t>(b)));
}

std::int64_t maxUlps(const gpu::Projection& a, const gpu::Projection& b) {
    std::int64_t worst = 0;
    for (int r = 0; r < 3; ++r) {
        worst = std::max({worst, ulps(a.row[r].x, b.row[r].x), ulps(a.row[r].y, b.row[r].y), ulps(a.row[r].z, b.row[r].z),
                          ulps(a.row[r].w, b.row[r].w)});
    }
    return std::max({worst, ulps(a.open_epsilon, b.open_epsilon), ulps(a.world_to_depth, b.world_to_depth),
                     ulps(a.closed_epsilon, b.closed_epsilon)});
}

}  // namespace

TEST_CASE("the projection basis is orthonormal with u x v = d", "[projection]") {
    for (const std::array<float, 3>& dir : {std::array<float, 3>{0, 0, 1}, {1, 0, 0}, {0, -2, 0}, {0.2f, -0.3f, 1.0f}, {0.95f, 0.1f, 0.0f}}) {
        const ProjectionBasis b = projectionBasis(dir);
        CHECK(dot(b.u, b.u) == Approx(1.0).margin(1e-6));
        CHECK(dot(b.v, b.v) == Approx(1.0).margin(1e-6));
        CHECK(dot(b.u, b.v) == Approx(0.0).margin(1e-6));
        CHECK(dot(b.u, b.d) == Approx(0.0).margin(1e-6));
        const double len = std::sqrt(dot(dir, dir));
        CHECK(dot(b.d, dir) / len == Approx(1.0).margin(1e-6));
        const std::array<float, 3> cross{b.u[1] * b.v[2] - b.u[2] * b.v[1], b.u[2] * b.v[0] - b.u[0] * b.v[2], b.u[0] * b.v[1] - b.u[1] * b.v[0]};
        CHECK(dot(cross, b.d) == Approx(1.0).margin(1e-6));
    }
    // Axis directions give exact axes (the automatic direction is always one).
    const ProjectionBasis z = projectionBasis({0, 0, 1});
    CHECK(z.u == std::array<float, 3>{1, 0, 0});
    CHECK(z.v == std::array<float, 3>{0, 1, 0});
}

TEST_CASE("a region maps into the image and the depth range, and the inverse maps back", "[projection]") {
    const std::array<float, 6> region{-1.0f, -2.0f, 0.5f, 3.0f, 1.0f, 1.5f};
    const gpu::Projection p = regionProjection(projectionBasis({0, 0, 1}), region, 0.1f, 0.01f);
    // The region's corners: x, y in [0, 1] (the wider extent spans it), depth in [near, near + span].
    const auto lo = toSampling(p, {region[0], region[1], region[2]}), hi = toSampling(p, {region[3], region[4], region[5]});
    CHECK(lo[0] == Approx(0.0).margin(1e-6));
    CHECK(hi[0] == Approx(1.0).margin(1e-6));
    CHECK(lo[1] == Approx(0.125).margin(1e-6));  // 3 of 4 units, centred
    CHECK(hi[1] == Approx(0.875).margin(1e-6));
    CHECK(lo[2] == Approx(gpu::kDepthNear).margin(1e-6));
    CHECK(hi[2] == Approx(gpu::kDepthNear + gpu::kDepthSpan).margin(1e-6));
    CHECK(p.open_epsilon == Approx(0.1f * gpu::kDepthSpan));
    CHECK(p.closed_epsilon == Approx(0.01f * gpu::kDepthSpan));
    CHECK(imageWidth(p) == Approx(4.0));
    // The inverse of a sampling box is the world box it came from (oblique direction too).
    for (const std::array<float, 3>& dir : {std::array<float, 3>{0, 0, 1}, {0.2f, -0.3f, 1.0f}}) {
        const gpu::Projection q = regionProjection(projectionBasis(dir), region, 0, 0);
        const std::array<float, 3> point{0.3f, -0.4f, 1.1f};
        const auto s = toSampling(q, point);
        const auto w = samplingBoxToWorld(q, {s[0], s[1], s[2]}, {s[0], s[1], s[2]});
        for (int a = 0; a < 3; ++a) {
            CHECK(w[a] == Approx(point[a]).margin(1e-5));
            CHECK(w[a + 3] == Approx(point[a]).margin(1e-5));
        }
    }
}

TEST_CASE("the host's fit equals the fit the GPU computed", "[gpu][projection]") {
    test::ValidatedContext ctx;
    auto sphere = uvSphere(1.0f, 24, 12);
    auto cube = box({0.7f, 0.4f, 1.3f}, 2);
    REQUIRE(sphere);
    REQUIRE(cube);
    REQUIRE(transformMesh(*cube, Transform3x4{1, 0, 0, 0.6f, 0, 0, -1, -0.11f, 0, 1, 0, 0.29f}));
    auto up = uploadMeshes(ctx.device(), {&*sphere, &*cube});
    REQUIRE(up);
    auto bp = BroadPhase::create(ctx.device(), PeelingMethod::create);
    REQUIRE(bp);
    std::int64_t worst = 0;
    for (const std::array<float, 3>& dir : {std::array<float, 3>{0, 0, 1}, {0.2f, -0.3f, 1.0f}, {1, 0.5f, 0.25f}}) {
        for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
            BroadPhaseSettings s;
            s.resolution = 64;
            s.direction = dir;
            s.backend = backend;
            s.open_epsilon = 0.02f;
            s.closed_epsilon = 0.001f;
            auto r = (*bp)->run(up->meshes, s);
            REQUIRE(r);
            const gpu::Projection gpu_fit = (*bp)->gpuProjection();
            INFO("direction " << dir[0] << ", " << dir[1] << ", " << dir[2]);
            // Vulkan lets a GPU's division be 2.5 ulps from the rounded quotient; on lavapipe the
            // two agree exactly (the line printed below says how far apart they are here).
            const std::int64_t d = maxUlps(gpu_fit, r->projection);
            CHECK(d <= 2);
            worst = std::max(worst, d);
        }
    }
    std::printf("projection | host fit vs GPU fit: at most %lld ulps apart\n", static_cast<long long>(worst));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
