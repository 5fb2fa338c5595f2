#include "passes/broad_phase.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <string>

#include "broadphase.h"
#include "passes/projection.hpp"
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
                 std::uint32_t step = 0, std::uint32_t level = 0, std::uint32_t coverage = gpu::kCoverageCentre) {
    gpu::Push push{frame, object, step, level, coverage};
    pc.fns().vkCmdBindPipeline(pc.cmd, p.bindPoint(), p.handle());
    const VkShaderStageFlags stages = p.bindPoint() == VK_PIPELINE_BIND_POINT_COMPUTE
                                          ? VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT)
                                          : VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    pc.fns().vkCmdPushConstants(pc.cmd, p.layout(), stages, 0, sizeof(push), &push);
}

double gib(VkDeviceSize bytes) { return double(bytes) / double(1ull << 30); }

std::string gibText(VkDeviceSize bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f GiB", gib(bytes));
    return buf;
}

// Every buffer the broad phase allocates, sized for a run (one list for ensureBuffers and
// the memory check).
struct BufferPlan {
    const char* name;
    VkDeviceSize size;
    vk::MemoryKind kind;
};
std::vector<BufferPlan> planBuffers(std::uint32_t n, std::uint32_t triangles, std::uint32_t objects) {
    using vk::MemoryKind;
    const VkDeviceSize pixels = VkDeviceSize(n) * n;
    VkDeviceSize texels = 0;
    for (std::uint32_t s = n; s >= 1; s /= 2) texels += VkDeviceSize(s) * s;
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles, 1);
    const VkDeviceSize rows = (tris + gpu::kPackRowWidth - 1) / gpu::kPackRowWidth;
    const VkDeviceSize blocks = (tris + gpu::kGroupSize - 1) / gpu::kGroupSize;
    const VkDeviceSize scratch = std::max(2 * rows + 2 * rows * gpu::kPackRowWidth, 2 * blocks);
    return {{"frame", sizeof(gpu::Frame), MemoryKind::Upload},
            {"objects", sizeof(gpu::ObjectGpu) * std::max<std::uint32_t>(objects, 1), MemoryKind::Upload},
            {"projection", sizeof(gpu::Projection), MemoryKind::Upload},
            {"header", sizeof(gpu::Header), MemoryKind::DeviceLocal},
            {"header-readback", sizeof(gpu::Header), MemoryKind::Readback},
            {"counts", pixels * 4, MemoryKind::DeviceLocal},
            {"front-keys", pixels * 8, MemoryKind::DeviceLocal},
            {"back-keys", pixels * 8, MemoryKind::DeviceLocal},
            {"ray-state", pixels * sizeof(gpu::PixelState), MemoryKind::DeviceLocal},
            {"bundles", texels * 16, MemoryKind::DeviceLocal},
            {"sparse", tris * 16, MemoryKind::DeviceLocal},
            {"records", tris * sizeof(CandidateTriangle), MemoryKind::Readback},
            {"pack-scratch", scratch * 4, MemoryKind::DeviceLocal}};
}

}  // namespace

