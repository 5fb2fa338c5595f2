#include "api/vertex_scans.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vkcollide::vertex_scans {
namespace {

static_assert(sizeof(Float3) == 12, "Float3 is three packed floats");

// The box, largest magnitude and finiteness of a run of vertices.
struct Acc {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    float big = 0;
    bool finite = true;

    // Component c of a coordinate v. A NaN or infinity fails the magnitude test (NaN
    // compares false) and never enters the box.
    void take(int c, float v) {
        const float a = std::fabs(v);
        lo[c] = v < lo[c] ? v : lo[c];
        hi[c] = v > hi[c] ? v : hi[c];
        big = a > big ? a : big;
        finite = finite && a <= std::numeric_limits<float>::max();
    }
    void add(const Acc& o) {
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], o.lo[c]), hi[c] = std::max(hi[c], o.hi[c]);
        big = std::max(big, o.big);
        finite = finite && o.finite;
    }
};

// Copies `floats` floats (whole vertices) from `in` to `out` and, kTwo, to `out2`, and takes
// them into `io`, one float at a time.
template <bool kTwo>
void copyFloats(const float* in, float* out, float* out2, std::size_t floats, Acc& io) {
    for (std::size_t i = 0; i < floats; ++i) {
        out[i] = in[i];
        if constexpr (kTwo) out2[i] = in[i];
        io.take(int(i % 3), in[i]);
    }
}

// The same for `vertices` vertices, in blocks of four (12 floats: the components repeat
// with period 3, so float j of a block is always component j % 3), each lane with its own
// minimum, maximum, magnitude and finiteness, folded into components at the end. With
// SSE2 (every x86-64) a block is three registers, written once to each output; about one
// memory copy per output (measured: 0.76 ms for 1M vertices to two outputs on the
// development machine, where the compiler's vectorization of the same loop took 0.97 ms).
template <bool kTwo>
void copyVertices(const float* in, float* out, float* out2, std::size_t vertices, Acc& io) {
    const std::size_t blocks = vertices / 4;
    float lo[12], hi[12], big[12];
    bool finite = true;
#if defined(__SSE2__)
    const __m128 sign = _mm_set1_ps(-0.0f), largest = _mm_set1_ps(std::numeric_limits<float>::max());
    __m128 vlo[3], vhi[3], vbig[3], vbad = _mm_setzero_ps();
    for (int j = 0; j < 3; ++j) vlo[j] = _mm_set1_ps(INFINITY), vhi[j] = _mm_set1_ps(-INFINITY), vbig[j] = _mm_setzero_ps();
    for (std::size_t k = 0; k < blocks; ++k) {
        for (int j = 0; j < 3; ++j) {
            const std::size_t at = 12 * k + 4 * j;
            const __m128 v = _mm_loadu_ps(in + at), a = _mm_andnot_ps(sign, v);
            _mm_storeu_ps(out + at, v);
            if constexpr (kTwo) _mm_storeu_ps(out2 + at, v);
            vlo[j] = _mm_min_ps(v, vlo[j]);  // a NaN in v gives the second operand
            vhi[j] = _mm_max_ps(v, vhi[j]);
            vbig[j] = _mm_max_ps(a, vbig[j]);
            vbad = _mm_or_ps(vbad, _mm_cmpnle_ps(a, largest));  // true for infinities and NaNs
        }
    }
    for (int j = 0; j < 3; ++j) _mm_storeu_ps(lo + 4 * j, vlo[j]), _mm_storeu_ps(hi + 4 * j, vhi[j]), _mm_storeu_ps(big + 4 * j, vbig[j]);
    finite = _mm_movemask_ps(vbad) == 0;
#else
    int lane_finite[12];
    for (int j = 0; j < 12; ++j) lo[j] = INFINITY, hi[j] = -INFINITY, big[j] = 0, lane_finite[j] = 1;
    for (std::size_t k = 0; k < blocks; ++k) {
        for (int j = 0; j < 12; ++j) {
            const float v = in[12 * k + j], a = std::fabs(v);
            out[12 * k + j] = v;
            if constexpr (kTwo) out2[12 * k + j] = v;
            lo[j] = v < lo[j] ? v : lo[j];
            hi[j] = v > hi[j] ? v : hi[j];
            big[j] = a > big[j] ? a : big[j];
            lane_finite[j] &= int(a <= std::numeric_limits<float>::max());
        }
    }
    for (int j = 0; j < 12; ++j) finite = finite && lane_finite[j];
#endif
    Acc blocks_acc;
    for (int j = 0; j < 12; ++j) {
        const int c = j % 3;
        blocks_acc.lo[c] = std::min(blocks_acc.lo[c], lo[j]);
        blocks_acc.hi[c] = std::max(blocks_acc.hi[c], hi[j]);
        blocks_acc.big = std::max(blocks_acc.big, big[j]);
    }
    blocks_acc.finite = finite;
    io.add(blocks_acc);
    const std::size_t done = 12 * blocks;
    copyFloats<kTwo>(in + done, out + done, out2 ? out2 + done : nullptr, 3 * vertices - done, io);
}

