// The GPU's exact triangle-triangle decision (spirv/cells/tritri_exact.glsl.inc on
// spirv/cells/exact_predicates.glsl.inc, through tests/shaders/exact_tritri_test.comp.glsl)
// against the CPU's (src/narrow/triangle_intersection.cpp, exact_predicates.cpp,
// neighbours.hpp): the same answer on every case, millions of them, random and adversarial
// (coplanar, touching, shared vertices and edges, offsets of 2^-20 .. 2^-60, coordinates
// from 1e-30 to 1e30 and subnormal, mixed magnitudes whose differences are not exact in
// double, degenerate triangles, grids), and each predicate's sign against the CPU's. Each
// adversarial family must reach the exact fallback, so a test cannot pass on filters alone.
// The tallies are printed with -s.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <sstream>
#include <string>

#include "graph/executor.hpp"
#include "narrow/exact_predicates.hpp"
#include "narrow/expansion.hpp"
#include "narrow/neighbours.hpp"
#include "narrow/triangle_intersection.hpp"
#include "support/gpu_fixture.hpp"
#include "support/record_dispatch.hpp"
#include "test_shaders/all.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

using Tri = std::array<Float3, 3>;

struct PairCase {
    Tri a, b;
    std::array<std::uint32_t, 3> index_a{0, 1, 2}, index_b{3, 4, 5};
};

struct PointCase {
    Float3 p[4];
};

// The test shader's push constants (exact_tritri_test.comp.glsl).
struct ExactPush {
    VkDeviceAddress cases, results;
    std::uint32_t count, mode;
};

constexpr std::uint32_t kGroupSize = 64;
constexpr std::size_t kChunk = 1u << 20;  // cases per dispatch (within maxComputeWorkGroupCount)

class ExactRunner {
public:
    explicit ExactRunner(ValidatedContext& ctx) : ctx_(ctx) {
        auto pipeline = vk::Pipeline::createCompute(ctx.device(), shaders::exact_tritri_test_comp, {}, sizeof(ExactPush), "exact-test");
        REQUIRE(pipeline);
        pipeline_.emplace(std::move(*pipeline));
    }

    // words_per_case words per case in, results_per_case result words per case out.
    std::vector<std::uint32_t> run(const std::vector<std::uint32_t>& words, std::size_t words_per_case, std::uint32_t mode,
                                   std::size_t results_per_case = 1) {
        const std::size_t n = words.size() / words_per_case;
        std::vector<std::uint32_t> result(n * results_per_case);
        for (std::size_t first = 0; first < n; first += kChunk) {
            const std::size_t count = std::min(kChunk, n - first);
            runChunk(words.data() + first * words_per_case, count, words_per_case, mode, results_per_case,
                     result.data() + first * results_per_case);
        }
        return result;
    }

private:
    void runChunk(const std::uint32_t* words, std::size_t count, std::size_t words_per_case, std::uint32_t mode,
                  std::size_t results_per_case, std::uint32_t* out_results) {
        vk::Device& device = ctx_.device();
        auto input = vk::Buffer::create(device, count * words_per_case * 4, 0, vk::MemoryKind::Upload, "exact-cases");
        auto output = vk::Buffer::create(device, count * results_per_case * 4, 0, vk::MemoryKind::Readback, "exact-results");
        REQUIRE(input);
        REQUIRE(output);
        std::memcpy(input->mapped(), words, count * words_per_case * 4);
        input->flush();
        graph::Graph g;
        const auto in_id = g.importBuffer("exact-cases", *input);
        const auto out_id = g.importBuffer("exact-results", *output, true);
        const VkPipeline handle = pipeline_->handle();
        const VkPipelineLayout layout = pipeline_->layout();
        const ExactPush push{input->address(), output->address(), static_cast<std::uint32_t>(count), mode};
        const auto groups = static_cast<std::uint32_t>((count + kGroupSize - 1) / kGroupSize);
        g.addPass("exact", graph::PassKind::Compute).read(in_id).write(out_id).record([=](graph::PassContext& pc) {
            recordDispatch(pc, handle, layout, push, groups);
        });
        graph::Executor executor(device);
        REQUIRE(executor.run(g));
        REQUIRE_NO_VALIDATION_MESSAGES(ctx_);
        output->invalidate();
        std::memcpy(out_results, output->mapped(), count * results_per_case * 4);
    }

    ValidatedContext& ctx_;
    std::optional<vk::Pipeline> pipeline_;
};

std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

void appendPoint(std::vector<std::uint32_t>& io_words, const Float3& p) {
    io_words.push_back(bits(p.x));
    io_words.push_back(bits(p.y));
    io_words.push_back(bits(p.z));
}

std::string show(const Float3& p) {
    char text[128];
    std::snprintf(text, sizeof text, "(%a, %a, %a)", double(p.x), double(p.y), double(p.z));
    return text;
}

std::string show(const Tri& t) { return show(t[0]) + " " + show(t[1]) + " " + show(t[2]); }

struct PairTally {
    std::size_t cases = 0, hits = 0, neighbours = 0, fallback_cases = 0, mismatches = 0;
};