VkDeviceSize broadPhaseMemory(std::uint32_t resolution, std::uint32_t triangles, std::uint32_t objects) {
    VkDeviceSize total = 0;
    for (const BufferPlan& b : planBuffers(resolution, triangles, objects)) total += b.size;
    return total;
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
    auto raster = [&](vk::Pipeline& out, std::span<const std::uint32_t> frag, const char* name, bool conservative = false) -> Result<void> {
        vk::Pipeline::RasterDesc rd;
        rd.vertex_spirv = shaders::sample_vert;
        rd.fragment_spirv = frag;
        rd.conservative = conservative;
        auto p = vk::Pipeline::createRaster(device, rd, none, push, name);
        if (!p) return p.error();
        out = std::move(*p);
        return {};
    };
    auto& P = bp->pipes_;
    for (auto r : {compute(P.validate, shaders::validate_comp, "validate"), compute(P.bounds, shaders::bounds_comp, "bounds"), compute(P.fit, shaders::fit_comp, "fit"),
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
    if (device.conservative_rasterization)
        if (auto r = raster(P.count_conservative, shaders::count_frag, "count-conservative", true); !r) return r.error();
    return bp;
}

Result<void> BroadPhase::ensureBuffers(std::uint32_t n, std::uint32_t triangles, std::uint32_t objects, bool ray_image) {
    using vk::MemoryKind;
    const std::vector<BufferPlan> plan = planBuffers(n, triangles, objects);
    // Refuse what the device cannot hold before allocating anything: a clear
    // OutOfMemory instead of a driver failure half-way (or a validation error for a
    // buffer above maxBufferSize). The heap size is an upper bound: the engine's own
    // allocations live there too, and vkAllocateMemory may still fail (OutOfMemory).
    std::vector<VkDeviceSize> per_heap(device_->memory.memoryHeapCount, 0);
    VkDeviceSize total = 0;
    const VkDeviceSize limit = std::min(device_->max_buffer_size, device_->max_allocation_size);
    for (const BufferPlan& b : plan) {
        if (b.size > limit)
            return Error(ErrorCode::OutOfMemory, "resolution " + std::to_string(n) + " with " + std::to_string(triangles) +
                                                     " triangles needs a '" + b.name + "' buffer of " + gibText(b.size) +
                                                     ", more than the device's largest buffer (" + gibText(limit) +
                                                     "): lower the resolution or split the scene");
        const VkMemoryPropertyFlags required = b.kind == MemoryKind::DeviceLocal ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                                                                 : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
        if (auto type = device_->findMemoryType(~0u, required)) per_heap[device_->memory.memoryTypes[*type].heapIndex] += b.size;
        total += b.size;
    }
    for (std::uint32_t h = 0; h < per_heap.size(); ++h)
        if (per_heap[h] > device_->memory.memoryHeaps[h].size)
            return Error(ErrorCode::OutOfMemory, "resolution " + std::to_string(n) + " with " + std::to_string(triangles) +
                                                     " triangles needs " + gibText(total) + " of device memory, more than the " +
                                                     gibText(device_->memory.memoryHeaps[h].size) +
                                                     " memory heap holds: lower the resolution or split the scene");
    auto make = [&](vk::Buffer& b, const BufferPlan& p) -> Result<void> {
        if (b.valid() && b.size() >= p.size) return {};
        b.reset();  // free the smaller one first: peak memory is the new size, not both
        auto r = vk::Buffer::create(*device_, p.size, 0, p.kind, p.name);
        if (!r) return r.error();
        b = std::move(*r);
        return {};
    };
    vk::Buffer* targets[] = {&buf_.frame, &buf_.objects_buf, &buf_.projection, &buf_.header, &buf_.header_rb, &buf_.counts,
                             &buf_.front, &buf_.back, &buf_.state, &buf_.bundles, &buf_.sparse, &buf_.records, &buf_.scratch};
    static_assert(std::size(targets) == 13);
    for (std::size_t i = 0; i < plan.size(); ++i)
        if (auto r = make(*targets[i], plan[i]); !r) return r.error();
    if (ray_image) {
        if (auto r = make(buf_.ray_image, {"ray-image", VkDeviceSize(n) * n * 4, MemoryKind::Readback}); !r) return r.error();
    }
    return {};
}

void BroadPhase::addHeaderReadback(graph::Graph& g, graph::ResourceId header, graph::ResourceId header_rb) const {
    g.addPass("readback-header", PassKind::Transfer).use(header, Use::TransferSrc).use(header_rb, Use::TransferDst).record([this](PassContext& pc) {
        VkBufferCopy copy{0, 0, sizeof(gpu::Header)};
        pc.fns().vkCmdCopyBuffer(pc.cmd, buf_.header.handle(), buf_.header_rb.handle(), 1, &copy);
    });
}

Result<void> BroadPhase::prepare(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
    const std::uint32_t n = s.resolution;
    if (n < gpu::kMinResolution || n > gpu::kMaxResolution || (n & (n - 1)) != 0)
        return Error(ErrorCode::InvalidArgument, "resolution " + std::to_string(n) + " is not a power of two in [" +
                                                     std::to_string(gpu::kMinResolution) + ", " + std::to_string(gpu::kMaxResolution) + "]");
    const float dl = s.direction[0] * s.direction[0] + s.direction[1] * s.direction[1] + s.direction[2] * s.direction[2];
    if (!(dl > 0) || !std::isfinite(dl)) return Error(ErrorCode::InvalidArgument, "projection direction must be finite and non-zero");
    if (meshes.empty()) return Error(ErrorCode::InvalidArgument, "no objects to test (zero meshes)");
    if (!(s.open_epsilon >= 0) || !std::isfinite(s.open_epsilon)) return Error(ErrorCode::InvalidArgument, "open_epsilon must be finite and >= 0");
    if (!(s.closed_epsilon >= 0) || !std::isfinite(s.closed_epsilon))
        return Error(ErrorCode::InvalidArgument, "closed_epsilon must be finite and >= 0");
    if (s.coverage == Coverage::Best) return Error(ErrorCode::InvalidArgument, "coverage Best is a setting: resolve it first");
    if (s.coverage == Coverage::Conservative && !device_->conservative_rasterization)
        return Error(ErrorCode::UnsupportedFeature, "conservative coverage needs VK_EXT_conservative_rasterization, which " +
                                                        device_->info.name + " lacks (or the adopted device did not enable): use dilation");
    if (s.region) {
        const auto& r = *s.region;
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(r[a]) || !std::isfinite(r[a + 3]) || !(r[a] <= r[a + 3]))
                return Error(ErrorCode::InvalidArgument, "sampling region must be finite with min <= max on every axis");
    }

    std::uint64_t total = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const GpuMesh& m = meshes[i];
        const std::string who = "object " + std::to_string(i) + ": ";
        if (m.triangle_count == 0) return Error(ErrorCode::InvalidMesh, who + "has no triangles (empty mesh)");
        if (m.vertex_count == 0) return Error(ErrorCode::InvalidMesh, who + "has no vertices");
        if (!m.vertices || !m.indices) return Error(ErrorCode::InvalidArgument, who + "vertex or index address is null");
        if (m.vertex_stride < 12 || m.vertex_stride % 4 != 0 || m.vertices % 4 != 0 || m.indices % 4 != 0)
            return Error(ErrorCode::InvalidArgument, who + "positions and indices must be 4-byte aligned, with a vertex stride of at least 12 bytes");
        for (float t : m.transform)
            if (!std::isfinite(t)) return Error(ErrorCode::InvalidArgument, who + "transform is not finite");
        total += m.triangle_count;
    }
    if (total >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidArgument, "scene has more than 2^30 triangles");
    const auto triangles = static_cast<std::uint32_t>(total);
    const auto objects = static_cast<std::uint32_t>(meshes.size());
    if (auto ok = ensureBuffers(n, triangles, objects, s.keep_ray_image); !ok) return ok.error();
    BackendChoice backend = chooseSamplingBackend(device_->properties, computeSamplingSupported(*device_), s.backend, n, triangles,
                                                  triangles == last_triangles_ ? last_fragments_per_triangle_ : -1.0);
    if (s.coverage != Coverage::Centre && backend.backend == SamplingBackend::Compute) {
        // Thin-triangle coverage is drawn by sample.vert (or a conservative pipeline): raster only.
        if (s.backend == SamplingBackend::Compute)
            return Error(ErrorCode::UnsupportedFeature, "thin-triangle coverage (dilate or conservative) needs the raster sampling backend");
        backend = {SamplingBackend::Raster, "thin-triangle coverage needs raster (Auto would take compute: " + backend.reason + ")"};
    }
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

    // Objects and the frame description.
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
        o.flags = (m.open ? gpu::kObjectOpen : 0u) | (m.index16 ? gpu::kObjectIndex16 : 0u) |
                  (m.check_on_gpu ? gpu::kObjectCheckOnGpu : 0u);
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
    const ProjectionBasis basis = projectionBasis(s.direction);
    for (int k = 0; k < 3; ++k)
        fr.direction_basis[k] = basis.u[k], fr.direction_basis[3 + k] = basis.v[k], fr.direction_basis[6 + k] = basis.d[k];
    fr.open_epsilon_world = s.open_epsilon;
    fr.fit_margin = s.fit_margin;
    fr.closed_epsilon_world = s.closed_epsilon;
    fr.compute_sampling = compute_frame;
    VkDeviceSize offset = 0;
    for (std::uint32_t l = 0; l < levels; ++l) {
        fr.level_offset[l] = static_cast<std::uint32_t>(offset);
        offset += VkDeviceSize(n >> l) * (n >> l);
    }
    if (s.region) {
        // The caller's box: the same mapping the fit shader computes, done here.
        const gpu::Projection pr = regionProjection(basis, *s.region, s.open_epsilon, s.closed_epsilon);
        std::memcpy(buf_.projection.mapped(), &pr, sizeof(pr));
        buf_.projection.flush();
    }
    std::memcpy(buf_.frame.mapped(), &fr, sizeof(fr));
    buf_.frame.flush();

    frame_ = Prepared{};
    frame_.frame = fr;
    frame_.settings = s;
    frame_.meshes.assign(meshes.begin(), meshes.end());
    frame_.any_gpu_check = std::any_of(meshes.begin(), meshes.end(), [](const GpuMesh& m) { return m.check_on_gpu; });
    frame_.backend = backend;
    return {};
}

