// The compute sampling backend: object sampling (paper §4, pass 1) without the graphics
// pipeline. It produces the raster backend's depth-complexity counts and peeling keys, so
// the shared passes after it (classify, finalize, merge, separate, pack) see the same data.
//
// Coverage is the rasterizer's: vertices go through sample.vert's transform and the
// viewport transform, are snapped to the device's sub-pixel grid
// (VkPhysicalDeviceLimits::subPixelPrecisionBits, round to nearest even), and a pixel is
// covered when its centre is inside the snapped triangle, with the top-left rule for
// centres exactly on an edge. Facing is the sign of the snapped area, as in Vulkan.
// Depth is a plane evaluated at the pixel centre in float, through the snapped vertices
// (hardware rasterizers; the H200 matches) or the unsnapped ones (llvmpipe): it can differ
// from the rasterizer's gl_FragCoord.z by a few ulps, so two fragments of one ray whose
// depths are that close may be peeled in the other order (the tie tolerance).
// Fragments with depth outside [0, 1] are dropped (the rasterizer clips them); window
// positions farther than 2^(29 - subpixel bits) pixels are clamped (the rasterizer clips at
// its guard band). Neither happens with the automatic fit.
//
// Passes it records:
//   submission 1: "csample-setup" (per triangle: setup, small/big lists, tile binning,
//                 indirect arguments), then "depth-complexity" (compute, counts)
//   submission 2: with fragment lists (stored by the count pass; "csample-gather" again
//                 if a ray had more than it stored), per step "peel[i]" picking per
//                 pixel; otherwise per step "peel[i]" drawing the triangles again (step 0
//                 done by the count pass when fused)
// Triangles whose pixel box has at most `small_box` pixels are drawn by one invocation
// each; bigger ones are cut into 8x8-pixel tiles drawn by one workgroup each (one
// invocation per pixel), so a big triangle does not serialise on one invocation.
// docs/broadphase.md ("Sampling backends") has the whole design and its measurements.
//
// Its buffers are owner-sized rows of the broad phase's table (added at create()).
// Not thread-safe; one instance per BroadPhase.
#pragma once

#include <cstdint>
#include <memory>

#include "broad/peeling/sampling/sampler.hpp"

namespace vkcollide::passes {

class ComputeSampler final : public Sampler {
public:
    // UnsupportedFeature where computeSamplingSupported() is false.
    static Result<std::unique_ptr<ComputeSampler>> create(vk::Device& device, BufferTable& io_table);

    SamplingBackend backend() const noexcept override { return SamplingBackend::Compute; }
    // Sizes the buffers for the run and writes the CsFrame; returns its address.
    Result<VkDeviceAddress> prepare(const BroadPhaseSettings& settings, const RunShape& shape) override;
    void import(graph::Graph& g) override;
    // Setup, then the depth-complexity counts; when fused also step 0's keys.
    void recordDepthComplexity(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const override;
    // Fragment lists (complete, or to gather again) or drawing per step.
    Result<void> preparePeeling(std::uint32_t depth_complexity) override;
    // 1 when the depth-complexity pass did peeling step 0 (fused): peel-init leaves the
    // keys and step 0 records no peel pass.
    std::uint32_t stepsDoneByCount() const noexcept override { return fuse_ ? 1u : 0u; }
    // With fragment lists each step picks per pixel, and step 0 is preceded by
    // "csample-gather" when the lists were too short.
    void recordPeelStep(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t step) const override;
    void report(BroadPhaseResult& io_result) const override { io_result.compute_fragment_lists = fragment_lists_; }

private:
    ComputeSampler(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}
    Result<void> reserve(std::initializer_list<RowSize> sizes) const;
    vk::Device* device_;
    BufferTable* table_;
    vk::Pipeline setup_, bin_, args_, count_, peel_, gather_pipe_, pick_;
    TableRow frame_, triangles_, lists_, items_, counters_, args_buf_, fill_, fragments_;
    // This backend's buffers in the graph being recorded.
    struct Ids {
        graph::ResourceId triangles, lists, items, counters, args, fill, fragments;
    } ids_;
    std::uint32_t resolution_ = 0, triangles_count_ = 0;
    std::uint64_t list_budget_ = 0;
    std::uint32_t list_layers_ = 0;       // stored by the count pass this run
    std::uint32_t next_list_layers_ = 0;  // what the last run needed
    bool fuse_ = false;
    bool fragment_lists_ = false;
    bool gather_ = false;
};

}  // namespace vkcollide::passes
