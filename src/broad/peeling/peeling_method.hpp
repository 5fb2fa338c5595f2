// The paper's method (Georgii, Krüger, Westermann 2006, passes 1-4) on the method seam:
//   measure: object sampling's depth complexity       sampling/object_sampling.hpp
//   main:    (depth-aware: triangle bounds)            triangle_bounds.hpp
//            peeling steps + classification, finalize  sampling/object_sampling.hpp
//            ray merging                               merging.hpp
//            primitive separation                      separation.hpp
//            packing into the records buffer           packing.hpp
//   collect: the records (and the collision-ray image) read back.
// The number of peeling steps is the measured depth complexity (run()) or the caller's
// prediction (submit()), at most the layer cap; half as many with dual peeling.
//
// Bounded submissions: a deep scene on a slow device peels for minutes, and GPU work
// cannot be taken back once submitted (after a timeout the world's destructor waits for
// it). So the main part submits at most a chunk of peeling steps
// (BroadPhaseSettings::peel_chunk: automatically what the device does in about
// kPeelChunkTargetMs), and collect() answers Again for the next chunk until the last,
// which also records finalize, merging, separation and packing. The broad phase checks
// the detection's deadline before each chunk. On a GPU a chunk covers every step.
#pragma once

#include <memory>

#include "broad/method.hpp"
#include "broad/peeling/merging.hpp"
#include "broad/peeling/packing.hpp"
#include "broad/peeling/sampling/object_sampling.hpp"
#include "broad/peeling/separation.hpp"
#include "broad/peeling/triangle_bounds.hpp"

namespace vkcollide::passes {

class PeelingMethod final : public BroadPhaseMethod {
public:
    static Result<std::unique_ptr<BroadPhaseMethod>> create(vk::Device& device, BufferTable& io_table, const CoreBuffers& core);

    // The method's rows of the table (also for broadPhaseMemory's plan without a device).
    struct Buffers {
        BufferId fragments, counts, front, back, state, bundles, sparse, records, scratch, ray_image;
        // Depth-aware separation only (size 0 otherwise).
        BufferId tri_bounds, edge_depth, bundle_depth, sparse_depth, ray_depth_image;
    };
    static Buffers addRows(BufferTable& io_table);

    Result<void> prepare(const BroadPhaseSettings& settings, const RunShape& shape, gpu::Frame& io_frame) override;
    // The compute sampler, which a run makes when it first samples in compute (Auto picks it per scene).
    Result<void> preparePipelines(const BroadPhaseSettings& settings) override { return sampling_->makeComputeSampler(settings.backend); }
    void import(graph::Graph& g) override { sampling_->import(g); }
    Result<void> begin(const RunView& run, const gpu::Header* measured, std::span<const graph::PassTiming> measured_passes,
                       std::uint32_t predicted_layers) override;
    // Measure: the depth complexity; Main: the first chunk of peeling steps; Again: the
    // next chunk. The last chunk is followed by finalize, merging, separation, packing.
    void record(Phase phase, graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const override;
    Result<Collected> collect(const RunView& run, const gpu::Header& header, BroadPhaseResult& io_result) override;

private:
    PeelingMethod(BufferTable& table, const CoreBuffers& core) : table_(&table), core_(core) {}
    SamplingBuffers samplingBuffers(const GraphBuffers& buffers) const;
    void setLayers(const RunView& run, std::uint32_t layers);
    // The chunk [chunk_first_, chunk_end_) of peeling steps, and after the last one the rest.
    void recordChunk(graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const;
    // Steps per submission for this run: the setting, or what the device does in about
    // kPeelChunkTargetMs (from the last run's peeling, else this run's depth-complexity
    // pass, else a guess by device type).
    std::uint32_t chunkSteps(const RunView& run, std::span<const graph::PassTiming> measured_passes) const;
    // A complete run's GPU time per peeling step, for the next run's chunks.
    void noteStepTime(std::span<const graph::PassTiming> passes);
    static double countPassMs(std::span<const graph::PassTiming> passes);
    int backendIndex() const noexcept { return sampling_->backend() == SamplingBackend::Compute ? 1 : 0; }

    BufferTable* table_;
    CoreBuffers core_;
    Buffers buf_{};
    std::unique_ptr<TriangleBounds> bounds_;
    std::unique_ptr<ObjectSampling> sampling_;
    std::unique_ptr<Merging> merging_;
    std::unique_ptr<Separation> separation_;
    std::unique_ptr<Packing> packing_;
    vk::Device* device_ = nullptr;
    std::uint32_t layers_ = 0, steps_ = 0;  // of the run being recorded
    std::uint32_t chunk_ = 0;               // its steps per submission
    std::uint32_t chunk_first_ = 0, chunk_end_ = 0;  // the steps recorded next
    // Measured by the last complete run (0: not yet): GPU ms per peeling step (peel and
    // classify), and that over the ms of its depth-complexity pass (one draw of the scene).
    // Both per sampling backend (a compute step that picks from fragment lists costs a
    // fraction of its count pass; a raster step about as much).
    double step_ms_[2] = {0, 0}, step_per_count_[2] = {0, 0};
};

// The GPU time an automatic chunk of peeling steps aims at (BroadPhaseSettings::peel_chunk).
inline constexpr double kPeelChunkTargetMs = 200.0;

}  // namespace vkcollide::passes
