#include "passes/broad_phase.hpp"

#include <chrono>
#include <cmath>
#include <cstring>

#include "broadphase.h"
#include "shaders/all.hpp"

namespace vkcollide::passes {
namespace {

using graph::PassContext;
using graph::PassKind;
using graph::Use;

static_assert(gpu::kPackRowWidth == gpu::kGroupSize, "pack_rowcount reduces a row with the workgroup helpers");

std::uint32_t groups(std::uint64_t items, std::uint32_t size = gpu::kGroupSize) {
    return static_cast<std::uint32_t>((items + size - 1) / size);
}

void bindAndPush(const PassContext& pc, const vk::Pipeline& p, VkDeviceAddress frame, std::uint32_t object = 0,
                 std::uint32_t step = 0, std::uint32_t level = 0) {
    gpu::Push push{frame, object, step, level, 0};
    pc.fns().vkCmdBindPipeline(pc.cmd, p.bindPoint(), p.handle());
    const VkShaderStageFlags stages = p.bindPoint() == VK_PIPELINE_BIND_POINT_COMPUTE
                                          ? VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT)
                                          : VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    pc.fns().vkCmdPushConstants(pc.cmd, p.layout(), stages, 0, sizeof(push), &push);
}

}  // namespace

// Orthonormal u, v, d with u x v = d (so outward faces seen along d are front-facing).
std::array<float, 9> projectionBasis(const std::array<float, 3>& dir) {
    double d[3] = {dir[0], dir[1], dir[2]};
    double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& x : d) x /= len;
    double a[3] = {1, 0, 0};
    if (std::fabs(d[0]) > 0.9) a[0] = 0, a[1] = 1;
    double dot = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    double u[3] = {a[0] - d[0] * dot, a[1] - d[1] * dot, a[2] - d[2] * dot};
    double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= ul;
    double v[3] = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    return {float(u[0]), float(u[1]), float(u[2]), float(v[0]), float(v[1]), float(v[2]),
            float(d[0]), float(d[1]), float(d[2])};
}

SamplingProjection projectionForRegion(const std::array<float, 9>& basis, const std::array<float, 6>& b, float open_epsilon) {
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        float mn = 0, mx = 0;
        for (int c = 0; c < 8; ++c) {
            float p[3] = {(c & 1) ? b[3] : b[0], (c & 2) ? b[4] : b[1], (c & 4) ? b[5] : b[2]};
            float dot = basis[a * 3] * p[0] + basis[a * 3 + 1] * p[1] + basis[a * 3 + 2] * p[2];
            mn = c == 0 ? dot : std::min(mn, dot);
            mx = c == 0 ? dot : std::max(mx, dot);
        }
        lo[a] = mn;
        hi[a] = mx;
    }
    float size = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(size > 0)) size = 1;
    float depth = hi[2] - lo[2];
    if (!(depth > 0)) depth = 1;
    SamplingProjection out;
    for (int a = 0; a < 2; ++a) {
        float origin = 0.5f * (lo[a] + hi[a]) - 0.5f * size;
        for (int k = 0; k < 3; ++k) out.rows[a * 4 + k] = basis[a * 3 + k] / size;
        out.rows[a * 4 + 3] = -origin / size;
    }
    for (int k = 0; k < 3; ++k) out.rows[8 + k] = basis[6 + k] * 0.9f / depth;
    out.rows[11] = 0.05f - 0.9f * lo[2] / depth;
    out.rows[13] = 0.9f / depth;
    out.rows[12] = open_epsilon * out.rows[13];
    return out;
}

