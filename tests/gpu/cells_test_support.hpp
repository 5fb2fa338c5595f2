// Shared by the cell stage's tests: a scene of host meshes with transforms uploaded
// as gpu::ObjectGpu, a projection fitted to it along a direction, one run of the stage,
// and its survivors as (object, triangle) pairs for comparison with the exact reference.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "broad/cells/cell_stage.hpp"
#include "graph/executor.hpp"
#include "graph/graph.hpp"
#include "support/exact_reference.hpp"
#include "support/gpu_fixture.hpp"

namespace vkcollide::test {

// A generated mesh, required to have been made, named.
inline HostMesh generated(Result<HostMesh> made, const char* name) {
    REQUIRE(made);
    made->name = name;
    return std::move(*made);
}

// `count` independent triangles (no shared vertices) with vertices within `size` of a
// random point of the cube [lo, hi]^3.
inline HostMesh soup(std::mt19937& rng, std::uint32_t count, float lo, float hi, float size, const char* name) {
    std::uniform_real_distribution<float> where(lo, hi), offset(-size, size);
    HostMesh m;
    m.name = name;
    for (std::uint32_t t = 0; t < count; ++t) {
        const Float3 c{where(rng), where(rng), where(rng)};
        for (int k = 0; k < 3; ++k) {
            m.indices.push_back(static_cast<std::uint32_t>(m.positions.size()));
            m.positions.push_back({c.x + offset(rng), c.y + offset(rng), c.z + offset(rng)});
        }
    }
    return m;
}

// Appends a triangle with vertices of its own.
inline void addTriangle(HostMesh& m, Float3 a, Float3 b, Float3 c) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
}

struct CellScene {
    std::vector<HostMesh> meshes;
    std::vector<Transform> transforms;  // one per mesh; missing: identity
    std::vector<std::uint8_t> self;     // one per mesh; missing: off
    Transform transformOf(std::size_t i) const { return i < transforms.size() ? transforms[i] : kIdentityTransform; }
    bool selfOf(std::size_t i) const { return i < self.size() && self[i] != 0; }
};

// The scene's positions and indices in host-visible GPU buffers.
struct UploadedScene {
    std::vector<vk::Buffer> buffers;
    std::vector<gpu::ObjectGpu> objects;
};

// Mesh i of the scene as an object whose positions and indices are at these addresses.
inline gpu::ObjectGpu objectOf(const CellScene& scene, std::size_t i, VkDeviceAddress vertices, VkDeviceAddress indices,
                               std::uint32_t triangle_base, std::uint32_t flags = 0) {
    const HostMesh& m = scene.meshes[i];
    gpu::ObjectGpu o{};
    o.vertices = vertices;
    o.indices = indices;
    o.vertex_stride = 12;
    o.vertex_count = static_cast<std::uint32_t>(m.positions.size());
    o.triangle_count = static_cast<std::uint32_t>(m.triangleCount());
    o.triangle_base = triangle_base;
    o.flags = flags;
    const Transform t = scene.transformOf(i);
    for (int r = 0; r < 3; ++r) o.model[r] = {t[4 * r], t[4 * r + 1], t[4 * r + 2], t[4 * r + 3]};
    return o;
}

// Every mesh in one vertex and one index buffer (32-bit indices), each object addressing
// its part: scenes of more objects than a device has allocations.
inline UploadedScene uploadSharedScene(vk::Device& device, const CellScene& scene) {
    std::size_t vertices = 0, indices = 0;
    for (const HostMesh& m : scene.meshes) vertices += m.positions.size(), indices += m.indices.size();
    auto vb = vk::Buffer::create(device, std::max<std::size_t>(vertices * 12, 16), 0, vk::MemoryKind::Upload, "test-vertices");
    auto ib = vk::Buffer::create(device, std::max<std::size_t>(indices * 4, 16), 0, vk::MemoryKind::Upload, "test-indices");
    REQUIRE(vb);
    REQUIRE(ib);
    UploadedScene up;
    std::size_t v = 0, k = 0;
    std::uint32_t base = 0;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const HostMesh& m = scene.meshes[i];
        std::memcpy(static_cast<char*>(vb->mapped()) + v * 12, m.positions.data(), m.positions.size() * 12);
        std::memcpy(static_cast<char*>(ib->mapped()) + k * 4, m.indices.data(), m.indices.size() * 4);
        const gpu::ObjectGpu o = objectOf(scene, i, vb->address() + v * 12, ib->address() + k * 4, base);
        base += o.triangle_count;
        v += m.positions.size();
        k += m.indices.size();
        up.objects.push_back(o);
    }
    vb->flush();
    ib->flush();
    up.buffers.push_back(std::move(*vb));
    up.buffers.push_back(std::move(*ib));
    return up;
}

