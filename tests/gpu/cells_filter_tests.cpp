// The GPU triangle-triangle filter (spirv/cells/tritri_filter.glsl.inc) alone, against the exact
// test of the narrow phase (src/narrow/triangle_intersection.hpp): it must never reject an
// intersecting pair -- touching, coplanar, degenerate, near-coplanar, slivers, 1e6
// coordinates, and inputs an ulp or more away from the exact ones with that distance as
// its margin -- and it should reject most disjoint pairs (the counts are printed with -s).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "cells/cells.h"
#include "graph/executor.hpp"
#include "narrow/triangle_intersection.hpp"
#include "support/gpu_fixture.hpp"
#include "support/record_dispatch.hpp"
#include "test_shaders/all.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

using Tri = std::array<Float3, 3>;

struct Case {
    Tri a, b;            // what the filter sees
    Tri exact_a, exact_b;  // what the exact test decides on (the "CPU" positions)
    float eps = 0;       // the filter's margin: |seen - exact| per coordinate, bounded
};

// Runs the filter on every case; 1 = rejected (proved disjoint).
std::vector<std::uint32_t> runFilter(ValidatedContext& ctx, const std::vector<Case>& cases) {
    vk::Device& device = ctx.device();
    auto pipeline = vk::Pipeline::createCompute(device, shaders::cells_filter_test_comp, {}, sizeof(gpu::Push), "filter-test");
    REQUIRE(pipeline);
    const std::size_t n = cases.size();
    auto params = vk::Buffer::create(device, sizeof(gpu::CellsFilterParams), 0, vk::MemoryKind::Upload, "filter-params");
    auto input = vk::Buffer::create(device, n * sizeof(gpu::CellsFilterCase), 0, vk::MemoryKind::Upload, "filter-cases");
    auto verdict = vk::Buffer::create(device, n * 4, 0, vk::MemoryKind::Readback, "filter-verdict");
    REQUIRE(params);
    REQUIRE(input);
    REQUIRE(verdict);
    auto* out_cases = static_cast<gpu::CellsFilterCase*>(input->mapped());
    for (std::size_t i = 0; i < n; ++i) {
        std::memcpy(out_cases[i].a, cases[i].a.data(), 36);
        std::memcpy(out_cases[i].b, cases[i].b.data(), 36);
        out_cases[i].eps_a = out_cases[i].eps_b = cases[i].eps;
    }
    input->flush();
    gpu::CellsFilterParams fp{input->address(), verdict->address(), static_cast<std::uint32_t>(n), 0};
    std::memcpy(params->mapped(), &fp, sizeof fp);
    params->flush();
    graph::Graph g;
    const auto in_id = g.importBuffer("filter-cases", *input);
    const auto out_id = g.importBuffer("filter-verdict", *verdict, true);
    const VkPipeline handle = pipeline->handle();
    const VkPipelineLayout layout = pipeline->layout();
    const VkDeviceAddress params_address = params->address();
    const auto groups = static_cast<std::uint32_t>((n + gpu::kCellsGroupSize - 1) / gpu::kCellsGroupSize);
    g.addPass("filter", graph::PassKind::Compute).read(in_id).write(out_id).record([=](graph::PassContext& pc) {
        gpu::Push push{params_address, 0, 0, 0, 0};
        recordDispatch(pc, handle, layout, push, groups);
    });
    graph::Executor executor(device);
    REQUIRE(executor.run(g));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    verdict->invalidate();
    std::vector<std::uint32_t> result(n);
    std::memcpy(result.data(), verdict->mapped(), n * 4);
    return result;
}

struct Tally {
    std::size_t intersecting = 0, rejected_intersecting = 0, disjoint = 0, rejected_disjoint = 0;
};

// Checks the filter on `cases` and reports how many disjoint pairs it rejected.
Tally check(ValidatedContext& ctx, const char* what, const std::vector<Case>& cases) {
    const std::vector<std::uint32_t> verdict = runFilter(ctx, cases);
    Tally t;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const bool hit = narrow::trianglesIntersect(cases[i].exact_a, cases[i].exact_b);
        if (hit) {
            ++t.intersecting;
            if (verdict[i]) {
                ++t.rejected_intersecting;
                const Case& c = cases[i];
                UNSCOPED_INFO(what << ": rejected intersecting case " << i << std::hexfloat << " a0 " << c.a[0].x << ","
                                   << c.a[0].y << "," << c.a[0].z << " eps " << c.eps);
            }
        } else {
            ++t.disjoint;
            t.rejected_disjoint += verdict[i];
        }
    }
    INFO(what << ": " << t.intersecting << " intersecting, " << t.disjoint << " disjoint, rejected " << t.rejected_disjoint);
    CHECK(t.rejected_intersecting == 0);
    std::printf("filter %-28s intersecting %6zu (rejected %zu)  disjoint %6zu  rejected %6zu (%.1f %%)\n", what, t.intersecting,
                t.rejected_intersecting, t.disjoint, t.rejected_disjoint,
                t.disjoint ? 100.0 * double(t.rejected_disjoint) / double(t.disjoint) : 0.0);
    return t;
}