// Runs one family of pairs on the GPU and compares with the CPU.
PairTally checkPairs(ExactRunner& runner, const char* family, const std::vector<PairCase>& cases) {
    std::vector<std::uint32_t> words;
    words.reserve(cases.size() * 24);
    for (const PairCase& c : cases) {
        for (const Float3& p : c.a) appendPoint(words, p);
        for (const Float3& p : c.b) appendPoint(words, p);
        for (std::uint32_t i : c.index_a) words.push_back(i);
        for (std::uint32_t i : c.index_b) words.push_back(i);
    }
    const std::vector<std::uint32_t> gpu = runner.run(words, 24, 0);
    PairTally t;
    t.cases = cases.size();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const PairCase& c = cases[i];
        const bool hit = narrow::trianglesIntersect(c.a, c.b);
        const std::uint32_t ia[3] = {c.index_a[0], c.index_a[1], c.index_a[2]};
        const std::uint32_t ib[3] = {c.index_b[0], c.index_b[1], c.index_b[2]};
        const Float3 pa[3] = {c.a[0], c.a[1], c.a[2]}, pb[3] = {c.b[0], c.b[1], c.b[2]};
        const bool neighbours = narrow::areNeighbours(ia, pa, ib, pb);
        const bool gpu_hit = (gpu[i] & 1u) != 0, gpu_neighbours = (gpu[i] & 2u) != 0;
        t.hits += hit;
        t.neighbours += neighbours;
        t.fallback_cases += (gpu[i] >> 8) != 0;
        if (hit != gpu_hit || neighbours != gpu_neighbours) {
            if (t.mismatches < 8) {
                UNSCOPED_INFO(family << " case " << i << ": CPU " << hit << "/" << neighbours << " GPU " << gpu_hit << "/" << gpu_neighbours
                                     << "  a " << show(c.a) << "  b " << show(c.b));
            }
            ++t.mismatches;
        }
    }
    std::printf("exact pairs %-22s %8zu cases  %8zu intersecting  %7zu neighbours  %8zu reached the exact path  %zu mismatches\n", family,
                t.cases, t.hits, t.neighbours, t.fallback_cases, t.mismatches);
    CHECK(t.mismatches == 0);
    return t;
}

struct PointTally {
    std::size_t cases = 0, fallback_cases = 0, mismatches = 0, zeros = 0;
};

narrow::Float2 xy(const Float3& p) { return {p.x, p.y}; }
narrow::Float2 yz(const Float3& p) { return {p.y, p.z}; }

// Runs one family of point quadruples and compares every predicate's sign.
PointTally checkPoints(ExactRunner& runner, const char* family, const std::vector<PointCase>& cases) {
    std::vector<std::uint32_t> words;
    words.reserve(cases.size() * 12);
    for (const PointCase& c : cases) {
        for (const Float3& p : c.p) appendPoint(words, p);
    }
    const std::vector<std::uint32_t> gpu = runner.run(words, 12, 1);
    PointTally t;
    t.cases = cases.size();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Float3* p = cases[i].p;
        const narrow::PlaneOrientation plane(p[0], p[1], p[2]);
        const int signs[7] = {narrow::orient3d(p[0], p[1], p[2], p[3]),
                              narrow::orient3dExact(p[0], p[1], p[2], p[3]),
                              plane.side(p[3]),
                              narrow::orient2d(xy(p[0]), xy(p[1]), xy(p[2])),
                              narrow::orient2dExact(xy(p[0]), xy(p[1]), xy(p[2])),
                              narrow::orient2d(yz(p[1]), yz(p[2]), yz(p[3])),
                              narrow::orient2dExact(yz(p[1]), yz(p[2]), yz(p[3]))};
        std::uint32_t expected = plane.certainlyNotCollinear() ? (1u << 14) : 0u;
        for (int k = 0; k < 7; ++k) expected |= static_cast<std::uint32_t>(signs[k] + 1) << (2 * k);
        t.zeros += signs[0] == 0;
        t.fallback_cases += (gpu[i] >> 16) != 0;
        if ((gpu[i] & 0xffffu) != expected) {
            if (t.mismatches < 8) {
                UNSCOPED_INFO(family << " case " << i << ": CPU bits " << expected << " GPU " << (gpu[i] & 0xffffu) << "  " << show(p[0])
                                     << " " << show(p[1]) << " " << show(p[2]) << " " << show(p[3]));
            }
            ++t.mismatches;
        }
    }
    std::printf("exact points %-21s %8zu cases  %8zu coplanar  %8zu reached the exact path  %zu mismatches\n", family, t.cases, t.zeros,
                t.fallback_cases, t.mismatches);
    CHECK(t.mismatches == 0);
    return t;
}

// ---- generators ---------------------------------------------------------------------------

using Rng = std::mt19937_64;

