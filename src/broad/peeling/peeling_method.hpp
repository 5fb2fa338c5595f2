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
    void import(graph::Graph& g) override { sampling_->import(g); }
    Result<void> begin(const RunView& run, const gpu::Header* measured, std::uint32_t predicted_layers) override;
    // Measure: the depth complexity; Main: peeling, merging, separation, packing. Nothing
    // overflows on the GPU, so there is no Again.
    void record(Phase phase, graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const override;
    Result<Collected> collect(const RunView& run, const gpu::Header& header, BroadPhaseResult& io_result) override;

private:
    PeelingMethod(BufferTable& table, const CoreBuffers& core) : table_(&table), core_(core) {}
    SamplingBuffers samplingBuffers(const GraphBuffers& buffers) const;
    void setLayers(const RunView& run, std::uint32_t layers);
    void recordMain(graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const;

    BufferTable* table_;
    CoreBuffers core_;
    Buffers buf_{};
    std::unique_ptr<TriangleBounds> bounds_;
    std::unique_ptr<ObjectSampling> sampling_;
    std::unique_ptr<Merging> merging_;
    std::unique_ptr<Separation> separation_;
    std::unique_ptr<Packing> packing_;
    std::uint32_t layers_ = 0, steps_ = 0;  // of the run being recorded
};

}  // namespace vkcollide::passes