inline UploadedScene uploadScene(vk::Device& device, const CellScene& scene, bool index16 = false) {
    UploadedScene up;
    std::uint32_t base = 0;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const HostMesh& m = scene.meshes[i];
        auto vb = vk::Buffer::create(device, std::max<std::size_t>(m.positions.size() * 12, 16), 0, vk::MemoryKind::Upload, "test-vertices");
        REQUIRE(vb);
        std::memcpy(vb->mapped(), m.positions.data(), m.positions.size() * 12);
        vb->flush();
        const std::size_t index_bytes = index16 ? (m.indices.size() * 2 + 3) / 4 * 4 : m.indices.size() * 4;
        auto ib = vk::Buffer::create(device, std::max<std::size_t>(index_bytes, 16), 0, vk::MemoryKind::Upload, "test-indices");
        REQUIRE(ib);
        if (index16) {
            auto* idx = static_cast<std::uint16_t*>(ib->mapped());
            for (std::size_t k = 0; k < m.indices.size(); ++k) idx[k] = static_cast<std::uint16_t>(m.indices[k]);
        } else {
            std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
        }
        ib->flush();
        const gpu::ObjectGpu o = objectOf(scene, i, vb->address(), ib->address(), base, index16 ? gpu::kObjectIndex16 : 0u);
        base += o.triangle_count;
        up.objects.push_back(o);
        up.buffers.push_back(std::move(*vb));
        up.buffers.push_back(std::move(*ib));
    }
    return up;
}

// Sampling = world: x and y across the grid's [0, 1]^2, z the depth.
inline gpu::Projection worldProjection() {
    gpu::Projection pr{};
    pr.row[0] = {1, 0, 0, 0};
    pr.row[1] = {0, 1, 0, 0};
    pr.row[2] = {0, 0, 1, 0};
    return pr;
}

// Maps the scene's world box seen along `direction` onto [0, 1]^2 (square cells) and the
// depth onto [0, 1]. Any affine map would do for correctness; this one makes cells useful.
inline gpu::Projection fitProjection(const CellScene& scene, std::array<double, 3> direction) {
    double len = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    std::array<double, 3> d = {direction[0] / len, direction[1] / len, direction[2] / len};
    std::array<double, 3> a = std::fabs(d[0]) > 0.9 ? std::array<double, 3>{0, 1, 0} : std::array<double, 3>{1, 0, 0};
    double dot = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    std::array<double, 3> u = {a[0] - d[0] * dot, a[1] - d[1] * dot, a[2] - d[2] * dot};
    double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= ul;
    std::array<double, 3> v = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    const std::array<std::array<double, 3>, 3> basis = {u, v, d};
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < scene.meshes.size(); ++i)
        for (const Float3& p : worldPositions(scene.meshes[i], scene.transformOf(i)))
            for (int k = 0; k < 3; ++k) {
                const double s = basis[k][0] * p.x + basis[k][1] * p.y + basis[k][2] * p.z;
                lo[k] = std::min(lo[k], s);
                hi[k] = std::max(hi[k], s);
            }
    double size = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(size > 0)) size = 1;
    double depth = hi[2] - lo[2];
    if (!(depth > 0)) depth = 1;
    gpu::Projection p{};
    const double scale[3] = {size, size, depth};
    for (int k = 0; k < 3; ++k)
        p.row[k] = {float(basis[k][0] / scale[k]), float(basis[k][1] / scale[k]), float(basis[k][2] / scale[k]),
                    float(-lo[k] / scale[k])};
    return p;
}

struct CellRun {
    passes::CellStageResult result;
    std::vector<TrianglePair> pairs;  // (object, triangle) pairs
};

inline std::vector<TrianglePair> toObjectPairs(const std::vector<gpu::ObjectGpu>& objects,
                                               const std::vector<std::array<std::uint32_t, 2>>& global) {
    auto locate = [&](std::uint32_t t) {
        std::size_t o = objects.size() - 1;
        while (objects[o].triangle_base > t || objects[o].triangle_count == 0) --o;
        return std::pair<std::uint32_t, std::uint32_t>(static_cast<std::uint32_t>(o), t - objects[o].triangle_base);
    };
    std::vector<TrianglePair> out;
    for (const auto& g : global) {
        auto [oa, ta] = locate(g[0]);
        auto [ob, tb] = locate(g[1]);
        out.push_back({oa, ta, ob, tb});
    }
    return out;
}

struct CellRunOptions {
    std::uint32_t resolution = 64;
    std::array<double, 3> direction{0, 0, 1};
    passes::CellStageSettings settings;
    std::function<bool(std::uint32_t, std::uint32_t)> may_collide;
    bool index16 = false;
    bool shared_buffers = false;                // uploadSharedScene (32-bit indices)
    std::optional<gpu::Projection> projection;  // instead of fitting one along `direction`
};

