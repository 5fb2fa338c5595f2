#include "broad/peeling/sampling/object_sampling.hpp"

#include <algorithm>
#include <cassert>
#include <string>

#include "broad/peeling/sampling/backend_choice.hpp"
#include "broad/peeling/sampling/compute_sampler.hpp"
#include "shaders/all.hpp"

namespace vkcollide::passes {

using graph::PassContext;
using graph::PassKind;
using graph::Use;

Result<std::unique_ptr<ObjectSampling>> ObjectSampling::create(vk::Device& device, BufferTable& table) {
    std::unique_ptr<ObjectSampling> os(new ObjectSampling(device, table));
    auto raster = RasterSampler::create(device);
    if (!raster) return raster.error();
    os->raster_ = std::move(*raster);
    for (auto r : {makeCompute(device, os->reduce_max_, shaders::reduce_max_comp, "reduce-max"),
                   makeCompute(device, os->peel_init_, shaders::peel_init_comp, "peel-init"),
                   makeCompute(device, os->classify_, shaders::classify_comp, "classify"),
                   makeCompute(device, os->finalize_, shaders::finalize_comp, "finalize")})
        if (!r) return r.error();
    return os;
}

Result<VkDeviceAddress> ObjectSampling::prepare(const BroadPhaseSettings& s, const RunShape& shape) {
    choice_ = chooseSamplingBackend(device_->properties, computeSamplingSupported(*device_), s.backend, shape.resolution,
                                    shape.triangles, shape.triangles == last_triangles_ ? last_fragments_per_triangle_ : -1.0);
    if (s.coverage != Coverage::Centre && choice_.backend == SamplingBackend::Compute) {
        // Thin-triangle coverage is drawn by sample.vert (or a conservative pipeline): raster
        // only. An explicit Compute with it is refused by the API (validation.cpp).
        assert(s.backend != SamplingBackend::Compute);
        choice_ = {SamplingBackend::Raster, "thin-triangle coverage needs raster (Auto would take compute: " + choice_.reason + ")"};
    }
    // The raster backend renders an N x N area: the device's framebuffer and viewport
    // limits bound N (Vulkan guarantees only 4096). Auto samples larger images in compute.
    const VkPhysicalDeviceLimits& limits = device_->properties.limits;
    const std::uint32_t raster_max = std::min({limits.maxFramebufferWidth, limits.maxFramebufferHeight,
                                               limits.maxViewportDimensions[0], limits.maxViewportDimensions[1]});
    if (choice_.backend == SamplingBackend::Raster && shape.resolution > raster_max) {
        if (s.backend == SamplingBackend::Auto && s.coverage == Coverage::Centre && computeSamplingSupported(*device_))
            choice_ = {SamplingBackend::Compute, "resolution " + std::to_string(shape.resolution) +
                                                     " exceeds this device's largest framebuffer (" + std::to_string(raster_max) + ")"};
        else
            return Error(ErrorCode::UnsupportedFeature, "resolution " + std::to_string(shape.resolution) +
                                                            " exceeds this device's largest framebuffer and viewport (" +
                                                            std::to_string(raster_max) + ") for raster sampling" +
                                                            (s.coverage != Coverage::Centre ? " (thin-triangle coverage needs raster)" : "") +
                                                            ": lower the resolution or sample in compute");
    }
    if (choice_.backend == SamplingBackend::Compute) {
        if (auto ok = makeComputeSampler(SamplingBackend::Compute); !ok) return ok.error();
        active_ = compute_.get();
    } else {
        active_ = raster_.get();
    }
    return active_->prepare(s, shape);
}

Result<void> ObjectSampling::makeComputeSampler(SamplingBackend backend) {
    // Compute on a device without it fails here, by name (ComputeSampler::create).
    if (compute_ || backend == SamplingBackend::Raster || (backend == SamplingBackend::Auto && !computeSamplingSupported(*device_)))
        return {};
    auto created = ComputeSampler::create(*device_, *table_);
    if (!created) return created.error();
    compute_ = std::move(*created);
    return {};
}

void ObjectSampling::import(graph::Graph& g) { active_->import(g); }

void ObjectSampling::recordMeasure(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const {
    active_->recordDepthComplexity(g, run, b);
    const std::uint32_t pixels = run.frame.resolution * run.frame.resolution;
    addPass(g, "reduce-max", PassKind::Compute, Stage::Sampling)
        .read(b.fragments)
        .write(b.counts)
        .readWrite(b.header)
        .record([this, frame = run.frame_address, pixels](PassContext& pc) {
            bindAndPush(pc, reduce_max_, frame);
            dispatchItems(pc, pixels);
        });
}

Result<void> ObjectSampling::preparePeeling(std::uint32_t depth_complexity) { return active_->preparePeeling(depth_complexity); }

void ObjectSampling::recordPeelSteps(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t first,
                                     std::uint32_t end, const DepthAwareIds& depth) const {
    const std::uint32_t pixels = run.frame.resolution * run.frame.resolution;
    const VkDeviceAddress frame = run.frame_address;
    const bool dual = run.frame.dual != 0;
    if (first == 0) {
        const std::uint32_t done = active_->stepsDoneByCount();
        addPass(g, "peel-init", PassKind::Compute, Stage::Sampling)
            .read(b.counts)
            .write(b.state)
            .write(b.front)
            .write(b.back)
            .record([this, frame, pixels, done](PassContext& pc) {
                bindAndPush(pc, peel_init_, frame, 0, done);
                dispatchItems(pc, pixels);
            });
    }
    for (std::uint32_t step = first; step < end; ++step) {
        active_->recordPeelStep(g, run, b, step);
        auto classify = addPass(g, stepPassName(kClassifyPassPrefix, step), PassKind::Compute, Stage::Sampling);
        classify.read(b.counts).read(b.projection).readWrite(b.state).readWrite(b.front);
        if (dual) classify.readWrite(b.back);
        if (depth.bounds.valid()) classify.read(depth.bounds).readWrite(depth.bundle_depth);
        classify.record([this, frame, pixels, step](PassContext& pc) {
            bindAndPush(pc, classify_, frame, 0, step);
            dispatchItems(pc, pixels);
        });
    }
}

void ObjectSampling::recordFinalize(graph::Graph& g, const RunView& run, const SamplingBuffers& b, graph::ResourceId bundles,
                                    graph::ResourceId rays, const DepthAwareIds& depth) const {
    const std::uint32_t pixels = run.frame.resolution * run.frame.resolution;
    const VkDeviceAddress frame = run.frame_address;
    auto finalize = addPass(g, "finalize", PassKind::Compute, Stage::Sampling);
    finalize.read(b.state).use(bundles, Use::StorageWrite).readWrite(b.header);
    if (rays.valid()) finalize.write(rays);
    if (depth.bounds.valid()) finalize.read(b.counts).readWrite(depth.bundle_depth).read(depth.edge_depth);
    if (depth.ray_depth.valid()) finalize.write(depth.ray_depth);
    finalize.record([this, frame, pixels](PassContext& pc) {
        bindAndPush(pc, finalize_, frame);
        dispatchItems(pc, pixels);
    });
}

void ObjectSampling::report(const gpu::Header& h, std::uint32_t triangles, BroadPhaseResult& r) {
    r.backend = choice_.backend;
    r.backend_reason = choice_.reason;
    r.fragments = h.fragments;
    r.compute_small = h.cs_small, r.compute_big = h.cs_big, r.compute_items = h.cs_items;
    active_->report(r);
    last_triangles_ = triangles;
    last_fragments_per_triangle_ = double(h.fragments) / double(std::max(triangles, 1u));
}

}  // namespace vkcollide::passes
