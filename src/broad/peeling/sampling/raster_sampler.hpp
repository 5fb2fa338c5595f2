// The raster sampling backend: depth peeling on the graphics pipeline (paper §4). Every
// object's triangles are drawn by sample.vert; count.frag adds one per fragment to its
// ray's count, peel.frag keeps the nearest (and with dual peeling the farthest) key beyond
// the last one peeled. Thin-triangle coverage (Coverage::Dilate, ::Conservative) is drawn
// here only: the compute backend refuses it.
#pragma once

#include <memory>

#include "broad/peeling/sampling/sampler.hpp"

namespace vkcollide::passes {

class RasterSampler final : public Sampler {
public:
    static Result<std::unique_ptr<RasterSampler>> create(vk::Device& device);

    SamplingBackend backend() const noexcept override { return SamplingBackend::Raster; }
    Result<VkDeviceAddress> prepare(const BroadPhaseSettings&, const RunShape&) override { return VkDeviceAddress{0}; }
    void import(graph::Graph&) override {}
    void recordDepthComplexity(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const override;
    Result<void> preparePeeling(std::uint32_t) override { return {}; }
    std::uint32_t stepsDoneByCount() const noexcept override { return 0; }
    void recordPeelStep(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t step) const override;
    void report(BroadPhaseResult&) const override {}

private:
    RasterSampler() = default;
    void drawObject(const graph::PassContext& pc, const RunView& run, const vk::Pipeline& plain, const vk::Pipeline& conservative,
                    std::uint32_t object, std::uint32_t step, bool count_pass) const;
    vk::Pipeline count_, peel_;
    vk::Pipeline count_conservative_;  // only where the device rasterises conservatively
};

}  // namespace vkcollide::passes
