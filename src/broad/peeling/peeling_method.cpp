#include "broad/peeling/peeling_method.hpp"

#include <algorithm>
#include <cstring>

namespace vkcollide::passes {
namespace {

VkDeviceSize pixels(const RunShape& s) { return VkDeviceSize(s.resolution) * s.resolution; }
VkDeviceSize triangles(const RunShape& s) { return std::max<std::uint32_t>(s.triangles, 1); }
// Texels of the ray-bundle mipmap: every level down to 1x1.
VkDeviceSize mipTexels(const RunShape& s) {
    VkDeviceSize texels = 0;
    for (std::uint32_t n = s.resolution; n >= 1; n /= 2) texels += VkDeviceSize(n) * n;
    return texels;
}

}  // namespace

PeelingMethod::Buffers PeelingMethod::addRows(BufferTable& t) {
    using vk::MemoryKind;
    using F = gpu::Frame;
    Buffers b;
    // Sampling counts each ray's fragments in 64 bits (cleared every run); reduce-max packs
    // them into `counts` for the peeling passes (every ray written, so never cleared).
    b.fragments = t.add({"ray-fragments", MemoryKind::DeviceLocal, [](const RunShape& s) { return pixels(s) * 8; },
                         &F::ray_fragments, false, true});
    b.counts = t.add({"counts", MemoryKind::DeviceLocal, [](const RunShape& s) { return pixels(s) * 4; }, &F::counts});
    b.front = t.add({"front-keys", MemoryKind::DeviceLocal, [](const RunShape& s) { return pixels(s) * 8; }, &F::front_keys});
    b.back = t.add({"back-keys", MemoryKind::DeviceLocal, [](const RunShape& s) { return pixels(s) * 8; }, &F::back_keys});
    b.state = t.add({"ray-state", MemoryKind::DeviceLocal, [](const RunShape& s) { return pixels(s) * sizeof(gpu::PixelState); }, &F::state});
    b.bundles = t.add({"bundles", MemoryKind::DeviceLocal, [](const RunShape& s) { return mipTexels(s) * 16; }, &F::bundles});
    b.sparse = t.add({"sparse", MemoryKind::DeviceLocal, [](const RunShape& s) { return triangles(s) * 16; }, &F::sparse});
    b.records = t.add({"records", MemoryKind::Readback,
                       [](const RunShape& s) { return triangles(s) * sizeof(CandidateTriangle); }, &F::records, true});
    b.scratch = t.add({"pack-scratch", MemoryKind::DeviceLocal, [](const RunShape& s) { return Packing::scratchBytes(s.triangles); }, &F::scratch});
    b.ray_image = t.add({"ray-image", MemoryKind::Readback, [](const RunShape& s) { return s.ray_image ? pixels(s) * 4 : 0; },
                         &F::ray_image, true});
    b.tri_bounds =
        t.add({"triangle-bounds", MemoryKind::DeviceLocal,
               [](const RunShape& s) { return s.depth_aware ? triangles(s) * sizeof(gpu::TriangleBounds) : 0; }, &F::tri_bounds});
    b.bundle_depth = t.add({"bundle-depth", MemoryKind::DeviceLocal, [](const RunShape& s) { return s.depth_aware ? mipTexels(s) * 8 : 0; },
                            &F::bundle_depth});
    // Ordered-float (inverted minimum, maximum) per ray, zero = none: cleared every run.
    b.edge_depth = t.add({"edge-depth", MemoryKind::DeviceLocal, [](const RunShape& s) { return s.depth_aware ? pixels(s) * 8 : 0; },
                          &F::edge_depth, false, true});
    b.sparse_depth = t.add({"sparse-depth", MemoryKind::DeviceLocal, [](const RunShape& s) { return s.depth_aware ? triangles(s) * 8 : 0; },
                            &F::sparse_depth});
    b.ray_depth_image =
        t.add({"ray-depth-image", MemoryKind::Readback, [](const RunShape& s) { return s.depth_aware && s.ray_image ? pixels(s) * 8 : 0; },
               &F::ray_depth_image, true});
    return b;
}

Result<std::unique_ptr<BroadPhaseMethod>> PeelingMethod::create(vk::Device& device, BufferTable& table, const CoreBuffers& core) {
    std::unique_ptr<PeelingMethod> m(new PeelingMethod(table, core));
    m->device_ = &device;
    m->buf_ = addRows(table);
    auto bounds = TriangleBounds::create(device);
    if (!bounds) return bounds.error();
    m->bounds_ = std::move(*bounds);
    auto sampling = ObjectSampling::create(device, table);
    if (!sampling) return sampling.error();
    m->sampling_ = std::move(*sampling);
    auto merging = Merging::create(device);
    if (!merging) return merging.error();
    m->merging_ = std::move(*merging);
    auto separation = Separation::create(device);
    if (!separation) return separation.error();
    m->separation_ = std::move(*separation);
    auto packing = Packing::create(device);
    if (!packing) return packing.error();
    m->packing_ = std::move(*packing);
    return std::unique_ptr<BroadPhaseMethod>(std::move(m));
}

Result<void> PeelingMethod::prepare(const BroadPhaseSettings& s, const RunShape& shape, gpu::Frame& fr) {
    auto compute_frame = sampling_->prepare(s, shape);
    if (!compute_frame) return compute_frame.error();
    const std::uint32_t n = shape.resolution, tris = std::max(shape.triangles, 1u);
    fr.compute_sampling = *compute_frame;
    fr.dual = s.dual ? 1u : 0u;
    fr.depth_aware = s.depth_aware ? 1u : 0u;
    fr.pack_rows = (tris + gpu::kPackRowWidth - 1) / gpu::kPackRowWidth;
    fr.pack_blocks = (tris + gpu::kGroupSize - 1) / gpu::kGroupSize;
    std::uint32_t levels = 0;
    for (std::uint32_t x = n; x >= 1; x /= 2) ++levels;
    fr.levels = levels;
    VkDeviceSize offset = 0;
    for (std::uint32_t l = 0; l < levels; ++l) {
        fr.level_offset[l] = static_cast<std::uint32_t>(offset);
        offset += VkDeviceSize(n >> l) * (n >> l);
    }
    return {};
}

SamplingBuffers PeelingMethod::samplingBuffers(const GraphBuffers& b) const {
    return {b[core_.projection], b[core_.header], b[buf_.counts], b[buf_.state], b[buf_.front], b[buf_.back], b[buf_.fragments]};
}

void PeelingMethod::record(Phase phase, graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const {
    switch (phase) {
        case Phase::Measure: sampling_->recordMeasure(g, run, samplingBuffers(buffers)); return;
        case Phase::Main:
        case Phase::Again: recordChunk(g, run, buffers); return;
    }
}

void PeelingMethod::setLayers(const RunView& run, std::uint32_t layers) {
    // Rays deeper than kMaxRayFragments are collision rays without peeling (reduce-max), so
    // no ray needs more steps than that, whatever the depth complexity.
    layers = std::min(layers, gpu::kMaxRayFragments);
    layers_ = run.settings.layer_cap ? std::min(layers, run.settings.layer_cap) : layers;
    steps_ = run.settings.dual ? (layers_ + 1) / 2 : layers_;
}

Result<void> PeelingMethod::begin(const RunView& run, const gpu::Header* measured, std::span<const graph::PassTiming> measured_passes,
                                  std::uint32_t predicted_layers) {
    // Measured: the compute backend sizes its per-ray fragment lists for that depth.
    // Predicted: the depth is unknown, so the compute backend draws each peeling step
    // (fragment lists could be incomplete if the scene got deeper, and that would not be
    // conservative).
    const std::uint32_t layers = measured ? measured->depth_complexity : predicted_layers;
    if (auto ok = sampling_->preparePeeling(measured ? layers : 0); !ok) return ok.error();
    setLayers(run, layers);
    chunk_ = chunkSteps(run, measured_passes);
    chunk_first_ = 0;
    chunk_end_ = std::min(steps_, chunk_);
    return {};
}

double PeelingMethod::countPassMs(std::span<const graph::PassTiming> passes) {
    double ms = 0;
    for (const graph::PassTiming& p : passes)
        if (p.name == kDepthComplexityPass) ms += p.gpu_ms;
    return ms;
}

std::uint32_t PeelingMethod::chunkSteps(const RunView& run, std::span<const graph::PassTiming> measured_passes) const {
    if (run.settings.peel_chunk) return run.settings.peel_chunk;
    // A peeling step draws the scene once, as the depth-complexity pass did, and classifies
    // every ray: this run's count pass scaled by the last run's ratio (before any, 1.5),
    // else the last run's step, else a guess by device type (a CPU implementation such as
    // lavapipe takes about a microsecond per triangle and 0.1 us per ray; a GPU takes
    // microseconds for a whole step).
    const int b = backendIndex();
    double step_ms = 0;
    if (const double count_ms = countPassMs(measured_passes); count_ms > 0)
        step_ms = count_ms * (step_per_count_[b] > 0 ? step_per_count_[b] : 1.5);
    else if (step_ms_[b] > 0)
        step_ms = step_ms_[b];
    else if (device_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        step_ms = 1e-3 * run.frame.triangle_count + 1e-4 * double(run.frame.resolution) * run.frame.resolution;
    if (step_ms <= 0) return std::max(steps_, 1u);
    return static_cast<std::uint32_t>(std::clamp(kPeelChunkTargetMs / step_ms, 1.0, double(std::max(steps_, 1u))));
}

void PeelingMethod::noteStepTime(std::span<const graph::PassTiming> passes) {
    double steps_ms = 0;
    for (const graph::PassTiming& p : passes)
        if (p.name.starts_with(kPeelPassPrefix) || p.name.starts_with(kClassifyPassPrefix)) steps_ms += p.gpu_ms;
    if (steps_ == 0 || steps_ms <= 0) return;  // nothing peeled, or no timestamps
    const int b = backendIndex();
    step_ms_[b] = steps_ms / steps_;
    if (const double count_ms = countPassMs(passes); count_ms > 0) step_per_count_[b] = step_ms_[b] / count_ms;
}

void PeelingMethod::recordChunk(graph::Graph& g, const RunView& run, const GraphBuffers& b) const {
    // Invalid ids (rows of size 0) when depth-aware separation is off.
    const DepthAwareIds depth{b[buf_.tri_bounds], b[buf_.bundle_depth], b[buf_.ray_depth_image], b[buf_.edge_depth]};
    if (chunk_first_ == 0 && depth.bounds.valid()) bounds_->record(g, run, b[core_.projection], depth.bounds, depth.edge_depth);
    sampling_->recordPeelSteps(g, run, samplingBuffers(b), chunk_first_, chunk_end_, depth);
    if (chunk_end_ < steps_) return;  // collect() asks for the next chunk
    sampling_->recordFinalize(g, run, samplingBuffers(b), b[buf_.bundles], b[buf_.ray_image], depth);
    merging_->record(g, run, b[buf_.bundles], depth.bundle_depth);
    separation_->record(g, run, b[core_.projection], b[buf_.bundles], b[buf_.sparse],
                        {depth.bounds, depth.bundle_depth, b[buf_.sparse_depth]});
    packing_->record(g, run,
                     {b[buf_.sparse], b[buf_.scratch], b[core_.header], b[core_.projection], b[buf_.records], b[buf_.sparse_depth]});
}

Result<Collected> PeelingMethod::collect(const RunView& run, const gpu::Header& h, BroadPhaseResult& result) {
    if (chunk_end_ < steps_) {
        chunk_first_ = chunk_end_;
        chunk_end_ = std::min(steps_, chunk_end_ + chunk_);
        return Collected::Again;
    }
    const std::uint32_t triangles = run.frame.triangle_count, pixels = run.frame.resolution * run.frame.resolution;
    // A pass's loops ended early: only where the device ends long loops without an error.
    if (h.loop_limit & gpu::kLoopLimitSplat)
        return Error(ErrorCode::LimitExceeded,
                     "depth-aware separation: edge-on triangles at resolution " + std::to_string(run.frame.resolution) +
                         " reach more rays than " + vk::loopLimitPhrase(*device_, "marks") +
                         ": lower the resolution, set DetectSettings::peeling.depth_aware false, or detect on a GPU");
    if (h.loop_limit & gpu::kLoopLimitDraw)
        return Error(ErrorCode::LimitExceeded,
                     "compute sampling: the big triangles' tiles at resolution " + std::to_string(run.frame.resolution) +
                         " take more per work item than " + vk::loopLimitPhrase(*device_, "draws") +
                         ": lower the resolution, or detect on a GPU");
    sampling_->report(h, triangles, result);
    result.layers = layers_;
    result.peel_steps = steps_;
    result.peel_submissions = (std::max(steps_, 1u) + chunk_ - 1) / chunk_;
    noteStepTime(result.passes);
    result.collision_rays = h.collision_rays;
    result.deep_rays = h.deep_rays;
    if (h.record_count > triangles)
        return Error(ErrorCode::VulkanError, "packing reported " + std::to_string(h.record_count) + " records for " +
                                                 std::to_string(triangles) + " triangles");
    // The count first, then exactly that many records.
    const vk::Buffer& records = table_->buffer(buf_.records);
    result.records.resize(h.record_count);
    if (h.record_count) {
        records.invalidate(0, VkDeviceSize(h.record_count) * sizeof(CandidateTriangle));
        std::memcpy(result.records.data(), records.mapped(), size_t(h.record_count) * sizeof(CandidateTriangle));
    }
    if (run.settings.keep_ray_image) {
        const vk::Buffer& rays = table_->buffer(buf_.ray_image);
        rays.invalidate();
        result.ray_image.resize(pixels);
        const auto* src = static_cast<const std::uint32_t*>(rays.mapped());
        for (std::uint32_t i = 0; i < pixels; ++i) result.ray_image[i] = static_cast<std::uint8_t>(src[i]);
        if (run.settings.depth_aware) {
            const vk::Buffer& depths = table_->buffer(buf_.ray_depth_image);
            depths.invalidate();
            result.ray_depth.resize(pixels);
            std::memcpy(result.ray_depth.data(), depths.mapped(), size_t(pixels) * sizeof(result.ray_depth[0]));
        }
    }
    return Collected::Done;
}

}  // namespace vkcollide::passes