Result<std::unique_ptr<BroadPhase>> BroadPhase::create(vk::Device& device) {
    std::unique_ptr<BroadPhase> bp(new BroadPhase(device));
    const std::uint32_t push = sizeof(gpu::Push);
    const std::span<const vk::Pipeline::Binding> none;
    auto compute = [&](vk::Pipeline& out, std::span<const std::uint32_t> code, const char* name) -> Result<void> {
        auto p = vk::Pipeline::createCompute(device, code, none, push, name);
        if (!p) return p.error();
        out = std::move(*p);
        return {};
    };
    auto raster = [&](vk::Pipeline& out, std::span<const std::uint32_t> frag, const char* name) -> Result<void> {
        vk::Pipeline::RasterDesc rd;
        rd.vertex_spirv = shaders::sample_vert;
        rd.fragment_spirv = frag;
        auto p = vk::Pipeline::createRaster(device, rd, none, push, name);
        if (!p) return p.error();
        out = std::move(*p);
        return {};
    };
    auto& P = bp->pipes_;
    for (auto r : {compute(P.bounds, shaders::bounds_comp, "bounds"), compute(P.fit, shaders::fit_comp, "fit"),
                   raster(P.count, shaders::count_frag, "count"), raster(P.peel, shaders::peel_frag, "peel"),
                   compute(P.reduce_max, shaders::reduce_max_comp, "reduce-max"),
                   compute(P.peel_init, shaders::peel_init_comp, "peel-init"),
                   compute(P.classify, shaders::classify_comp, "classify"),
                   compute(P.finalize, shaders::finalize_comp, "finalize"), compute(P.merge, shaders::merge_comp, "merge"),
                   compute(P.separate, shaders::separate_comp, "separate"),
                   compute(P.pack_rowcount, shaders::pack_rowcount_comp, "pack-rowcount"),
                   compute(P.scan_counts, shaders::scan_counts_comp, "scan-counts"),
                   compute(P.pack_shift, shaders::pack_shift_comp, "pack-shift"),
                   compute(P.pack_move, shaders::pack_move_comp, "pack-move"),
                   compute(P.scan_blocksum, shaders::scan_blocksum_comp, "scan-blocksum"),
                   compute(P.scan_scatter, shaders::scan_scatter_comp, "scan-scatter")})
        if (!r) return r.error();
    return bp;
}

Result<void> BroadPhase::ensureBuffers(std::uint32_t n, std::uint32_t triangles, std::uint32_t objects, bool ray_image) {
    using vk::MemoryKind;
    auto make = [&](vk::Buffer& b, VkDeviceSize size, MemoryKind kind, const char* name) -> Result<void> {
        if (b.valid() && b.size() >= size) return {};
        auto r = vk::Buffer::create(*device_, size, 0, kind, name);
        if (!r) return r.error();
        b = std::move(*r);
        return {};
    };
    const VkDeviceSize pixels = VkDeviceSize(n) * n;
    VkDeviceSize texels = 0;
    for (std::uint32_t s = n; s >= 1; s /= 2) texels += VkDeviceSize(s) * s;
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles, 1);
    const VkDeviceSize rows = (tris + gpu::kPackRowWidth - 1) / gpu::kPackRowWidth;
    const VkDeviceSize blocks = (tris + gpu::kGroupSize - 1) / gpu::kGroupSize;
    const VkDeviceSize scratch = std::max(2 * rows + 2 * rows * gpu::kPackRowWidth, 2 * blocks);
    for (auto r : {make(buf_.frame, sizeof(gpu::Frame), MemoryKind::Upload, "frame"),
                   make(buf_.objects_buf, sizeof(gpu::ObjectGpu) * std::max<std::uint32_t>(objects, 1), MemoryKind::Upload, "objects"),
                   make(buf_.projection, sizeof(gpu::Projection), MemoryKind::Upload, "projection"),
                   make(buf_.header, sizeof(gpu::Header), MemoryKind::DeviceLocal, "header"),
                   make(buf_.header_rb, sizeof(gpu::Header), MemoryKind::Readback, "header-readback"),
                   make(buf_.counts, pixels * 4, MemoryKind::DeviceLocal, "counts"),
                   make(buf_.front, pixels * 8, MemoryKind::DeviceLocal, "front-keys"),
                   make(buf_.back, pixels * 8, MemoryKind::DeviceLocal, "back-keys"),
                   make(buf_.state, pixels * sizeof(gpu::PixelState), MemoryKind::DeviceLocal, "ray-state"),
                   make(buf_.bundles, texels * 16, MemoryKind::DeviceLocal, "bundles"),
                   make(buf_.sparse, tris * 16, MemoryKind::DeviceLocal, "sparse"),
                   make(buf_.records, tris * sizeof(CandidateTriangle), MemoryKind::Readback, "records"),
                   make(buf_.scratch, scratch * 4, MemoryKind::DeviceLocal, "pack-scratch")})
        if (!r) return r.error();
    if (ray_image) {
        if (auto r = make(buf_.ray_image, pixels * 4, MemoryKind::Readback, "ray-image"); !r) return r.error();
    }
    return {};
}