int uniformInt(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
float uniformFloat(Rng& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }

Float3 add(const Float3& a, const Float3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Float3 scaled(const Float3& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
Float3 intVec(Rng& rng, int range) {
    return {float(uniformInt(rng, -range, range)), float(uniformInt(rng, -range, range)), float(uniformInt(rng, -range, range))};
}

// Exact symmetries of a whole pair: an axis permutation, sign flips, a power-of-two scale
// and a translation by a dyadic vector of few bits (exact as long as the sums are).
struct ExactMap {
    int perm = 0, signs = 0, exponent = 0;
    Float3 shift{};

    Float3 operator()(const Float3& p) const {
        const float c[3] = {p.x, p.y, p.z};
        const int p0 = perm % 3, p1 = (p0 + 1 + perm / 3) % 3, p2 = 3 - p0 - p1;
        float v[3] = {c[p0], c[p1], c[p2]};
        for (int k = 0; k < 3; ++k) {
            if (signs & (1 << k)) v[k] = -v[k];
            v[k] = std::ldexp(v[k], exponent);
        }
        return add({v[0], v[1], v[2]}, shift);
    }
    Tri operator()(const Tri& t) const { return {(*this)(t[0]), (*this)(t[1]), (*this)(t[2])}; }
};

// A random exact map; exponents from -100 to 100 span 1e-30 .. 1e30. The shift (a few bits at
// the scale of the coordinates, or none) keeps the sums exact.
ExactMap randomMap(Rng& rng, int min_exponent = -100, int max_exponent = 100) {
    ExactMap m;
    m.perm = uniformInt(rng, 0, 5);
    m.signs = uniformInt(rng, 0, 7);
    m.exponent = uniformInt(rng, min_exponent, max_exponent);
    if (uniformInt(rng, 0, 1)) m.shift = scaled(intVec(rng, 8), std::ldexp(1.0f, m.exponent - 2));
    return m;
}

// A point of the lattice plane o + i u + j v (all small integers: exact floats).
struct LatticePlane {
    Float3 o, u, v, n;  // n: an integer vector off the plane (u x v, nonzero)

    Float3 at(int i, int j, int k = 0) const {
        return {o.x + float(i) * u.x + float(j) * v.x + float(k) * n.x, o.y + float(i) * u.y + float(j) * v.y + float(k) * n.y,
                o.z + float(i) * u.z + float(j) * v.z + float(k) * n.z};
    }
};

LatticePlane randomLatticePlane(Rng& rng, bool through_origin = false) {
    LatticePlane p;
    do {
        p.u = intVec(rng, 3);
        p.v = intVec(rng, 3);
        p.n = {p.u.y * p.v.z - p.u.z * p.v.y, p.u.z * p.v.x - p.u.x * p.v.z, p.u.x * p.v.y - p.u.y * p.v.x};
    } while (p.n.x == 0 && p.n.y == 0 && p.n.z == 0);
    if (uniformInt(rng, 0, 2) == 0) {  // axis-aligned planes too (box faces)
        p.u = {1, 0, 0};
        p.v = {0, 1, 0};
        p.n = {0, 0, 1};
    }
    p.o = through_origin ? Float3{} : intVec(rng, 8);
    return p;
}

Float3 latticePoint(Rng& rng, const LatticePlane& plane, int range, int off = 0) {
    return plane.at(uniformInt(rng, -range, range), uniformInt(rng, -range, range), off);
}

// A coplanar pair, overlapping, touching or disjoint, or one triangle leaving the plane.
PairCase coplanarPair(Rng& rng) {
    const LatticePlane plane = randomLatticePlane(rng);
    const int range = uniformInt(rng, 1, 4);
    PairCase c;
    for (Float3& p : c.a) p = latticePoint(rng, plane, range);
    for (Float3& p : c.b) p = latticePoint(rng, plane, range);
    const int mode = uniformInt(rng, 0, 3);
    if (mode == 1) c.b[0] = c.a[uniformInt(rng, 0, 2)];  // a shared vertex in the plane
    if (mode == 2) c.b[2] = latticePoint(rng, plane, range, uniformInt(rng, -2, 2));  // one vertex off the plane
    return c;
}

// b touches a: at a vertex, an edge's midpoint, an interior point, by a shared edge, or an
// edge of b crossing an edge of a; b's other vertices on either side or in a's plane.
PairCase touchingPair(Rng& rng) {
    const LatticePlane plane = randomLatticePlane(rng);
    PairCase c;
    // Even lattice coordinates: midpoints and quarter points are lattice points too.
    for (Float3& p : c.a) p = plane.at(2 * uniformInt(rng, -3, 3), 2 * uniformInt(rng, -3, 3));
    const int e = uniformInt(rng, 0, 2);
    const Float3 mid = scaled(add(c.a[e], c.a[(e + 1) % 3]), 0.5f);
    const Float3 inside = scaled(add(add(c.a[0], c.a[1]), scaled(c.a[2], 2)), 0.25f);
    auto side = [&] {
        return add(plane.at(uniformInt(rng, -4, 4), uniformInt(rng, -4, 4)), scaled(plane.n, float(uniformInt(rng, -2, 2))));
    };
    switch (uniformInt(rng, 0, 5)) {
        case 0: c.b = {c.a[e], side(), side()}; break;  // shared vertex
        case 1: c.b = {c.a[e], c.a[(e + 1) % 3], side()}; break;  // shared edge
        case 2: c.b = {mid, side(), side()}; break;  // vertex on an edge
        case 3: c.b = {inside, side(), side()}; break;  // vertex on the face
        case 4: {  // edge through an edge
            const Float3 t = add(scaled(plane.n, float(uniformInt(rng, 1, 2))), plane.at(uniformInt(rng, -1, 1), uniformInt(rng, -1, 1)));
            const Float3 t0 = add(t, scaled(plane.o, -1));
            c.b = {add(mid, t0), add(mid, scaled(t0, -1)), side()};
            break;
        }
        default: c.b = {mid, add(mid, scaled(add(mid, scaled(c.a[(e + 2) % 3], -1)), 1)), side()}; break;  // edge-on, outward
    }
    if (uniformInt(rng, 0, 1)) std::swap(c.a, c.b);
    if (uniformInt(rng, 0, 1)) std::swap(c.b[0], c.b[uniformInt(rng, 0, 2)]);
    return c;
}

// Degenerate triangles (collinear, needles, points) against anything on the same lattice.
PairCase degeneratePair(Rng& rng) {
    const LatticePlane plane = randomLatticePlane(rng);
    auto degenerate = [&] {
        const Float3 o = latticePoint(rng, plane, 3, uniformInt(rng, -1, 1));
        const Float3 d = uniformInt(rng, 0, 1) ? plane.u : intVec(rng, 2);
        switch (uniformInt(rng, 0, 3)) {
            case 0: return Tri{o, o, o};  // a point
            case 1: return Tri{o, add(o, d), add(o, d)};  // a segment, two equal ends
            case 2: return Tri{o, add(o, scaled(d, float(uniformInt(rng, -3, 3)))), add(o, scaled(d, float(uniformInt(rng, -3, 3))))};
            default: return Tri{o, add(o, scaled(d, 4)), add(o, scaled(d, std::ldexp(1.0f, -uniformInt(rng, 1, 20))))};  // needle
        }
    };
    PairCase c;
    c.a = degenerate();
    const int other = uniformInt(rng, 0, 2);
    if (other == 0) {
        c.b = degenerate();
    } else {
        for (Float3& p : c.b) p = latticePoint(rng, plane, 3, other == 1 ? 0 : uniformInt(rng, -1, 1));
    }
    if (uniformInt(rng, 0, 1)) std::swap(c.a, c.b);
    return c;
}

// Random points on a small integer grid (few bits: many exact incidences).
PairCase gridPair(Rng& rng) {
    PairCase c;
    for (Float3& p : c.a) p = intVec(rng, 2);
    for (Float3& p : c.b) p = intVec(rng, 2);
    return c;
}

// Mating plates as the bench's cad-mating has them: two plates stacked face to face, turned
// about a random axis, world vertices M p in double rounded once to float (the CPU's), so
// the mating faces are coplanar in exact arithmetic but only nearly after rounding. a is a
// triangle of the lower plate's top face, b one of the upper plate's bottom face in the same
// or a neighbouring lattice cell (either diagonal): mostly touching or overlapping, every
// test decided by a hair.
PairCase matingPlatesPair(Rng& rng) {
    double axis[3] = {uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1)};
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]) + 1e-9;
    for (double& x : axis) x /= length;
    const double angle = uniformFloat(rng, 0.05f, 3.0f), c = std::cos(angle), sn = std::sin(angle), t = 1 - c;
    const double x = axis[0], y = axis[1], z = axis[2];
    const double r[3][3] = {{t * x * x + c, t * x * y - sn * z, t * x * z + sn * y},
                            {t * x * y + sn * z, t * y * y + c, t * y * z - sn * x},
                            {t * x * z - sn * y, t * y * z + sn * x, t * z * z + c}};
    const int n = 9;
    const float plate = float(uniformInt(rng, 0, 7));  // the lower plate's place in the stack
    auto world = [&](int i, int j, float local_z, float stack) {
        const float q[3] = {-0.5f + 1.0f * float(i) / float(n), -0.25f + 0.5f * float(j) / float(n), local_z};
        float out[3];
        for (int row = 0; row < 3; ++row) {
            const float m[4] = {float(r[row][0]), float(r[row][1]), float(r[row][2]), float(r[row][2] * 0.25 * stack)};
            const double w = ((double(m[0]) * q[0] + double(m[1]) * q[1]) + double(m[2]) * q[2]) + double(m[3]);
            out[row] = float(w);
        }
        return Float3{out[0], out[1], out[2]};
    };
    auto triangle = [&](int i, int j, float local_z, float stack, int half, int diagonal) {
        const Float3 p00 = world(i, j, local_z, stack), p10 = world(i + 1, j, local_z, stack), p01 = world(i, j + 1, local_z, stack),
                     p11 = world(i + 1, j + 1, local_z, stack);
        if (diagonal == 0) return half == 0 ? Tri{p00, p10, p11} : Tri{p00, p11, p01};
        return half == 0 ? Tri{p00, p10, p01} : Tri{p10, p11, p01};
    };
    PairCase pc;
    const int i = uniformInt(rng, 1, n - 2), j = uniformInt(rng, 1, n - 2);
    pc.a = triangle(i, j, 0.125f, plate, uniformInt(rng, 0, 1), uniformInt(rng, 0, 1));
    pc.b = triangle(i + uniformInt(rng, -1, 1), j + uniformInt(rng, -1, 1), -0.125f, plate + 1, uniformInt(rng, 0, 1), uniformInt(rng, 0, 1));
    return pc;
}

