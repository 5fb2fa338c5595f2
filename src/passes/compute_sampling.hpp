// Object sampling (paper §4, pass 1) without the graphics pipeline: a compute backend that
// produces the raster backend's depth-complexity counts and peeling keys, so the shared
// passes after it (classify, finalize, merge, separate, pack) see the same data.
//
// Coverage is the rasterizer's: vertices go through sample.vert's transform and the
// viewport transform, are snapped to the device's sub-pixel grid
// (VkPhysicalDeviceLimits::subPixelPrecisionBits, round to nearest even), and a pixel is
// covered when its centre is inside the snapped triangle, with the top-left rule for
// centres exactly on an edge. Facing is the sign of the snapped area, as in Vulkan.
// Depth is the plane through the unsnapped window positions, evaluated at the pixel
// centre in float: it can differ from the rasterizer's gl_FragCoord.z by a few ulps, so two
// fragments of one ray whose depths are that close may be peeled in the other order.
// Fragments with depth outside [0, 1] are dropped (the rasterizer clips them); window
// positions farther than 2^(29 - subpixel bits) pixels are clamped (the rasterizer clips at
// its guard band). Neither happens with the automatic fit.
//
// Passes it records:
//   submission 1: "csample-setup" (per triangle: setup, small/big lists, tile binning,
//                 indirect arguments), then "depth-complexity" (compute, counts)
//   submission 2: "peel[i]" (compute) in place of the raster peel of step i
// Triangles whose pixel box has at most `small_box` pixels are drawn by one invocation
// each; bigger ones are cut into 8x8-pixel tiles drawn by one workgroup each (one
// invocation per pixel), so a big triangle does not serialise on one invocation.
//
// Not thread-safe; one instance per BroadPhase.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "graph/executor.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::passes {

struct GpuMesh;

using vkcollide::SamplingBackend;  // Auto, Raster, Compute (world.hpp)
const char* toString(SamplingBackend backend) noexcept;

struct ComputeSamplingTuning {
    // Most pixels in the pixel box of a triangle drawn by one invocation; bigger boxes are
    // drawn in tiles. 0 draws every triangle in tiles.
    std::uint32_t small_box = 64;
    // The depth-complexity pass also does peeling step 0 (the nearest and farthest key of
    // every ray): one traversal of the triangles fewer.
    bool fuse_first_step = true;
};

// The backend that runs and a one-line reason.
struct BackendChoice {
    SamplingBackend backend = SamplingBackend::Raster;
    std::string reason;
};

// What Auto picks (Raster and Compute are returned as asked):
//  1. A GPU whose graphics pipeline runs on a small part of the chip -- NVIDIA GH100 parts
//     (H100, H200, H800, GH200, H20): 2 of their TPCs run graphics. Compute always.
//  2. Any other GPU (full raster hardware): raster, except for tiny triangles (fewer than
//     kTinyTriangleFragments fragments per triangle), where quad-based rasterizers waste
//     most of their work.
//  3. A CPU implementation (lavapipe): raster.
// `fragments_per_triangle` is the scene's mean number of covered pixels per triangle:
// measured by the previous run on the same triangle count (the depth-complexity counts
// summed), or < 0 when unknown; then estimated as resolution^2 * 2 / triangles (a fitted
// scene covering about half the image four layers deep).
inline constexpr double kTinyTriangleFragments = 1.0;
BackendChoice chooseSamplingBackend(const VkPhysicalDeviceProperties& device, SamplingBackend requested,
                                    std::uint32_t resolution, std::uint32_t triangles, double fragments_per_triangle);

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

    // The broad phase's resources these passes use.
    struct Shared {
        graph::ResourceId projection, header, counts, state, front, back;
    };
    // This backend's buffers in one graph; import once per graph.
    struct Ids {
        graph::ResourceId triangles, lists, items, counters, args;
    };
    Ids import(graph::Graph& g);

    // Submission 1: setup, then the depth-complexity counts (pass "depth-complexity");
    // with fusesFirstStep() also step 0's keys (shared.front, shared.back).
    void addDepthComplexity(graph::Graph& g, const Ids& ids, const Shared& shared, std::span<const GpuMesh> meshes,
                            VkDeviceAddress frame) const;
    // Submission 2: one peeling step (pass "peel[step]"), before classify[step]; records
    // nothing for step 0 when fusesFirstStep().
    void addPeelStep(graph::Graph& g, const Ids& ids, const Shared& shared, std::uint32_t step, bool dual,
                     VkDeviceAddress frame) const;

private:
    explicit ComputeSampling(vk::Device& device) : device_(&device) {}
    vk::Device* device_;
    vk::Pipeline setup_, bin_, args_, count_, peel_;
    vk::Buffer frame_, triangles_, lists_, items_, counters_, args_buf_;
    std::uint32_t resolution_ = 0;
    bool fuse_ = false;
};

}  // namespace vkcollide::passes
