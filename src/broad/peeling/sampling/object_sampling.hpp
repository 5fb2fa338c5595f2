// Paper pass 1, object sampling, as one stage: the depth complexity (counts per ray and
// their maximum) in the measuring part, then the peeling steps with classification and the
// finalize pass that turns per-ray states into level 0 of the ray-bundle mipmap.
//
// The backend-specific parts (depth-complexity counts, peeling keys) come from the active
// Sampler (raster_sampler.hpp, compute_sampler.hpp); which one runs is chosen per run
// (backend_choice.hpp). The passes around them (reduce-max, peel-init, classify[i],
// finalize) are shared.
#pragma once

#include <cstdint>
#include <memory>

#include "broad/peeling/sampling/backend_choice.hpp"
#include "broad/peeling/sampling/compute_sampler.hpp"
#include "broad/peeling/sampling/raster_sampler.hpp"
#include "broad/peeling/sampling/sampler.hpp"

namespace vkcollide::passes {

// Depth-aware separation's buffers that classify and finalize use (invalid ids when off):
// the triangle bounds, the bundles' depth intervals (level 0 holds each ray's while it is
// peeled), the per-ray interval image (only with keep_ray_image) and the edge-on
// triangles' depths per ray.
struct DepthAwareIds {
    graph::ResourceId bounds, bundle_depth, ray_depth, edge_depth;
};

class ObjectSampling {
public:
    // The compute backend's rows go into `io_table` when it is first used.
    static Result<std::unique_ptr<ObjectSampling>> create(vk::Device& device, BufferTable& io_table);

    // Chooses the backend for the run (Auto: backend_choice.hpp) and prepares it. Returns
    // the address for gpu::Frame::compute_sampling (0 for raster). Precondition: no
    // thin-triangle coverage with an explicit Compute backend (Auto then picks raster).
    [[nodiscard]] Result<VkDeviceAddress> prepare(const BroadPhaseSettings& settings, const RunShape& shape);
    // Creates the compute sampler now where a run with `backend` may sample in compute on
    // this device (Auto where it can, Compute), instead of at the first run that does.
    [[nodiscard]] Result<void> makeComputeSampler(SamplingBackend backend);
    // The active backend's own buffers into a graph about to be recorded.
    void import(graph::Graph& g);
    // Measuring part: depth-complexity counts, then "reduce-max" (header's depth complexity
    // and fragment sum, thin rays flagged).
    void recordMeasure(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const;
    // Before the peeling steps: the measured depth complexity, or 0 when predicted.
    [[nodiscard]] Result<void> preparePeeling(std::uint32_t depth_complexity);
    // Peeling steps [first, end): "peel[i]" and "classify[i]" each, after "peel-init" when
    // `first` is 0. A run's steps may be recorded in several graphs (submissions) in
    // order: the per-ray state stays in the table's buffers between them.
    void recordPeelSteps(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t first, std::uint32_t end,
                         const DepthAwareIds& depth) const;
    // After the last step: "finalize" into `bundles` level 0 (and the collision-ray image
    // into `rays` when valid; with depth-aware separation the rays' depth intervals into
    // `depth`).
    void recordFinalize(graph::Graph& g, const RunView& run, const SamplingBuffers& b, graph::ResourceId bundles, graph::ResourceId rays,
                        const DepthAwareIds& depth) const;
    // Backend, its reason and the sampling statistics of the run; remembers the scene's
    // fragments per triangle for the next run's Auto choice.
    void report(const gpu::Header& header, std::uint32_t triangles, BroadPhaseResult& io_result);
    // The run's backend (after prepare()).
    SamplingBackend backend() const noexcept { return choice_.backend; }

private:
    ObjectSampling(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}
    vk::Device* device_;
    BufferTable* table_;
    std::unique_ptr<RasterSampler> raster_;
    std::unique_ptr<ComputeSampler> compute_;  // created on first use
    Sampler* active_ = nullptr;
    BackendChoice choice_;
    vk::Pipeline reduce_max_, peel_init_, classify_, finalize_;
    std::uint32_t last_triangles_ = 0;  // the previous run's scene, for Auto
    double last_fragments_per_triangle_ = -1;
};

}  // namespace vkcollide::passes