// A touching or coplanar configuration moved to the origin (its contact point at 0), then one
// vertex of b displaced by +-2^-k, k from 20 to 60, relative to coordinates of order 1: the
// displaced coordinates are exact and tiny, so the differences to the others are not exact
// in double past k = 29 (the general form), and the determinants are tiny.
PairCase offsetPair(Rng& rng) {
    PairCase c = uniformInt(rng, 0, 1) ? touchingPair(rng) : coplanarPair(rng);
    const Float3 origin = c.b[0];
    for (Float3& p : c.a) p = add(p, scaled(origin, -1));
    for (Float3& p : c.b) p = add(p, scaled(origin, -1));
    const int k = uniformInt(rng, 20, 60);
    const float delta = std::ldexp(1.0f, -k);
    const int axis = uniformInt(rng, 0, 3);
    Float3 d = axis == 0   ? Float3{delta, 0, 0}
               : axis == 1 ? Float3{0, delta, 0}
               : axis == 2 ? Float3{0, 0, delta}
                           : Float3{delta, -delta, delta};
    if (uniformInt(rng, 0, 1)) d = scaled(d, -1);
    c.b[0] = add(c.b[0], d);
    // Sometimes also relative to coordinates of order 1 (2^-20 .. 2^-23 of 1 is exact).
    if (uniformInt(rng, 0, 3) == 0) c.b[1].x += std::ldexp(c.b[1].x == 0 ? 1.0f : c.b[1].x, -uniformInt(rng, 20, 23));
    return c;
}

