// Object sampling (paper §4, pass 1) without the graphics pipeline: a compute backend that
// produces the raster backend's depth-complexity counts and peeling keys, so the shared
// passes after it (classify, finalize, merge, separate, pack) see the same data.
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
// Not thread-safe; one instance per BroadPhase.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "config.h"
#include "graph/executor.hpp"
#include "vk/resources.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide::passes {

struct GpuMesh;

using vkcollide::SamplingBackend;  // Auto, Raster, Compute (vkcollide/types.hpp)

struct ComputeSamplingTuning {
    // Most pixels in the pixel box of a triangle drawn by one invocation; bigger boxes are
    // drawn in tiles. 0 draws every triangle in tiles. (Defaults: spirv/config.h.)
    std::uint32_t small_box = gpu::kCsSmallBox;
    // Fragment lists: the count pass stores the first `list_layers` keys of every ray
    // (N^2 x layers x 8 bytes) and each peeling step picks its keys per pixel, instead of
    // drawing every triangle again per step. A ray with more keys costs one more drawing
    // (gather) in that run, and the next run stores as many layers as this one needed.
    // Lists are used while the buffer needs at most `list_budget_bytes`; 0: never.
    std::uint64_t list_budget_bytes = gpu::kCsListBudgetBytes;
    std::uint32_t list_layers = gpu::kCsListLayers;
    // Without fragment lists (budget 0): the depth-complexity pass also does peeling step 0
    // (the nearest and farthest key of every ray), one drawing of the triangles fewer.
    bool fuse_first_step = true;
    // The depth plane: through the snapped vertices (hardware rasterizers) or the unsnapped
    // ones (llvmpipe's setup); Device picks by vendor (Mesa: unsnapped).
    enum class DepthPlane { Device, Snapped, Unsnapped } depth_plane = DepthPlane::Device;
};

// The backend that runs and a one-line reason.
struct BackendChoice {
    SamplingBackend backend = SamplingBackend::Raster;
    std::string reason;
};

// What Auto picks (Raster and Compute are returned as asked):
//  1. A GPU whose graphics pipeline runs on a small part of the chip -- NVIDIA GH100 parts
//     (H100, H200, H800, GH200, H20): 2 of their TPCs run graphics. Compute always (H200:
//     6-57x faster from 0.8 to 1600 px per triangle, docs/results.md).
//  2. Any other GPU (full raster hardware): raster, except for tiny triangles (fewer than
//     kTinyTriangleFragments fragments per triangle), where quad-based rasterizers waste
//     most of their work (an inference; not measured on such a GPU).
//  3. A CPU implementation (lavapipe): compute for triangles under kCpuComputeFragments
//     pixels, raster for bigger ones (lavapipe on 2 cores, wall time per run: compute
//     3-4x faster at 7 px per triangle, raster about 2x faster from 24 px up).
// `fragments_per_triangle` is the scene's mean number of covered pixels per triangle:
// measured by the previous run on the same triangle count (the depth-complexity counts
// summed), or < 0 when unknown; then estimated as resolution^2 * 2 / triangles (a fitted
// scene covering about half the image four layers deep). Thresholds: spirv/config.h.
// A device without subgroup ballot and arithmetic in compute shaders gets raster (and an
// error if Compute is requested).
BackendChoice chooseSamplingBackend(const VkPhysicalDeviceProperties& device, bool compute_supported,
                                    SamplingBackend requested, std::uint32_t resolution, std::uint32_t triangles,
                                    double fragments_per_triangle);

// Whether the device runs the compute backend: subgroup ballot and arithmetic in compute.
bool computeSamplingSupported(const vk::Device& device);

class ComputeSampling {
public:
    static Result<std::unique_ptr<ComputeSampling>> create(vk::Device& device);

    // Sizes the buffers for `triangles` and writes the CsFrame. Returns its address (for
    // Frame::compute_sampling). Call before recording either submission.
    [[nodiscard]] Result<VkDeviceAddress> prepare(std::uint32_t resolution, std::uint32_t triangles,
                                                  const ComputeSamplingTuning& tuning);
    // Whether the prepared run does peeling step 0 in the depth-complexity pass: then
    // peel_init leaves the keys (its step 1) and step 0 records no peel pass.
    bool fusesFirstStep() const noexcept { return fuse_; }
    // After submission 1: fragment lists (complete, or to gather again) or drawing per
    // step, given the depth complexity.
    [[nodiscard]] Result<void> preparePeeling(std::uint32_t depth_complexity);
    bool usesFragmentLists() const noexcept { return fragment_lists_; }
    bool gathers() const noexcept { return gather_; }

    // The broad phase's resources these passes use.
    struct Shared {
        graph::ResourceId projection, header, counts, state, front, back;
    };
    // This backend's buffers in one graph; import once per graph.
    struct Ids {
        graph::ResourceId triangles, lists, items, counters, args, fill, fragments;
    };
    Ids import(graph::Graph& g);

    // Submission 1: setup, then the depth-complexity counts (pass "depth-complexity");
    // with fusesFirstStep() also step 0's keys (shared.front, shared.back).
    void addDepthComplexity(graph::Graph& g, const Ids& ids, const Shared& shared, std::span<const GpuMesh> meshes,
                            VkDeviceAddress frame) const;
    // Submission 2: one peeling step (pass "peel[step]"), before classify[step]; records
    // nothing for step 0 when fusesFirstStep(). With fragment lists each step picks per
    // pixel, and step 0 is preceded by "csample-gather" when gathers().
    void addPeelStep(graph::Graph& g, const Ids& ids, const Shared& shared, std::uint32_t step, bool dual,
                     VkDeviceAddress frame) const;

private:
    explicit ComputeSampling(vk::Device& device) : device_(&device) {}
    vk::Device* device_;
    vk::Pipeline setup_, bin_, args_, count_, peel_, gather_pipe_, pick_;
    vk::Buffer frame_, triangles_, lists_, items_, counters_, args_buf_, fill_, fragments_;
    std::uint32_t resolution_ = 0;
    std::uint64_t list_budget_ = 0;
    std::uint32_t list_layers_ = 0;       // stored by the count pass this run
    std::uint32_t next_list_layers_ = 0;  // what the last run needed
    bool fuse_ = false;
    bool fragment_lists_ = false;
    bool gather_ = false;
};

}  // namespace vkcollide::passes