bool finiteVertex(const Float3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Vertices per step of UploadWrites::Staged: 12 KB, still in L1 when streamed on.
constexpr std::size_t kStepVertices = 1024;

}  // namespace

namespace {

// copyAndScan's loop, with `extra_items` more items of other work (extra(k)) in the same
// parallel loop: the executor's threads are started once for both.
template <class Extra>
VertexScan copyScanWith(Executor& executor, std::span<const Float3> in, std::span<Float3> out, Float3* upload, UploadWrites writes,
                        std::size_t extra_items, const Extra& extra) {
    const std::size_t n = in.size();
    const std::size_t threads = std::max(1u, executor.threadCount());
    // A few chunks per thread (chunks differ in speed: caches, other work), none smaller than
    // kMinChunkVertices (waking the threads costs tens of microseconds), boundaries on
    // multiples of 16 vertices (whole 64-byte lines of the upload buffer per thread).
    std::size_t grain = threads == 1 ? n : std::max(kMinChunkVertices, (n + 4 * threads - 1) / (4 * threads));
    grain = std::max<std::size_t>(16, (grain + 15) / 16 * 16);
    const std::size_t chunks = (n + grain - 1) / grain;
    std::vector<Acc> parts(chunks);
    const float* src = &in.data()->x;
    float* dst = &out.data()->x;
    float* up = upload ? &upload->x : nullptr;
    const auto copy_chunk = [&](std::size_t c) {
        const std::size_t begin = c * grain, end = std::min(n, begin + grain);
        Acc& acc = parts[c];
        if (!up) {
            copyVertices<false>(src + 3 * begin, dst + 3 * begin, nullptr, end - begin, acc);
        } else if (writes == UploadWrites::Fused) {
            copyVertices<true>(src + 3 * begin, dst + 3 * begin, up + 3 * begin, end - begin, acc);
        } else {
            for (std::size_t b = begin; b < end; b += kStepVertices) {
                const std::size_t e = std::min(end, b + kStepVertices);
                copyVertices<false>(src + 3 * b, dst + 3 * b, nullptr, e - b, acc);
                std::memcpy(up + 3 * b, dst + 3 * b, (e - b) * sizeof(Float3));
            }
        }
    };
    executor.parallelFor(chunks + extra_items, 1, [&](std::size_t first, std::size_t last) {
        for (std::size_t k = first; k < last; ++k) k < chunks ? copy_chunk(k) : extra(k - chunks);
    });
    Acc all;
    VertexScan r;
    for (std::size_t c = 0; c < chunks; ++c) {
        if (all.finite && !parts[c].finite) {  // the first bad chunk holds the first bad vertex
            r.first_bad = c * grain;
            while (finiteVertex(in[r.first_bad])) ++r.first_bad;
        }
        all.add(parts[c]);
    }
    r.box = {all.lo[0], all.lo[1], all.lo[2], all.hi[0], all.hi[1], all.hi[2]};
    r.max_abs = all.big;
    r.finite = all.finite;
    return r;
}

}  // namespace

VertexScan copyAndScan(Executor& executor, std::span<const Float3> in, std::span<Float3> out, Float3* upload, UploadWrites writes) {
    return copyScanWith(executor, in, out, upload, writes, 0, [](std::size_t) {});
}

namespace {

// One mesh's sampling: all its triangles up to kShapeSampleTriangles, else that many in
// evenly spaced blocks of kShapeBlock consecutive ones (neighbouring triangles share vertex
// cache lines: a sample of single triangles spread over the mesh misses the cache about
// four times per triangle, and the vertices were just written by other cores), measured in
// runs of kShapeChunk.
struct ShapeSampling {
    std::size_t triangles = 0, sampled = 0, first_run = 0;

    // A mesh of `indices`, its runs numbered from first_run.
    static ShapeSampling of(std::span<const std::uint32_t> indices, std::size_t first_run) {
        ShapeSampling m;
        m.triangles = indices.size() / 3;
        m.sampled = std::min(m.triangles, kShapeSampleTriangles);
        m.first_run = first_run;
        return m;
    }
    std::size_t runs() const { return (sampled + kShapeChunk - 1) / kShapeChunk; }