Case plain(const Tri& a, const Tri& b) { return {a, b, a, b, 0.0f}; }

// Exact symmetries: axis permutation, sign flips, a dyadic scale and translation.
Tri transformExact(const Tri& t, int perm, int signs, float scale, Float3 shift) {
    Tri out;
    for (int k = 0; k < 3; ++k) {
        const float c[3] = {t[k].x, t[k].y, t[k].z};
        const int p0 = perm % 3, p1 = (perm / 3 + p0 + 1) % 3, p2 = 3 - p0 - p1;
        float v[3] = {c[p0], c[p1], c[p2]};
        for (int a = 0; a < 3; ++a)
            if (signs & (1 << a)) v[a] = -v[a];
        out[k] = {v[0] * scale + shift.x, v[1] * scale + shift.y, v[2] * scale + shift.z};
    }
    return out;
}

float dyadic(std::mt19937& rng, int bits = 8) {
    std::uniform_int_distribution<int> d(-(1 << bits), 1 << bits);
    return std::ldexp(float(d(rng)), -bits);
}
Float3 dyadic3(std::mt19937& rng, int bits = 8) { return {dyadic(rng, bits), dyadic(rng, bits), dyadic(rng, bits)}; }

}  // namespace

TEST_CASE("cells filter: random pairs", "[cells][gpu][filter]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) {
        WARN("the device has no shaderFloat64: the filter is not used there");
        return;
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), small(-0.15f, 0.15f);
    std::vector<Case> cases;
    for (int i = 0; i < 20000; ++i) {
        const Float3 ca{unit(rng), unit(rng), unit(rng)}, cb{ca.x + small(rng), ca.y + small(rng), ca.z + small(rng)};
        Tri a, b;
        for (int k = 0; k < 3; ++k) {
            a[k] = {ca.x + small(rng), ca.y + small(rng), ca.z + small(rng)};
            b[k] = {cb.x + small(rng), cb.y + small(rng), cb.z + small(rng)};
        }
        cases.push_back(plain(a, b));
    }
    const Tally t = check(ctx, "random", cases);
    CHECK(t.intersecting > 1000);
    CHECK(100 * t.rejected_disjoint > 99 * t.disjoint);
}

TEST_CASE("cells filter: exact touching, shared vertices and edges, coplanar pairs", "[cells][gpu][filter]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    std::mt19937 rng(2);
    std::vector<Case> cases;
    for (int i = 0; i < 4000; ++i) {
        // A in the plane z = c; points in it are exact dyadic combinations.
        const float c = dyadic(rng);
        Tri a = {Float3{dyadic(rng), dyadic(rng), c}, Float3{dyadic(rng), dyadic(rng), c}, Float3{dyadic(rng), dyadic(rng), c}};
        const Float3 inside{(a[0].x + a[1].x + 2 * a[2].x) / 4, (a[0].y + a[1].y + 2 * a[2].y) / 4, c};
        const Float3 mid{(a[0].x + a[1].x) / 2, (a[0].y + a[1].y) / 2, c};
        const float up = std::fabs(dyadic(rng)) + 0.0625f;
        const float side = (i % 2) ? up : -up;
        std::vector<Tri> bs = {
            {inside, Float3{inside.x + dyadic(rng), inside.y + dyadic(rng), c + side}, Float3{inside.x + dyadic(rng), inside.y, c + up}},  // vertex on face
            {a[1], Float3{dyadic(rng), dyadic(rng), c + side}, Float3{dyadic(rng), dyadic(rng), c - up}},  // shared vertex
            {a[0], a[1], Float3{dyadic(rng), dyadic(rng), c + side}},  // shared edge
            {Float3{mid.x + 0.25f, mid.y - 0.125f, c + up}, Float3{mid.x - 0.25f, mid.y + 0.125f, c - up}, Float3{mid.x + 0.5f, mid.y, c + side}},  // edge through the edge
            {Float3{dyadic(rng), dyadic(rng), c}, Float3{dyadic(rng), dyadic(rng), c}, Float3{dyadic(rng), dyadic(rng), c}},  // coplanar
            {a[0], a[1], Float3{2 * mid.x - a[2].x, 2 * mid.y - a[2].y, c}},  // coplanar, shared edge only
            {mid, Float3{mid.x + 2 * (mid.x - a[2].x), mid.y + 2 * (mid.y - a[2].y), c}, Float3{mid.x, mid.y, c + side}},  // edge-on touching
            {a[0], a[0], Float3{a[0].x + dyadic(rng), a[0].y, c + side}},  // degenerate, touching at a vertex
        };
        for (const Tri& b : bs) {
            const int perm = i % 6, signs = (i / 6) % 8;
            const float scale = std::ldexp(1.0f, (i % 11) - 5);
            const Float3 shift = dyadic3(rng, 4);
            cases.push_back(plain(transformExact(a, perm, signs, scale, shift), transformExact(b, perm, signs, scale, shift)));
        }
    }
    const Tally t = check(ctx, "exact contacts", cases);
    CHECK(t.intersecting > 20000);
    // Coplanar disjoint pairs (flat cloth, box faces) are proved apart in the plane.
    CHECK(t.disjoint > 1000);
    CHECK(t.rejected_disjoint == t.disjoint);
}