// Mixed magnitudes on a lattice plane through the origin: every vertex scaled by its own power
// of two (2^-100 .. 2^100) stays on the plane (and on its ray from the origin), so contacts
// stay exact while the coordinate differences are far from exact in double.
PairCase mixedPair(Rng& rng) {
    const LatticePlane plane = randomLatticePlane(rng, true);
    auto vertex = [&](int off) { return scaled(latticePoint(rng, plane, 3, off), std::ldexp(1.0f, uniformInt(rng, -100, 100))); };
    PairCase c;
    for (Float3& p : c.a) p = vertex(0);
    const int mode = uniformInt(rng, 0, 3);
    for (Float3& p : c.b) p = vertex(mode == 0 ? 0 : uniformInt(rng, -1, 1));
    if (mode == 1) c.b[0] = {};  // the origin
    if (mode == 1) c.a[0] = {};
    if (mode == 2) c.b[0] = scaled(c.a[0], std::ldexp(1.0f, -uniformInt(rng, 0, 60)));  // on a's ray from the origin
    return c;
}

// Random triangles near each other, at scales from 1e-30 to 1e30, with rounding.
PairCase randomPair(Rng& rng) {
    const float scale = std::pow(10.0f, uniformFloat(rng, -30, 30));
    const Float3 centre{uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1)};
    const Float3 other = add(centre, {uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f)});
    PairCase c;
    for (Float3& p : c.a)
        p = scaled(add(centre, {uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f)}), scale);
    for (Float3& p : c.b)
        p = scaled(add(other, {uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f), uniformFloat(rng, -0.3f, 0.3f)}), scale);
    return c;
}

// Subnormal and tiny normal floats next to zero and to ordinary ones.
PairCase subnormalPair(Rng& rng) {
    PairCase c = uniformInt(rng, 0, 1) ? gridPair(rng) : touchingPair(rng);
    const int exponent = -uniformInt(rng, 130, 147);
    for (Float3& p : c.a) p = scaled(p, std::ldexp(1.0f, exponent));
    for (Float3& p : c.b) p = scaled(p, std::ldexp(1.0f, exponent));
    if (uniformInt(rng, 0, 3) == 0) c.b[2] = scaled(c.b[2], std::ldexp(1.0f, 120));  // mixed with ordinary floats
    return c;
}

// The neighbour rule: shared indices, bit-identical positions, +0 against -0.
PairCase neighbourPair(Rng& rng) {
    PairCase c = gridPair(rng);
    for (auto& i : c.index_a) i = std::uint32_t(uniformInt(rng, 0, 12));
    for (auto& i : c.index_b) i = std::uint32_t(uniformInt(rng, 0, 12));
    if (uniformInt(rng, 0, 1)) c.b[uniformInt(rng, 0, 2)] = c.a[uniformInt(rng, 0, 2)];
    if (uniformInt(rng, 0, 2) == 0) {
        Float3& p = c.b[uniformInt(rng, 0, 2)];
        if (p.x == 0) p.x = -p.x;  // -0: equal as a float, not bit-identical
    }
    return c;
}

std::vector<PairCase> generate(std::size_t count, std::uint64_t seed, const std::function<PairCase(Rng&)>& make, bool transform) {
    Rng rng(seed);
    std::vector<PairCase> cases;
    cases.reserve(count);
    while (cases.size() < count) {
        PairCase c = make(rng);
        if (transform) {
            const ExactMap m = randomMap(rng);
            c.a = m(c.a);
            c.b = m(c.b);
        }
        if (uniformInt(rng, 0, 1)) std::swap(c.a, c.b);
        cases.push_back(c);
    }
    return cases;
}