inline CellRun runCells(ValidatedContext& ctx, passes::CellStage& stage, const CellScene& scene, const CellRunOptions& opt) {
    UploadedScene up = opt.shared_buffers ? uploadSharedScene(ctx.device(), scene) : uploadScene(ctx.device(), scene, opt.index16);
    passes::CellStageInput in;
    in.objects = up.objects;
    in.projection = opt.projection ? *opt.projection : fitProjection(scene, opt.direction);
    in.resolution = opt.resolution;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) in.self_collision.push_back(scene.selfOf(i) ? 1 : 0);
    in.may_collide = opt.may_collide;
    graph::Executor executor(ctx.device());
    auto r = stage.run(executor, in, opt.settings);
    INFO((r ? std::string() : r.error().message()));
    REQUIRE(r);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
    CellRun run;
    run.pairs = toObjectPairs(up.objects, r->pairs);
    run.result = std::move(*r);
    return run;
}

inline std::vector<TrianglePair> referencePairs(const CellScene& scene,
                                                std::function<bool(std::uint32_t, std::uint32_t)> may_collide = {}) {
    std::vector<ReferenceObject> objs;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) objs.push_back({&scene.meshes[i], scene.transformOf(i), scene.selfOf(i)});
    ReferenceOptions options;
    options.may_collide = std::move(may_collide);
    auto r = computeReferencePairs(objs, options);
    REQUIRE(r);
    return *r;
}

// Every reference pair must be a survivor (recall 100 %, touching included).
inline void requireAllFound(const CellRun& run, const std::vector<TrianglePair>& reference) {
    const PairComparison c = comparePairs(run.pairs, reference);
    INFO("reference " << reference.size() << ", survivors " << run.pairs.size() << ", missed " << c.false_negatives
                      << ", candidates " << run.result.stats.candidates << ", entries " << run.result.stats.entries);
    for (std::size_t i = 0; i < std::min<std::size_t>(c.missed.size(), 5); ++i)
        UNSCOPED_INFO("missed (" << c.missed[i].object_a << ", " << c.missed[i].triangle_a << ") x (" << c.missed[i].object_b
                                 << ", " << c.missed[i].triangle_b << ")");
    REQUIRE(c.false_negatives == 0);
}

// With the exact pass run, the survivors are the reference's pairs (none missed, none
// extra); without it (a device without shaderFloat64), every reference pair is a survivor.
inline void requireExactPairs(const CellRun& run, const std::vector<TrianglePair>& reference) {
    if (!run.result.stats.exact_ran) return requireAllFound(run, reference);
    const PairComparison cmp = comparePairs(run.pairs, reference);
    CHECK(cmp.false_negatives == 0);
    CHECK(cmp.false_positives == 0);
}

// The stage run as part of a larger graph: an earlier pass of that graph writes the
// projection `pr` into a device-local buffer (as the detection's fit does) and the stage
// reads it there; rerun until complete (at most 8 runs). `in` is used as given, its
// projection_address set here.
inline passes::CellStageResult runWithWrittenProjection(ValidatedContext& ctx, passes::CellStage& stage, passes::CellStageInput in,
                                                        const gpu::Projection& pr) {
    auto staging = vk::Buffer::create(ctx.device(), sizeof pr, 0, vk::MemoryKind::Upload, "projection-staging");
    auto written = vk::Buffer::create(ctx.device(), sizeof pr, 0, vk::MemoryKind::DeviceLocal, "projection");
    REQUIRE(staging);
    REQUIRE(written);
    std::memcpy(staging->mapped(), &pr, sizeof pr);
    staging->flush();
    in.projection.reset();
    in.projection_address = written->address();
    REQUIRE(stage.prepare(in));
    graph::Executor executor(ctx.device());
    passes::CellStageResult out;
    for (int attempt = 0;; ++attempt) {
        REQUIRE(attempt < 8);
        graph::Graph g;
        const auto src = g.importBuffer("projection-staging", *staging);
        const auto dst = g.importBuffer("projection", *written);
        const VkBuffer from = staging->handle(), to = written->handle();
        g.addPass("write-projection", graph::PassKind::Transfer)
            .use(src, graph::Use::TransferSrc)
            .use(dst, graph::Use::TransferDst)
            .record([from, to](graph::PassContext& pc) {
                VkBufferCopy copy{0, 0, sizeof(gpu::Projection)};
                pc.fns().vkCmdCopyBuffer(pc.cmd, from, to, 1, &copy);
            });
        stage.record(g, dst);
        REQUIRE(executor.run(g));
        auto outcome = stage.finish(out);
        while (outcome && *outcome == passes::CellStage::Outcome::MorePairs) {  // the pair pass's next chunk
            graph::Graph chunk;
            stage.recordPairChunk(chunk);
            REQUIRE(executor.run(chunk));
            outcome = stage.finish(out);
        }
        INFO((outcome ? std::string() : outcome.error().message()));
        REQUIRE(outcome);
        if (*outcome == passes::CellStage::Outcome::Complete) break;
    }
    return out;
}

}  // namespace vkcollide::test