    std::size_t triangleOf(std::size_t k) const {
        if (sampled == triangles) return k;
        constexpr std::size_t kBlocks = kShapeSampleTriangles / kShapeBlock;
        return (k / kShapeBlock) * triangles / kBlocks + k % kShapeBlock;
    }
};

struct ShapePartial {
    double sum = 0;
    std::array<double, 6> moment{};
    std::array<double, 3> axis_area{};
};

// The partial sums of sampled triangles [begin, end) of one mesh.
ShapePartial shapeRun(const ShapeMesh& mesh, const ShapeSampling& sampling, std::size_t begin, std::size_t end) {
    using Vec3 = std::array<double, 3>;
    ShapePartial p;
    auto at = [&](std::uint32_t i) { return Vec3{mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}; };
    auto dist = [](const Vec3& a, const Vec3& b) {
        return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    };
    for (std::size_t k = begin; k < end; ++k) {
        const std::size_t t = 3 * sampling.triangleOf(k);
        const Vec3 p0 = at(mesh.indices[t]), p1 = at(mesh.indices[t + 1]), p2 = at(mesh.indices[t + 2]);
        p.sum += dist(p0, p1) + dist(p1, p2) + dist(p2, p0);
        const Vec3 u{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const Vec3 c{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (!(len > 0)) continue;
        const double w = 0.5 / len;  // area * n n^T = N N^T / (2 |N|)
        p.moment[0] += w * c[0] * c[0], p.moment[1] += w * c[1] * c[1], p.moment[2] += w * c[2] * c[2];
        p.moment[3] += w * c[0] * c[1], p.moment[4] += w * c[0] * c[2], p.moment[5] += w * c[1] * c[2];
        for (int a = 0; a < 3; ++a)
            if (std::fabs(c[a]) >= kAxisFaceCos * len) p.axis_area[a] += 0.5 * len;
    }
    return p;
}

// A mesh's shape from its runs' partial sums, added in run order.
Shape finishShape(const ShapeSampling& m, std::span<const ShapePartial> parts) {
    Shape s;
    double sum = 0;
    for (std::size_t r = m.first_run; r < m.first_run + m.runs(); ++r) {
        sum += parts[r].sum;
        for (int k = 0; k < 6; ++k) s.area_moment[k] += parts[r].moment[k];
        for (int a = 0; a < 3; ++a) s.axis_area[a] += parts[r].axis_area[a];
    }
    // Scaled to the whole mesh: the moment is a sum over triangles.
    const double scale = m.sampled ? double(m.triangles) / double(m.sampled) : 0.0;
    for (double& v : s.area_moment) v *= scale;
    for (double& v : s.axis_area) v *= scale;
    s.edge_length = m.sampled ? static_cast<float>(sum / double(3 * m.sampled)) : 0.0f;
    return s;
}

}  // namespace

Shape measureShape(Executor& executor, std::span<const Float3> positions, std::span<const std::uint32_t> indices) {
    const ShapeMesh mesh{positions, indices};
    Shape s;
    measureShapes(executor, std::span(&mesh, 1), std::span(&s, 1));
    return s;
}

void measureShapes(Executor& executor, std::span<const ShapeMesh> meshes, std::span<Shape> out) {
    std::vector<ShapeSampling> sampling(meshes.size());
    std::size_t runs = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        sampling[i] = ShapeSampling::of(meshes[i].indices, runs);
        runs += sampling[i].runs();
    }
    // One item per run of kShapeChunk sampled triangles of some mesh: the same runs, so
    // the same partial sums, as measuring each mesh alone.
    std::vector<ShapePartial> parts(runs);
    executor.parallelFor(runs, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const auto mesh = std::upper_bound(sampling.begin(), sampling.end(), r,
                                               [](std::size_t run, const ShapeSampling& m) { return run < m.first_run; }) - 1;
            // Meshes without triangles own no run, so several may share a first_run: the
            // last of them (upper_bound - 1) is the one with runs.
            const std::size_t i = static_cast<std::size_t>(mesh - sampling.begin());
            const std::size_t first = (r - mesh->first_run) * kShapeChunk;
            parts[r] = shapeRun(meshes[i], *mesh, first, std::min(first + kShapeChunk, mesh->sampled));
        }
    });
    for (std::size_t i = 0; i < meshes.size(); ++i) out[i] = finishShape(sampling[i], parts);
}

VertexScan copyScanAndMeasure(Executor& executor, std::span<const Float3> in, std::span<Float3> out, Float3* upload,
                              std::span<const std::uint32_t> indices, Shape& shape, UploadWrites writes) {
    const ShapeSampling sampling = ShapeSampling::of(indices, 0);
    const std::size_t runs = sampling.runs();
    std::vector<ShapePartial> parts(runs);
    const ShapeMesh mesh{in, indices};
    const VertexScan scan = copyScanWith(executor, in, out, upload, writes, runs, [&](std::size_t r) {
        const std::size_t first = r * kShapeChunk;
        parts[r] = shapeRun(mesh, sampling, first, std::min(first + kShapeChunk, sampling.sampled));
    });
    if (scan.finite) shape = finishShape(sampling, parts);
    return scan;
}

}  // namespace vkcollide::vertex_scans