bool skipWithoutFloat64(ValidatedContext& ctx) {
    if (ctx.device().shader_float64) return false;
    WARN("the device has no shaderFloat64: the CPU decides every pair there");
    return true;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("exact GPU triangle pairs decide as the CPU on random and adversarial pairs", "[gpu][exact]") {
    ValidatedContext ctx;
    if (skipWithoutFloat64(ctx)) return;
    const auto start = std::chrono::steady_clock::now();
    ExactRunner runner(ctx);
    std::printf("exact: pipeline ready in %.2f s\n", secondsSince(start));
    struct Family {
        const char* name;
        std::size_t count;
        std::function<PairCase(Rng&)> make;
        bool transform, must_fall_back, all_touch;
    };
    const Family families[] = {
        {"random", 400000, randomPair, false, false, false},
        {"coplanar", 300000, coplanarPair, true, true, false},
        {"touching", 300000, touchingPair, true, true, true},  // touching by construction
        {"offsets 2^-20..2^-60", 200000, offsetPair, false, true, false},
        {"mixed magnitudes", 200000, mixedPair, false, true, false},
        {"degenerate", 200000, degeneratePair, true, true, false},
        {"grid", 300000, gridPair, true, true, false},
        {"subnormal", 50000, subnormalPair, false, true, false},
        {"neighbours", 50000, neighbourPair, false, false, false},
        {"mating plates", 300000, matingPlatesPair, false, true, false},
    };
    std::size_t total = 0, fallbacks = 0;
    std::uint64_t seed = 1;
    for (const Family& f : families) {
        const PairTally t = checkPairs(runner, f.name, generate(f.count, seed++, f.make, f.transform));
        total += t.cases;
        fallbacks += t.fallback_cases;
        if (f.must_fall_back) {
            INFO(f.name << ": cases that reached the exact path");
            CHECK(t.fallback_cases > t.cases / 1000);
        }
        if (std::strcmp(f.name, "neighbours") == 0) CHECK(t.neighbours > t.cases / 4);
        CHECK(t.hits > 0);
        if (f.all_touch) {
            CHECK(t.hits == t.cases);
        } else {
            CHECK(t.hits < t.cases);
        }
    }
    std::printf("exact pairs: %zu cases, %zu reached the exact path, %.2f s\n", total, fallbacks, secondsSince(start));
}

TEST_CASE("exact GPU predicates return the CPU's signs", "[gpu][exact]") {
    ValidatedContext ctx;
    if (skipWithoutFloat64(ctx)) return;
    const auto start = std::chrono::steady_clock::now();
    ExactRunner runner(ctx);
    auto make = [](std::size_t count, std::uint64_t seed, const std::function<void(Rng&, PointCase&)>& fill) {
        Rng rng(seed);
        std::vector<PointCase> cases(count);
        for (PointCase& c : cases) fill(rng, c);
        return cases;
    };
    // Random points at one scale: mostly the filters.
    const auto random = make(200000, 11, [](Rng& rng, PointCase& c) {
        const float scale = std::pow(10.0f, uniformFloat(rng, -30, 30));
        for (Float3& p : c.p) p = scaled({uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1), uniformFloat(rng, -1, 1)}, scale);
    });
    // Coplanar and nearly coplanar lattice points, mapped exactly (1e-30 .. 1e30), the fourth
    // sometimes moved by 2^-20 .. 2^-60 of the scale.
    const auto coplanar = make(300000, 12, [](Rng& rng, PointCase& c) {
        const LatticePlane plane = randomLatticePlane(rng);
        for (Float3& p : c.p) p = latticePoint(rng, plane, 4);
        if (uniformInt(rng, 0, 3) == 0) c.p[1] = c.p[0];  // collinear triples
        const Float3 offset = scaled(intVec(rng, 1), std::ldexp(1.0f, -uniformInt(rng, 20, 60)));
        if (uniformInt(rng, 0, 1)) {
            // The fourth point moved to the origin (exact on the lattice), then off by the offset:
            // representable, and its differences to the others are not exact in double.
            const Float3 o = c.p[3];
            for (Float3& p : c.p) p = add(p, scaled(o, -1));
            c.p[3] = offset;
        }
        const ExactMap m = randomMap(rng);
        for (Float3& p : c.p) p = m(p);
    });
    // Mixed magnitudes: lattice points through the origin, each scaled by its own power of two
    // (coplanar exactly; differences not exact in double), the fourth sometimes off the plane.
    const auto mixed = make(300000, 13, [](Rng& rng, PointCase& c) {
        const LatticePlane plane = randomLatticePlane(rng, true);
        const int off = uniformInt(rng, 0, 1) ? 0 : uniformInt(rng, -1, 1);
        for (int k = 0; k < 4; ++k) {
            c.p[k] = scaled(latticePoint(rng, plane, 3, k == 3 ? off : 0), std::ldexp(1.0f, uniformInt(rng, -100, 100)));
        }
    });
    // Random floats of random exponents, including subnormals and 3e38.
    const auto wild = make(200000, 14, [](Rng& rng, PointCase& c) {
        for (Float3& p : c.p) {
            float v[3];
            for (float& x : v) {
                x = std::ldexp(uniformFloat(rng, -1, 1), uniformInt(rng, -149, 128));
                if (uniformInt(rng, 0, 7) == 0) x = 0;
            }
            p = {v[0], v[1], v[2]};
        }
        if (uniformInt(rng, 0, 1)) c.p[3] = c.p[uniformInt(rng, 0, 2)];
    });
    const struct {
        const char* name;
        const std::vector<PointCase>* cases;
        bool must_fall_back;
    } families[] = {
        {"random", &random, false}, {"coplanar", &coplanar, true}, {"mixed magnitudes", &mixed, true}, {"wild exponents", &wild, false}};
    std::size_t total = 0;
    for (const auto& f : families) {
        const PointTally t = checkPoints(runner, f.name, *f.cases);
        total += t.cases;
        if (f.must_fall_back) {
            INFO(f.name << ": cases whose filtered predicates reached the exact path");
            CHECK(t.fallback_cases > t.cases / 10);
        }
    }
    std::printf("exact points: %zu cases (7 predicates each, 3 of them exact arithmetic alone), %.2f s\n", total, secondsSince(start));
}

namespace {

// A double of 53 random bits (a random significand) times 2^exponent, with a random sign.
double randomDouble(Rng& rng, int exponent) {
    const std::uint64_t significand = (rng() >> 11) | (std::uint64_t{1} << 52);
    const double v = std::ldexp(double(significand), exponent - 52);
    return rng() & 1 ? -v : v;
}

void appendDouble(std::vector<std::uint32_t>& io_words, double d) {
    std::uint64_t u;
    std::memcpy(&u, &d, 8);
    io_words.push_back(static_cast<std::uint32_t>(u));
    io_words.push_back(static_cast<std::uint32_t>(u >> 32));
}

double doubleAt(const std::uint32_t* words) {
    const std::uint64_t u = std::uint64_t{words[0]} | (std::uint64_t{words[1]} << 32);
    double d;
    std::memcpy(&d, &u, 8);
    return d;
}

std::string showDouble(double d) {
    char text[64];
    std::snprintf(text, sizeof text, "%a", d);
    return text;
}

}  // namespace