BroadPhase::Resources BroadPhase::importResources(graph::Graph& g, bool full) {
    Resources r;
    r.header = g.importBuffer("header", buf_.header);
    r.header_rb = g.importBuffer("header-readback", buf_.header_rb, true);
    r.counts = g.importBuffer("counts", buf_.counts);
    r.projection = g.importBuffer("projection", buf_.projection);
    r.front = g.importBuffer("front-keys", buf_.front);  // the compute backend's depth complexity uses them
    r.back = g.importBuffer("back-keys", buf_.back);
    if (computeBackend()) r.compute = compute_->import(g);
    if (!full) return r;
    r.state = g.importBuffer("ray-state", buf_.state);
    r.bundles = g.importBuffer("bundles", buf_.bundles);
    r.sparse = g.importBuffer("sparse", buf_.sparse);
    r.records = g.importBuffer("records", buf_.records, true);
    r.scratch = g.importBuffer("pack-scratch", buf_.scratch);
    if (frame_.settings.keep_ray_image) r.rays = g.importBuffer("ray-image", buf_.ray_image, true);
    return r;
}

// One object's triangles in a sampling pass, with the run's coverage. The count pass
// draws thin triangles enlarged (dilation) or through the overestimating pipeline (a
// second draw), so they flag every ray they touch; those rays are done before peeling,
// so the peeling passes draw only the other triangles, exactly as the count pass did.
void BroadPhase::drawObject(const PassContext& pc, const vk::Pipeline& plain, const vk::Pipeline& conservative,
                            VkDeviceAddress frame_addr, std::uint32_t object, std::uint32_t step, bool count_pass) const {
    const std::uint32_t vertices = frame_.meshes[object].triangle_count * 3;
    if (!count_pass && frame_.settings.coverage != Coverage::Centre) {
        bindAndPush(pc, plain, frame_addr, object, step, 0, gpu::kCoverageSkipThin);
        pc.fns().vkCmdDraw(pc.cmd, vertices, 1, 0, 0);
        return;
    }
    switch (frame_.settings.coverage) {
        case Coverage::Centre:
            bindAndPush(pc, plain, frame_addr, object, step);
            pc.fns().vkCmdDraw(pc.cmd, vertices, 1, 0, 0);
            break;
        case Coverage::Dilate:
            bindAndPush(pc, plain, frame_addr, object, step, 0, gpu::kCoverageDilate);
            pc.fns().vkCmdDraw(pc.cmd, vertices, 1, 0, 0);
            break;
        case Coverage::Conservative:
        case Coverage::Best:  // resolved by the API before a run; never here
            bindAndPush(pc, plain, frame_addr, object, step, 0, gpu::kCoverageSkipThin);
            pc.fns().vkCmdDraw(pc.cmd, vertices, 1, 0, 0);
            bindAndPush(pc, conservative, frame_addr, object, step, 0, gpu::kCoverageOnlyThin);
            pc.fns().vkCmdDraw(pc.cmd, vertices, 1, 0, 0);
            break;
    }
}