TEST_CASE("cells filter: near-coplanar crossings, slivers and needles, 1e6 coordinates", "[cells][gpu][filter]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), tiny(-1.0f, 1.0f);
    auto randomTri = [&](float scale, Float3 at) {
        return Tri{Float3{at.x + scale * unit(rng), at.y + scale * unit(rng), at.z + scale * unit(rng)},
                   Float3{at.x + scale * unit(rng), at.y + scale * unit(rng), at.z + scale * unit(rng)},
                   Float3{at.x + scale * unit(rng), at.y + scale * unit(rng), at.z + scale * unit(rng)}};
    };
    for (float offset : {0.0f, 1e6f}) {
        std::vector<Case> coplanar, slivers;
        for (int i = 0; i < 10000; ++i) {
            const Float3 at{offset, -offset, offset};
            const float scale = offset > 0 ? 100.0f : 1.0f;
            const Tri a = randomTri(scale, at);
            const float amount = std::ldexp(1.0f, -(i % 30)) * scale;  // 1 .. 2^-29 times the size
            Tri b = a;
            for (Float3& v : b) v = {v.x + amount * tiny(rng), v.y + amount * tiny(rng), v.z + amount * tiny(rng)};
            std::swap(b[1], b[2]);
            coplanar.push_back(plain(a, b));
            // A sliver: nearly collinear, crossing a needle.
            const Float3 p = a[0], q = a[1];
            const Tri sliver = {p, q, Float3{(p.x + q.x) / 2 + amount * tiny(rng), (p.y + q.y) / 2 + amount * tiny(rng), (p.z + q.z) / 2}};
            const Float3 m{(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2};
            const Tri needle = {Float3{m.x, m.y, m.z - scale}, Float3{m.x + amount * tiny(rng), m.y, m.z + scale},
                                Float3{m.x, m.y + amount * tiny(rng), m.z + scale}};
            slivers.push_back(plain(sliver, needle));
            slivers.push_back(plain(sliver, b));
        }
        const Tally c = check(ctx, offset > 0 ? "near-coplanar at 1e6" : "near-coplanar", coplanar);
        const Tally s = check(ctx, offset > 0 ? "slivers, needles at 1e6" : "slivers, needles", slivers);
        CHECK(c.intersecting > 1000);
        CHECK(s.intersecting > 1000);
    }
}

TEST_CASE("cells filter: inputs away from the exact ones by up to eps", "[cells][gpu][filter]") {
    ValidatedContext ctx;
    if (!ctx.device().shader_float64) return;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> ulps(-3, 3);
    // The filter sees each coordinate moved by up to 3 ulps (as a GPU's float transform
    // may move it against the CPU's), with eps bounding the move; the exact test decides on
    // the unmoved ones. Touching pairs are the hard part: moved, many are apart.
    auto nudge = [&](float x) {
        int n = ulps(rng);
        while (n > 0) x = std::nextafter(x, 1e30f), --n;
        while (n < 0) x = std::nextafter(x, -1e30f), ++n;
        return x;
    };
    std::vector<Case> cases;
    for (int i = 0; i < 20000; ++i) {
        const float c = std::ldexp(float(i % 64 + 1), -6);
        const float big = (i % 3 == 0) ? 1e6f : 1.0f;
        const Tri a = {Float3{big * unit(rng), big * unit(rng), c}, Float3{big * unit(rng), big * unit(rng), c},
                       Float3{big * unit(rng), big * unit(rng), c}};
        const Float3 mid{(a[0].x + a[1].x) * 0.5f, (a[0].y + a[1].y) * 0.5f, c};
        const Tri b = {a[i % 3], Float3{mid.x, mid.y, c + big * unit(rng)}, Float3{big * unit(rng), big * unit(rng), c - (i % 2 ? 1 : -1) * big * unit(rng)}};
        Case k{a, b, a, b, 0};
        float moved = 0;
        for (Tri* t : {&k.a, &k.b})
            for (Float3& v : *t) {
                const Float3 before = v;
                v = {nudge(v.x), nudge(v.y), nudge(v.z)};
                moved = std::max({moved, std::fabs(v.x - before.x), std::fabs(v.y - before.y), std::fabs(v.z - before.z)});
            }
        k.eps = moved;
        cases.push_back(k);
    }
    const Tally t = check(ctx, "moved by eps", cases);
    CHECK(t.intersecting > 5000);
}