// The device responses' arithmetic (spirv/cells/rounded_fp64.glsl.inc): the quotient and the
// root rounded as IEEE rounds them, from the driver's own (after a Newton step) and stepped
// to from 5 ulps off the CPU's (the one-ulp correction alone), and
// doubles rounded to float through the bits (ties, subnormal floats, carries into the next
// binade), on the magnitudes the responses reach (2^-650 .. 2^520).
TEST_CASE("rounded GPU division, square root and float rounding equal the CPU's", "[gpu][exact]") {
    ValidatedContext ctx;
    if (skipWithoutFloat64(ctx)) return;
    ExactRunner runner(ctx);
    Rng rng(21);
    std::vector<std::uint32_t> words;
    std::size_t count = 0;
    const auto add = [&](double a, double b, double x, double f) {
        for (double d : {a, b, x, f, a / b, std::sqrt(x)}) appendDouble(words, d);
        ++count;
    };
    for (int k = 0; k < 1000000; ++k) {
        const int family = k % 8;
        double a = randomDouble(rng, uniformInt(rng, -650, 250));
        double b = randomDouble(rng, uniformInt(rng, -350, 260));
        double x = std::abs(randomDouble(rng, uniformInt(rng, -700, 520)));
        // A float's value with a random double's extra bits: every rounding case, subnormal
        // floats (2^-149 .. 2^-126) and the half of the least one included.
        double f = randomDouble(rng, uniformInt(rng, -152, 120));
        if (family == 1) {
            // Quotients and roots that are exact, and next to a power of two (binade edges).
            b = std::ldexp(1.0, uniformInt(rng, -300, 300)) * (rng() & 1 ? -1 : 1);
            const double r = randomDouble(rng, uniformInt(rng, -300, 200));
            x = r * r;
        } else if (family == 2) {
            a = std::nextafter(std::abs(b), 0.0) * double(1 << uniformInt(rng, 0, 8));  // just below a power-of-two ratio
            x = std::nextafter(std::ldexp(1.0, 2 * uniformInt(rng, -300, 250)), double(uniformInt(rng, 0, 1)));
        } else if (family == 3) {
            // Float ties: 24 kept bits, then exactly half (odd and even kept bits).
            const std::uint64_t kept = (rng() >> 40) | (std::uint64_t{1} << 23);
            f = std::ldexp(double(kept * 2 + 1), uniformInt(rng, -125, 100) - 24);
        } else if (family == 4) {
            // Subnormal float ties and carries into 2^-126.
            f = std::ldexp(double(2 * uniformInt(rng, 0, (1 << 23) - 1) + 1), -150);
            if (k % 16 == 4) f = std::nextafter(std::ldexp(1.0, -126), 0.0);
        } else if (family == 5) {
            // Unit-normal-like operands: a component over a length of similar size.
            b = std::abs(randomDouble(rng, uniformInt(rng, -300, 250)));
            a = b * std::ldexp(randomDouble(rng, 0), -uniformInt(rng, 0, 60));
        }
        add(a, b, x, f);
    }
    const std::vector<std::uint32_t> out = runner.run(words, 12, 2, 13);
    std::size_t mismatches = 0, driver_quotients_off = 0, driver_roots_off = 0;
    std::uint64_t driver_quotient_ulps = 0, driver_root_ulps = 0;
    // Ulps between two doubles of one sign.
    const auto ulps = [](double u, double v) {
        std::int64_t i, j;
        std::memcpy(&i, &u, 8);
        std::memcpy(&j, &v, 8);
        return static_cast<std::uint64_t>(i > j ? i - j : j - i);
    };
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t* in = &words[12 * i];
        const double a = doubleAt(in), b = doubleAt(in + 2), x = doubleAt(in + 4), f = doubleAt(in + 6);
        const std::uint32_t* r = &out[13 * i];
        const double q = a / b, s = std::sqrt(x);
        const float rounded = static_cast<float>(f);
        // The driver's own division and root, for the record (the rounding must not need them right).
        if (std::memcmp(&q, &r[8], 8) != 0) ++driver_quotients_off, driver_quotient_ulps = std::max(driver_quotient_ulps, ulps(q, doubleAt(&r[8])));
        if (std::memcmp(&s, &r[10], 8) != 0) ++driver_roots_off, driver_root_ulps = std::max(driver_root_ulps, ulps(s, doubleAt(&r[10])));
        const bool same = std::memcmp(&q, &r[0], 8) == 0 && std::memcmp(&s, &r[2], 8) == 0 && std::memcmp(&q, &r[4], 8) == 0 &&
                          std::memcmp(&s, &r[6], 8) == 0 && std::memcmp(&rounded, &r[12], 4) == 0;
        if (same) continue;
        if (++mismatches > 10) continue;
        UNSCOPED_INFO("case " << i << ": a " << showDouble(a) << " b " << showDouble(b) << " x " << showDouble(x) << " f " << showDouble(f)
                              << "; CPU " << showDouble(q) << " " << showDouble(s) << " " << showDouble(double(rounded)) << ", GPU "
                              << showDouble(doubleAt(&r[0])) << " " << showDouble(doubleAt(&r[2])) << " (from 5 ulps off "
                              << showDouble(doubleAt(&r[4])) << " " << showDouble(doubleAt(&r[6])) << ") float bits " << r[12]);
    }
    std::printf("rounding: %zu cases; the driver's own a / b off in %zu (at most %llu ulps), sqrt off in %zu (at most %llu ulps)\n",
                count, driver_quotients_off, static_cast<unsigned long long>(driver_quotient_ulps), driver_roots_off,
                static_cast<unsigned long long>(driver_root_ulps));
    INFO(mismatches << " of " << count << " cases differ");
    CHECK(mismatches == 0);
}