// Clear, input checks, fit and depth complexity.
void BroadPhase::recordMeasure(graph::Graph& g, const Resources& r) const {
    const std::uint32_t pixels = frame_.frame.resolution * frame_.frame.resolution;
    const VkDeviceAddress frame_addr = buf_.frame.address();
    const auto& meshes = frame_.meshes;
    const auto& P = pipes_;
    g.addPass("clear", PassKind::Transfer).use(r.header, Use::TransferDst).use(r.counts, Use::TransferDst).record([this, pixels](PassContext& pc) {
        // Writes the engine submitted earlier (vertex buffers it skinned or simulated)
        // become visible to everything this detection does.
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &mb;
        pc.fns().vkCmdPipelineBarrier2(pc.cmd, &dep);
        // Disjoint ranges: counters 0, bound minima +inf (ordered), maxima and checks 0.
        constexpr VkDeviceSize mins = offsetof(gpu::Header, bounds), maxs = mins + 12;
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), 0, mins, 0);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), mins, 12, 0xFFFFFFFFu);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.header.handle(), maxs, sizeof(gpu::Header) - maxs, 0);
        pc.fns().vkCmdFillBuffer(pc.cmd, buf_.counts.handle(), 0, VkDeviceSize(pixels) * 4, 0);
    });
    if (frame_.any_gpu_check) {
        g.addPass("validate", PassKind::Compute).readWrite(r.header).record([&, frame_addr](PassContext& pc) {
            for (std::uint32_t i = 0; i < meshes.size(); ++i) {
                if (!meshes[i].check_on_gpu) continue;
                bindAndPush(pc, P.validate, frame_addr, i);
                pc.fns().vkCmdDispatch(pc.cmd, groups(meshes[i].triangle_count), 1, 1);
            }
        });
    }
    if (!frame_.settings.region) {
        g.addPass("bounds", PassKind::Compute).readWrite(r.header).record([&, frame_addr](PassContext& pc) {
            for (std::uint32_t i = 0; i < meshes.size(); ++i) {
                bindAndPush(pc, P.bounds, frame_addr, i);
                pc.fns().vkCmdDispatch(pc.cmd, std::max(groups(meshes[i].vertex_count), 1u), 1, 1);
            }
        });
        g.addPass("fit", PassKind::Compute).read(r.header).write(r.projection).record([&, frame_addr](PassContext& pc) {
            bindAndPush(pc, P.fit, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
    }
    const std::uint32_t n = frame_.frame.resolution;
    if (computeBackend()) {
        compute_->addDepthComplexity(g, r.compute, {r.projection, r.header, r.counts, {}, r.front, r.back}, meshes, frame_addr);
    } else {
        g.addPass("depth-complexity", PassKind::Raster).renderArea(n, n).read(r.projection).readWrite(r.counts).record([&, frame_addr](PassContext& pc) {
            for (std::uint32_t i = 0; i < meshes.size(); ++i) drawObject(pc, P.count, P.count_conservative, frame_addr, i, 0, true);
        });
    }
    g.addPass("reduce-max", PassKind::Compute).read(r.counts).readWrite(r.header).record([&, frame_addr, pixels](PassContext& pc) {
        bindAndPush(pc, P.reduce_max, frame_addr);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
}

// Peeling steps, classification, merging, separation and packing.
void BroadPhase::recordPeelToPack(graph::Graph& g, const Resources& r, std::uint32_t steps) const {
    const gpu::Frame& fr = frame_.frame;
    const bool dual = fr.dual != 0, keep_rays = frame_.settings.keep_ray_image;
    const std::uint32_t n = fr.resolution, pixels = n * n, levels = fr.levels;
    const VkDeviceAddress frame_addr = buf_.frame.address();
    const auto& meshes = frame_.meshes;
    const auto& P = pipes_;

    const bool compute = computeBackend();
    const std::uint32_t fused = compute && compute_->fusesFirstStep() ? 1u : 0u;
    g.addPass("peel-init", PassKind::Compute).read(r.counts).write(r.state).write(r.front).write(r.back).record([&, frame_addr, pixels, fused](PassContext& pc) {
        bindAndPush(pc, P.peel_init, frame_addr, 0, fused);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
    for (std::uint32_t step = 0; step < steps; ++step) {
        if (compute) {
            compute_->addPeelStep(g, r.compute, {r.projection, r.header, r.counts, r.state, r.front, r.back}, step, dual, frame_addr);
        } else {
            auto peel = g.addPass("peel[" + std::to_string(step) + "]", PassKind::Raster);
            peel.renderArea(n, n).read(r.projection).read(r.state).readWrite(r.front);
            if (dual) peel.readWrite(r.back);
            peel.record([&, step, frame_addr](PassContext& pc) {
                for (std::uint32_t i = 0; i < meshes.size(); ++i) drawObject(pc, P.peel, P.peel, frame_addr, i, step, false);  // no conservative draw when peeling
            });
        }
        auto classify = g.addPass("classify[" + std::to_string(step) + "]", PassKind::Compute);
        classify.read(r.counts).read(r.projection).readWrite(r.state).readWrite(r.front);
        if (dual) classify.readWrite(r.back);
        classify.record([&, step, frame_addr, pixels](PassContext& pc) {
            bindAndPush(pc, P.classify, frame_addr, 0, step);
            pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
        });
    }
    auto finalize = g.addPass("finalize", PassKind::Compute);
    finalize.read(r.state).use(r.bundles, Use::StorageWrite).readWrite(r.header);
    if (keep_rays) finalize.write(r.rays);
    finalize.record([&, frame_addr, pixels](PassContext& pc) {
        bindAndPush(pc, P.finalize, frame_addr);
        pc.fns().vkCmdDispatch(pc.cmd, groups(pixels), 1, 1);
    });
    g.addPass("merge", PassKind::Compute).readWrite(r.bundles).record([&, frame_addr, n, levels](PassContext& pc) {
        for (std::uint32_t l = 1; l < levels; ++l) {
            bindAndPush(pc, P.merge, frame_addr, 0, 0, l);
            pc.fns().vkCmdDispatch(pc.cmd, groups(VkDeviceSize(n >> l) * (n >> l)), 1, 1);
            if (l + 1 < levels) pc.shaderBarrier();  // level l+1 reads level l
        }
    });
    g.addPass("separate", PassKind::Compute).read(r.projection).read(r.bundles).write(r.sparse).record([&, frame_addr](PassContext& pc) {
        for (std::uint32_t i = 0; i < meshes.size(); ++i) {
            bindAndPush(pc, P.separate, frame_addr, i);
            pc.fns().vkCmdDispatch(pc.cmd, groups(meshes[i].triangle_count), 1, 1);
        }
    });
    const std::uint32_t rows = fr.pack_rows, blocks = fr.pack_blocks;
    if (frame_.settings.packing == PackingMethod::Paper) {
        g.addPass("pack-count", PassKind::Compute).read(r.sparse).write(r.scratch).record([&, frame_addr, rows](PassContext& pc) {
            bindAndPush(pc, P.pack_rowcount, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, rows, 1, 1);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan_counts, frame_addr, 0, rows);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
        g.addPass("pack-shift", PassKind::Compute).read(r.sparse).readWrite(r.scratch).readWrite(r.header).record([&, frame_addr, rows](PassContext& pc) {
            bindAndPush(pc, P.pack_shift, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, groups(rows, 64), 1, 1);
        });
        g.addPass("pack-move", PassKind::Compute).read(r.sparse).read(r.scratch).read(r.projection).write(r.records).record([&, frame_addr, rows](PassContext& pc) {
            bindAndPush(pc, P.pack_move, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, rows, 1, 1);
        });
    } else {
        g.addPass("pack-scan", PassKind::Compute).read(r.sparse).write(r.scratch).readWrite(r.header).record([&, frame_addr, blocks](PassContext& pc) {
            bindAndPush(pc, P.scan_blocksum, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, blocks, 1, 1);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan_counts, frame_addr, 0, blocks);
            pc.fns().vkCmdDispatch(pc.cmd, 1, 1, 1);
        });
        g.addPass("pack-scatter", PassKind::Compute).read(r.sparse).read(r.scratch).read(r.projection).write(r.records).record([&, frame_addr, blocks](PassContext& pc) {
            bindAndPush(pc, P.scan_scatter, frame_addr);
            pc.fns().vkCmdDispatch(pc.cmd, blocks, 1, 1);
        });
    }
}

std::uint64_t BroadPhase::memoryBytes() const noexcept {
    std::uint64_t n = 0;
    for (const vk::Buffer* b : {&buf_.frame, &buf_.objects_buf, &buf_.projection, &buf_.header, &buf_.header_rb, &buf_.counts,
                                &buf_.front, &buf_.back, &buf_.state, &buf_.bundles, &buf_.sparse, &buf_.records, &buf_.scratch,
                                &buf_.ray_image})
        n += b->valid() ? b->size() : 0;
    return n;
}

gpu::Header BroadPhase::readHeader() {
    buf_.header_rb.invalidate();
    gpu::Header h;
    std::memcpy(&h, buf_.header_rb.mapped(), sizeof(h));
    return h;
}

// The GPU input checks' verdict, naming the object (its index in the run) and triangle.
Result<void> BroadPhase::checkInputs(const gpu::Header& h) {
    bad_objects_.clear();
    if (h.bad_index_count)
        bad_objects_.push_back({h.bad_index_object,
                                Error(ErrorCode::InvalidMesh, "object " + std::to_string(h.bad_index_object) + ": triangle " +
                                                                  std::to_string(h.bad_index_triangle) + " has an index >= the vertex count " +
                                                                  std::to_string(frame_.meshes.at(h.bad_index_object).vertex_count) + " (" +
                                                                  std::to_string(h.bad_index_count) + " triangles affected)")});
    if (h.bad_vertex_count && !(h.bad_index_count && h.bad_vertex_object == h.bad_index_object))
        bad_objects_.push_back({h.bad_vertex_object,
                                Error(ErrorCode::InvalidMesh, "object " + std::to_string(h.bad_vertex_object) + ": triangle " +
                                                                  std::to_string(h.bad_vertex_triangle) + " has a NaN or infinite vertex position (" +
                                                                  std::to_string(h.bad_vertex_count) + " triangles affected)")});
    if (!bad_objects_.empty()) return bad_objects_.front().error;
    return {};
}

// The projection the run used: the caller's region, or fit.comp's computation repeated on
// the host from the bounds it read.
gpu::Projection BroadPhase::hostProjection(const gpu::Header& h) const {
    const BroadPhaseSettings& s = frame_.settings;
    const ProjectionBasis basis = projectionBasis(s.direction);
    if (s.region) return regionProjection(basis, *s.region, s.open_epsilon, s.closed_epsilon);
    return fitProjection(basis, boundsFromHeader(h), s.fit_margin, s.open_epsilon, s.closed_epsilon);
}

void BroadPhase::addTimings(BroadPhaseResult& result, const graph::ExecutionReport& report) {
    for (const auto& p : report.passes) {
        const std::string& name = p.name;
        if (name == "depth-complexity" || name.rfind("peel", 0) == 0 || name.rfind("classify", 0) == 0 || name == "finalize" ||
            name == "clear" || name == "validate" || name == "bounds" || name == "fit" || name == "reduce-max" || name.rfind("csample", 0) == 0)
            result.sampling_ms += p.gpu_ms;
        else if (name == "merge") result.merging_ms += p.gpu_ms;
        else if (name == "separate") result.separation_ms += p.gpu_ms;
        else if (name.rfind("pack", 0) == 0) result.packing_ms += p.gpu_ms;
        result.passes.push_back(p);
    }
}

Result<BroadPhaseResult> BroadPhase::run(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "a broad phase is in flight: collect() it first");
    if (auto ok = prepare(meshes, s); !ok) return ok.error();

    // Submission 1: fit and depth complexity; the host reads how many layers to peel.
    graph::Graph g1;
    const Resources r1 = importResources(g1, false);
    recordMeasure(g1, r1);
    addHeaderReadback(g1, r1.header, r1.header_rb);
    auto report1 = executor_.run(g1);
    if (!report1) return report1.error();
    const gpu::Header h1 = readHeader();
    if (auto ok = checkInputs(h1); !ok) return ok.error();
    // The compute backend sizes its per-ray fragment lists for the measured depth.
    if (computeBackend())
        if (auto ok = compute_->preparePeeling(h1.depth_complexity); !ok) return ok.error();
    frame_.first = BroadPhaseResult{};
    addTimings(frame_.first, *report1);
    frame_.measured_layers = s.layer_cap ? std::min(h1.depth_complexity, s.layer_cap) : h1.depth_complexity;

    // Submission 2: peel, merge, separate, pack.
    graph::Graph g;
    const Resources r = importResources(g, true);
    frame_.steps = s.dual ? (frame_.measured_layers + 1) / 2 : frame_.measured_layers;
    recordPeelToPack(g, r, frame_.steps);
    addHeaderReadback(g, r.header, r.header_rb);
    if (auto ok = executor_.submit(g); !ok) return ok.error();
    pending_ = true;
    return collect();
}

Result<void> BroadPhase::submit(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s, std::uint32_t layers) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "a broad phase is in flight: collect() it first");
    if (auto ok = prepare(meshes, s); !ok) return ok.error();
    if (s.layer_cap) layers = std::min(layers, s.layer_cap);
    // Unknown depth: the compute backend draws each peeling step (fragment lists could be
    // incomplete if the scene got deeper, and that would not be conservative).
    if (computeBackend())
        if (auto ok = compute_->preparePeeling(0); !ok) return ok.error();
    frame_.first = BroadPhaseResult{};
    frame_.measured_layers = layers;
    frame_.steps = s.dual ? (layers + 1) / 2 : layers;
    graph::Graph g;
    const Resources r = importResources(g, true);
    recordMeasure(g, r);
    recordPeelToPack(g, r, frame_.steps);
    addHeaderReadback(g, r.header, r.header_rb);
    if (auto ok = executor_.submit(g); !ok) return ok.error();
    pending_ = true;
    return {};
}

Result<BroadPhaseResult> BroadPhase::collect() {
    if (!pending_) return Error(ErrorCode::InvalidArgument, "no broad phase in flight: submit() first");
    pending_ = false;
    auto report = executor_.collect();
    if (!report) return report.error();

    // The count first, then exactly that many records.
    const auto t0 = std::chrono::steady_clock::now();
    const gpu::Header h = readHeader();
    if (auto ok = checkInputs(h); !ok) return ok.error();
    BroadPhaseResult result = std::move(frame_.first);
    addTimings(result, *report);
    const gpu::Frame& fr = frame_.frame;
    const std::uint32_t triangles = fr.triangle_count, pixels = fr.resolution * fr.resolution;
    // A single submission measures the depth complexity in the same run; with a
    // separate measuring submission, the second header keeps the first's value.
    result.depth_complexity = h.depth_complexity;
    result.projection = hostProjection(h);
    result.backend = frame_.backend.backend;
    result.backend_reason = frame_.backend.reason;
    result.fragments = h.fragments;
    result.compute_small = h.cs_small, result.compute_big = h.cs_big, result.compute_items = h.cs_items;
    if (computeBackend()) result.compute_fragment_lists = compute_->usesFragmentLists();
    last_triangles_ = fr.triangle_count;
    last_fragments_per_triangle_ = double(h.fragments) / double(std::max(fr.triangle_count, 1u));
    result.layers = frame_.measured_layers;
    result.peel_steps = frame_.steps;
    result.triangles = triangles;
    result.collision_rays = h.collision_rays;
    if (h.record_count > triangles)
        return Error(ErrorCode::VulkanError, "packing reported " + std::to_string(h.record_count) + " records for " +
                                                 std::to_string(triangles) + " triangles");
    result.records.resize(h.record_count);
    if (h.record_count) {
        buf_.records.invalidate(0, VkDeviceSize(h.record_count) * sizeof(CandidateTriangle));
        std::memcpy(result.records.data(), buf_.records.mapped(), size_t(h.record_count) * sizeof(CandidateTriangle));
    }
    if (frame_.settings.keep_ray_image) {
        buf_.ray_image.invalidate();
        result.ray_image.resize(pixels);
        const auto* src = static_cast<const std::uint32_t*>(buf_.ray_image.mapped());
        for (std::uint32_t i = 0; i < pixels; ++i) result.ray_image[i] = static_cast<std::uint8_t>(src[i]);
    }
    result.readback_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace vkcollide::passes
