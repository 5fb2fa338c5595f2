// Session 60, development machine: the shape measurement's loop (vertex_scans.cpp, shapeRun) on
// 4,096 triangles of a 160x157 UV sphere. Built as 'g++ -O3 -std=c++20 session60_shape_loop.cpp'
// (simd.inc beside it: session60_shape_simd.inc); with the axis areas' branch put back (the
// 'if' form) it ran 0.065 ms, as here 0.049 ms (variant 0).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <chrono>
#include <vector>
#include <span>
#include <emmintrin.h>
struct Float3 { float x, y, z; };
constexpr std::size_t kShapeSampleTriangles = 4096, kShapeChunk = 512, kShapeBlock = 32;
constexpr double kAxisFaceCos = 0.9998;
struct ShapePartial { double sum = 0; std::array<double, 6> moment{}; std::array<double, 3> axis_area{}; };
struct ShapeSampling { std::size_t triangles = 0, sampled = 0;
    std::size_t triangleOf(std::size_t k) const {
        if (sampled == triangles) return k;
        constexpr std::size_t kBlocks = kShapeSampleTriangles / kShapeBlock;
        return (k / kShapeBlock) * triangles / kBlocks + k % kShapeBlock; } };
struct ShapeMesh { std::span<const Float3> positions; std::span<const std::uint32_t> indices; };
using Vec3 = std::array<double, 3>;
template <class Idx>
__attribute__((noinline)) ShapePartial run(const ShapeMesh& mesh, const ShapeSampling& sampling, std::size_t begin, std::size_t end, Idx idx) {
    ShapePartial p;
    auto at = [&](std::uint32_t i) { return Vec3{mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}; };
    auto dist = [](const Vec3& a, const Vec3& b) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); };
    for (std::size_t k = begin; k < end; ++k) {
        const std::size_t t = 3 * idx(k);
        const Vec3 p0 = at(mesh.indices[t]), p1 = at(mesh.indices[t + 1]), p2 = at(mesh.indices[t + 2]);
        p.sum += dist(p0, p1) + dist(p1, p2) + dist(p2, p0);
        const Vec3 u{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const Vec3 c{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (!(len > 0)) continue;
        const double w = 0.5 / len;
        p.moment[0] += w * c[0] * c[0], p.moment[1] += w * c[1] * c[1], p.moment[2] += w * c[2] * c[2];
        p.moment[3] += w * c[0] * c[1], p.moment[4] += w * c[0] * c[2], p.moment[5] += w * c[1] * c[2];
        const double half = 0.5 * len, lim = kAxisFaceCos * len; for (int a = 0; a < 3; ++a) p.axis_area[a] += std::fabs(c[a]) >= lim ? half : 0.0;
    }
    return p;
}
#include "session60_shape_simd.inc"
int main() {
    // UV sphere-ish mesh 48K triangles
    int nu = 160, nv = 157; std::vector<Float3> pos; std::vector<std::uint32_t> ind;
    for (int j = 0; j <= nv; ++j) for (int i = 0; i < nu; ++i) { double th = M_PI * j / nv, ph = 2 * M_PI * i / nu; pos.push_back({float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th))}); }
    for (int j = 0; j < nv; ++j) for (int i = 0; i < nu; ++i) { uint32_t a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu; ind.insert(ind.end(), {a, c, b, b, c, d}); }
    ShapeMesh m{pos, ind}; ShapeSampling s{ind.size() / 3, kShapeSampleTriangles};
    for (int variant = 0; variant < 3; ++variant) {
        double best = 1e9, chk = 0;
        for (int rep = 0; rep < 200; ++rep) {
            auto t0 = std::chrono::steady_clock::now();
            ShapePartial tot;
            for (std::size_t r = 0; r < 8; ++r) {
                ShapePartial p = variant == 0 ? run(m, s, r * 512, r * 512 + 512, [&](std::size_t k) { return s.triangleOf(k); })
                                : variant == 1 ? run(m, s, r * 512, r * 512 + 512, [&](std::size_t k) { return k; }) : run2(m, s, r * 512, r * 512 + 512, [&](std::size_t k) { return s.triangleOf(k); });
                tot.sum += p.sum + p.moment[0] + p.axis_area[0]+p.moment[5]; 
            }
            best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            chk = tot.sum;
        }
        std::printf("variant %d best %.4f ms chk %g\n", variant, best, chk);
    }
}