// The steps the rounding is made of, each against the CPU on full 53-bit doubles (the
// predicates' operands have at most 50 bits, so their tests cannot see a TwoProduct whose
// error term is wrong for wider ones): TwoSum, Veltkamp's split and Dekker's TwoProduct to
// the bit, and the sign of each one-ulp test (a - b * (c + h), x - (c + h)^2) against an
// expansion whose products are std::fma's. The cases sit where the rounding decides: c the
// quotient or the root or a neighbour, h half the gap to the next double up or down.
TEST_CASE("rounded GPU steps: TwoSum, split, TwoProduct and the one-ulp side tests equal the CPU's on full doubles", "[gpu][exact]") {
    ValidatedContext ctx;
    if (skipWithoutFloat64(ctx)) return;
    ExactRunner runner(ctx);
    Rng rng(77);
    std::vector<std::uint32_t> words;
    std::vector<std::array<double, 4>> cases;
    const auto add = [&](double a, double b, double c, double h) {
        cases.push_back({a, b, c, h});
        for (double d : {a, b, c, h}) appendDouble(words, d);
    };
    // The binade edge of the NVIDIA run of 2026-12-06 (case 2): sqrt(2^336 - 2^283) lies just below the
    // midpoint 2^168 - 2^114, seen from either neighbour.
    add(std::ldexp(0x1.fffffffffffffp0, 335), 1.0, std::ldexp(0x1.fffffffffffffp0, 167), std::ldexp(1.0, 114));
    add(std::ldexp(0x1.fffffffffffffp0, 335), 1.0, std::ldexp(1.0, 168), -std::ldexp(1.0, 114));
    // Odd cases sit at the root, even ones at the quotient; the root's side is compared on
    // the odd ones alone (at a quotient c * c may overflow: outside the rounding's domain).
    for (int k = 0; k < 200000; ++k) {
        const double a = std::abs(randomDouble(rng, uniformInt(rng, -300, 300)));
        const double b = std::abs(randomDouble(rng, uniformInt(rng, -300, 300)));
        double c = k % 2 ? std::sqrt(a) : a / b;
        for (int steps = uniformInt(rng, -2, 2); steps != 0; steps += steps > 0 ? -1 : 1) c = std::nextafter(c, steps > 0 ? 1e300 : 0.0);
        const bool up = rng() & 1;
        const double h = (std::nextafter(c, up ? 1e300 : 0.0) - c) / 2;
        add(a, b, c, h);
    }
    const std::vector<std::uint32_t> out = runner.run(words, 8, 3, 16);
    const char* names[] = {"TwoSum's sum",         "TwoSum's error",     "split's high part",   "split's low part",
                           "TwoProduct's product", "TwoProduct's error", "the quotient's side", "the root's side"};
    std::size_t wrong[8] = {};
    std::size_t mismatches = 0, fma_unfused = 0;
    std::string examples;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto [a, b, c, h] = cases[i];
        double expected[6];
        narrow::exact::twoSum(a, b, expected[0], expected[1]);
        const double big = 134217729.0 * a, a_big = big - a;  // Veltkamp, as the shader
        expected[2] = big - a_big;
        expected[3] = a - expected[2];
        narrow::exact::twoProduct(a, b, expected[4], expected[5]);
        // a - b * (c + h) and a - (c + h)^2 = a - c*c - 2ch - h*h (h a power of two: b*h, 2ch and h*h exact).
        double p, e;
        narrow::exact::Expansion<8> quotient, root;
        narrow::exact::twoProduct(b, c, p, e);
        for (double t : {a, -p, -e, -(b * h)}) quotient.add(t);
        narrow::exact::twoProduct(c, c, p, e);
        for (double t : {a, -p, -e, -(2 * c * h), -(h * h)}) root.add(t);
        const std::uint32_t* r = &out[16 * i];
        if (doubleAt(&r[14]) != expected[5]) ++fma_unfused;
        bool same = true;
        for (int k = 0; k < 6; ++k)
            if (doubleAt(&r[2 * k]) != expected[k]) ++wrong[k], same = false;  // by value: a zero's sign does not matter
        if (int(r[12]) - 1 != quotient.sign()) ++wrong[6], same = false;
        if ((i < 2 || i % 2 == 1) && int(r[13]) - 1 != root.sign()) ++wrong[7], same = false;  // cases 0 and 1 are roots too
        if (same || ++mismatches > 8) continue;
        std::ostringstream text;
        text << "\n  case " << i << ": a " << showDouble(a) << " b " << showDouble(b) << " c " << showDouble(c) << " h " << showDouble(h)
             << "; GPU TwoProduct " << showDouble(doubleAt(&r[8])) << " + " << showDouble(doubleAt(&r[10])) << ", CPU "
             << showDouble(expected[4]) << " + " << showDouble(expected[5]) << "; split " << showDouble(doubleAt(&r[4])) << " + "
             << showDouble(doubleAt(&r[6])) << "; sides GPU " << int(r[12]) - 1 << " " << int(r[13]) - 1 << ", CPU " << quotient.sign()
             << " " << root.sign();
        examples += text.str();
    }
    std::printf("rounding steps: %zu cases; the driver's fma(a, b, -a * b) differs from the product's error in %zu\n", cases.size(),
                fma_unfused);
    INFO(mismatches << " cases differ; the first:" << examples);
    for (int k = 0; k < 8; ++k) {
        INFO(names[k] << ": " << wrong[k] << " of " << cases.size() << " cases differ");
        CHECK(wrong[k] == 0);
    }
}