void BroadPhase::addHeaderReadback(graph::Graph& g, graph::ResourceId header, graph::ResourceId header_rb) const {
    g.addPass("readback-header", PassKind::Transfer).use(header, Use::TransferSrc).use(header_rb, Use::TransferDst).record([this](PassContext& pc) {
        VkBufferCopy copy{0, 0, sizeof(gpu::Header)};
        pc.fns().vkCmdCopyBuffer(pc.cmd, buf_.header.handle(), buf_.header_rb.handle(), 1, &copy);
    });
}

Result<BroadPhaseResult> BroadPhase::run(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
    const std::uint32_t n = s.resolution;
    if (n < 4 || n > 16384 || (n & (n - 1)) != 0)
        return Error(ErrorCode::InvalidArgument, "resolution " + std::to_string(n) + " is not a power of two in [4, 16384]");
    const float dl = s.direction[0] * s.direction[0] + s.direction[1] * s.direction[1] + s.direction[2] * s.direction[2];
    if (!(dl > 0) || !std::isfinite(dl)) return Error(ErrorCode::InvalidArgument, "projection direction must be finite and non-zero");
    if (meshes.empty()) return Error(ErrorCode::InvalidArgument, "no objects to test (zero meshes)");
    if (!(s.open_epsilon >= 0) || !std::isfinite(s.open_epsilon)) return Error(ErrorCode::InvalidArgument, "open_epsilon must be finite and >= 0");

    std::uint64_t total = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const GpuMesh& m = meshes[i];
        const std::string who = "object " + std::to_string(i) + ": ";
        if (m.triangle_count == 0) return Error(ErrorCode::InvalidMesh, who + "has no triangles (empty mesh)");
        if (!m.vertices || !m.indices) return Error(ErrorCode::InvalidArgument, who + "vertex or index address is null");
        if (m.vertex_stride < 12 || m.vertex_stride % 4 != 0 || m.vertices % 4 != 0)
            return Error(ErrorCode::InvalidArgument, who + "positions must be 4-byte aligned with a stride of at least 12 bytes");
        for (float t : m.transform)
            if (!std::isfinite(t)) return Error(ErrorCode::InvalidArgument, who + "transform is not finite");
        total += m.triangle_count;
    }
    if (total >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidArgument, "scene has more than 2^30 triangles");
    const auto triangles = static_cast<std::uint32_t>(total);
    const auto objects = static_cast<std::uint32_t>(meshes.size());
    if (auto ok = ensureBuffers(n, triangles, objects, s.keep_ray_image); !ok) return ok.error();
    const BackendChoice backend = chooseSamplingBackend(device_->properties, computeSamplingSupported(*device_), s.backend, n, triangles,
                                                        triangles == last_triangles_ ? last_fragments_per_triangle_ : -1.0);
    const bool compute = backend.backend == SamplingBackend::Compute;
    VkDeviceAddress compute_frame = 0;
    if (compute) {
        if (!compute_) {
            auto created = ComputeSampling::create(*device_);
            if (!created) return created.error();
            compute_ = std::move(*created);
        }
        auto prepared = compute_->prepare(n, triangles, s.compute);
        if (!prepared) return prepared.error();
        compute_frame = *prepared;
    }

    // Upload objects and the frame description.
    auto* objs = static_cast<gpu::ObjectGpu*>(buf_.objects_buf.mapped());
    std::uint32_t base = 0;
    for (std::uint32_t i = 0; i < objects; ++i) {
        const GpuMesh& m = meshes[i];
        gpu::ObjectGpu o{};
        o.vertices = m.vertices;
        o.indices = m.indices;
        o.vertex_stride = m.vertex_stride;
        o.vertex_count = m.vertex_count;
        o.triangle_count = m.triangle_count;
        o.triangle_base = base;
        o.flags = (m.open ? gpu::kObjectOpen : 0u) | (m.index16 ? gpu::kObjectIndex16 : 0u);
        for (int r = 0; r < 3; ++r) o.model[r] = {m.transform[r * 4], m.transform[r * 4 + 1], m.transform[r * 4 + 2], m.transform[r * 4 + 3]};
        objs[i] = o;
        base += m.triangle_count;
    }
    buf_.objects_buf.flush();
    std::uint32_t levels = 0;
    for (std::uint32_t x = n; x >= 1; x /= 2) ++levels;
    gpu::Frame fr{};
    fr.objects = buf_.objects_buf.address();
    fr.projection = buf_.projection.address();
    fr.header = buf_.header.address();
    fr.counts = buf_.counts.address();
    fr.front_keys = buf_.front.address();
    fr.back_keys = buf_.back.address();
    fr.state = buf_.state.address();
    fr.bundles = buf_.bundles.address();
    fr.sparse = buf_.sparse.address();
    fr.records = buf_.records.address();
    fr.scratch = buf_.scratch.address();
    fr.ray_image = s.keep_ray_image ? buf_.ray_image.address() : 0;
    fr.resolution = n;
    fr.levels = levels;
    fr.object_count = objects;
    fr.triangle_count = triangles;
    fr.dual = s.dual ? 1u : 0u;
    fr.pack_rows = (std::max(triangles, 1u) + gpu::kPackRowWidth - 1) / gpu::kPackRowWidth;
    fr.pack_blocks = (std::max(triangles, 1u) + gpu::kGroupSize - 1) / gpu::kGroupSize;
    const auto basis = projectionBasis(s.direction);
    std::memcpy(fr.direction_basis, basis.data(), sizeof(float) * 9);
    fr.open_epsilon_world = s.open_epsilon;
    fr.fit_margin = s.fit_margin;
    fr.compute_sampling = compute_frame;
    VkDeviceSize offset = 0;
    for (std::uint32_t l = 0; l < levels; ++l) {
        fr.level_offset[l] = static_cast<std::uint32_t>(offset);
        offset += VkDeviceSize(n >> l) * (n >> l);
    }
    if (s.region) {
        // The caller's box: the same mapping the fit shader computes, done here.
        const SamplingProjection sp = projectionForRegion(basis, *s.region, s.open_epsilon);
        gpu::Projection pr{};
        for (int a = 0; a < 3; ++a) pr.row[a] = {sp.rows[a * 4], sp.rows[a * 4 + 1], sp.rows[a * 4 + 2], sp.rows[a * 4 + 3]};
        pr.open_epsilon = sp.rows[12];
        pr.world_to_depth = sp.rows[13];
        std::memcpy(buf_.projection.mapped(), &pr, sizeof(pr));
        buf_.projection.flush();
    }

    BroadPhaseResult result;
    result.triangles = triangles;
    result.backend = backend.backend;
    result.backend_reason = backend.reason;
    const VkDeviceAddress frame_addr = buf_.frame.address();
    const std::uint32_t pixels = n * n;
    auto& P = pipes_;

    // ---- submission 1: fit and depth complexity --------------------------------------
    // One frame description serves both submissions.
    std::memcpy(buf_.frame.mapped(), &fr, sizeof(fr));
    buf_.frame.flush();
    graph::Graph g1;
    auto header = g1.importBuffer("header", buf_.header);
    auto header_rb = g1.importBuffer("header-readback", buf_.header_rb, true);
    auto counts = g1.importBuffer("counts", buf_.counts);
    auto projection = g1.importBuffer("projection", buf_.projection);
    g1.addPass("clear", PassKind::Transfer).use(header, Use::TransferDst).use(counts, Use::TransferDst).record([&](PassContext& pc) {
        // Disjoint ranges: counters 0, bound minima +inf (ordered), maxima and padding 0.
        constexpr VkDeviceSize mins = offsetof(gpu::Header, bounds), maxs = mins + 12;
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), 0, mins, 0);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), mins, 12, 0xFFFFFFFFu);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), maxs, sizeof(gpu::Header) - maxs, 0);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.counts.handle(), 0, VkDeviceSize(pixels) * 4, 0);
    });
    if (!s.region) {
        g1.addPass("bounds", PassKind::Compute).readWrite(header).record([&](PassContext& pc) {
            for (std::uint32_t i = 0; i < objects; ++i) {
                bindAndPush(pc, P.bounds, frame_addr, i);
                pc.fns().vkCmdDispatch(pc.cmd, std::max(groups(meshes[i].vertex_count), 1u), 1, 1);
            }
        });
        g1.addPass("fit", PassKind::Compute).read(header).write(projection).record([&](PassContext& pc) {
            bindAndPush(pc, P.fit, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
    }
    if (compute) {
        auto keys_front = g1.importBuffer("front-keys", buf_.front), keys_back = g1.importBuffer("back-keys", buf_.back);
        compute_->addDepthComplexity(g1, compute_->import(g1), {projection, header, counts, {}, keys_front, keys_back}, meshes,
                                     frame_addr);
    } else {
        g1.addPass("depth-complexity", PassKind::Raster).renderArea(n, n).read(projection).readWrite(counts).record([&](PassContext& pc) {
            for (std::uint32_t i = 0; i < objects; ++i) {
                bindAndPush(pc, P.count, frame_addr, i);
                pc.fns().vkCmdDraw(pc.cmd, meshes[i].triangle_count * 3, 1, 0, 0);
            }
        });
    }
    g1.addPass("reduce-max", PassKind::Compute).read(counts).readWrite(header).record([&](PassContext& pc) {
        bindAndPush(pc, P.reduce_max, frame_addr);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
    addHeaderReadback(g1, header, header_rb);
    auto report1 = executor_.run(g1);
    if (!report1) return report1.error();
    buf_.header_rb.invalidate();
    gpu::Header h1;
    std::memcpy(&h1, buf_.header_rb.mapped(), sizeof(h1));
    result.depth_complexity = h1.depth_complexity;
    result.layers = s.layer_cap ? std::min(h1.depth_complexity, s.layer_cap) : h1.depth_complexity;
    result.peel_steps = s.dual ? (result.layers + 1) / 2 : result.layers;
    result.fragments = h1.fragments;
    result.compute_small = h1.cs_small, result.compute_big = h1.cs_big, result.compute_items = h1.cs_items;
    if (compute) {
        if (auto ok = compute_->preparePeeling(h1.depth_complexity); !ok) return ok.error();
        result.compute_fragment_lists = compute_->usesFragmentLists();
    }
    last_triangles_ = triangles;
    last_fragments_per_triangle_ = double(h1.fragments) / double(std::max(triangles, 1u));
    for (auto& p : report1->passes) {
        result.sampling_ms += p.name == "readback-header" ? 0.0 : p.gpu_ms;
        result.passes.push_back(p);
    }

    // ---- submission 2: peel, merge, separate, pack -------------------------------------
    graph::Graph g;
    header = g.importBuffer("header", buf_.header);
    header_rb = g.importBuffer("header-readback", buf_.header_rb, true);
    counts = g.importBuffer("counts", buf_.counts);
    projection = g.importBuffer("projection", buf_.projection);
    auto front = g.importBuffer("front-keys", buf_.front);
    auto back = g.importBuffer("back-keys", buf_.back);
    auto state = g.importBuffer("ray-state", buf_.state);
    auto bundles = g.importBuffer("bundles", buf_.bundles);
    auto sparse = g.importBuffer("sparse", buf_.sparse);
    auto records = g.importBuffer("records", buf_.records, true);
    auto scratch = g.importBuffer("pack-scratch", buf_.scratch);
    graph::ResourceId rays;
    if (s.keep_ray_image) rays = g.importBuffer("ray-image", buf_.ray_image, true);

    g.addPass("peel-init", PassKind::Compute).read(counts).write(state).write(front).write(back).record([&](PassContext& pc) {
        bindAndPush(pc, P.peel_init, frame_addr, 0, compute && compute_->fusesFirstStep() ? 1u : 0u);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
    ComputeSampling::Ids compute_ids;
    if (compute) compute_ids = compute_->import(g);
    for (std::uint32_t step = 0; step < result.peel_steps; ++step) {
        if (compute) {
            compute_->addPeelStep(g, compute_ids, {projection, header, counts, state, front, back}, step, s.dual, frame_addr);
        } else {
            auto peel = g.addPass("peel[" + std::to_string(step) + "]", PassKind::Raster);
            peel.renderArea(n, n).read(projection).read(state).readWrite(front);
            if (s.dual) peel.readWrite(back);
            peel.record([&, step](PassContext& pc) {
                for (std::uint32_t i = 0; i < objects; ++i) {
                    bindAndPush(pc, P.peel, frame_addr, i, step);
                    pc.fns().vkCmdDraw(pc.cmd, meshes[i].triangle_count * 3, 1, 0, 0);
                }
            });
        }
        auto classify = g.addPass("classify[" + std::to_string(step) + "]", PassKind::Compute);
        classify.read(counts).read(projection).readWrite(state).readWrite(front);
        if (s.dual) classify.readWrite(back);
        classify.record([&, step](PassContext& pc) {
            bindAndPush(pc, P.classify, frame_addr, 0, step);
            pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
        });
    }
    auto finalize = g.addPass("finalize", PassKind::Compute);
    finalize.read(state).use(bundles, Use::StorageWrite).readWrite(header);
    if (s.keep_ray_image) finalize.write(rays);
    finalize.record([&](PassContext& pc) {
        bindAndPush(pc, P.finalize, frame_addr);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
    g.addPass("merge", PassKind::Compute).readWrite(bundles).record([&](PassContext& pc) {
        for (std::uint32_t l = 1; l < levels; ++l) {
            bindAndPush(pc, P.merge, frame_addr, 0, 0, l);
            pc.fns().vkCmdDispatch(pc.cmd, groups(VkDeviceSize(n >> l) * (n >> l)), 1, 1);
            if (l + 1 < levels) pc.shaderBarrier();  // level l+1 reads level l
        }
    });
    g.addPass("separate", PassKind::Compute).read(projection).read(bundles).write(sparse).record([&](PassContext& pc) {
        for (std::uint32_t i = 0; i < objects; ++i) {
            bindAndPush(pc, P.separate, frame_addr, i);
            pc.fns().vkCmdDispatch(pc.cmd, groups(meshes[i].triangle_count), 1, 1);
        }
    });
    if (s.packing == PackingMethod::Paper) {
        g.addPass("pack-count", PassKind::Compute).read(sparse).write(scratch).record([&](PassContext& pc) {
            bindAndPush(pc, P.pack_rowcount, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, fr.pack_rows, 1, 1);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan_counts, frame_addr, 0, fr.pack_rows);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
        g.addPass("pack-shift", PassKind::Compute).read(sparse).readWrite(scratch).readWrite(header).record([&](PassContext& pc) {
            bindAndPush(pc, P.pack_shift, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, groups(fr.pack_rows, 64), 1, 1);
        });
        g.addPass("pack-move", PassKind::Compute).read(sparse).read(scratch).read(projection).write(records).record([&](PassContext& pc) {
            bindAndPush(pc, P.pack_move, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, fr.pack_rows, 1, 1);
        });
    } else {
        g.addPass("pack-scan", PassKind::Compute).read(sparse).write(scratch).readWrite(header).record([&](PassContext& pc) {
            bindAndPush(pc, P.scan_blocksum, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, fr.pack_blocks, 1, 1);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan_counts, frame_addr, 0, fr.pack_blocks);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
        g.addPass("pack-scatter", PassKind::Compute).read(sparse).read(scratch).read(projection).write(records).record([&](PassContext& pc) {
            bindAndPush(pc, P.scan_scatter, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, fr.pack_blocks, 1, 1);
        });
    }
    addHeaderReadback(g, header, header_rb);
    auto report = executor_.run(g);
    if (!report) return report.error();

    // The count first, then exactly that many records.
    const auto t0 = std::chrono::steady_clock::now();
    buf_.header_rb.invalidate();
    gpu::Header h2;
    std::memcpy(&h2, buf_.header_rb.mapped(), sizeof(h2));
    result.collision_rays = h2.collision_rays;
    if (h2.record_count > triangles)
        return Error(ErrorCode::VulkanError, "packing reported " + std::to_string(h2.record_count) + " records for " +
                                                 std::to_string(triangles) + " triangles");
    result.records.resize(h2.record_count);
    if (h2.record_count) {
        buf_.records.invalidate(0, VkDeviceSize(h2.record_count) * sizeof(CandidateTriangle));
        std::memcpy(result.records.data(), buf_.records.mapped(), size_t(h2.record_count) * sizeof(CandidateTriangle));
    }
    if (s.keep_ray_image) {
        buf_.ray_image.invalidate();
        result.ray_image.resize(pixels);
        const auto* src = static_cast<const std::uint32_t*>(buf_.ray_image.mapped());
        for (std::uint32_t i = 0; i < pixels; ++i) result.ray_image[i] = static_cast<std::uint8_t>(src[i]);
    }
    result.readback_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    for (auto& p : report->passes) {
        const std::string& name = p.name;
        if (name.rfind("peel", 0) == 0 || name.rfind("classify", 0) == 0 || name.rfind("csample", 0) == 0 || name == "finalize")
            result.sampling_ms += p.gpu_ms;
        else if (name == "merge") result.merging_ms += p.gpu_ms;
        else if (name == "separate") result.separation_ms += p.gpu_ms;
        else if (name.rfind("pack", 0) == 0) result.packing_ms += p.gpu_ms;
        result.passes.push_back(p);
    }
    return result;
}

}  // namespace vkcollide::passes
