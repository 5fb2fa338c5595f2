// Which object-sampling backend runs (SamplingBackend::Auto's rule), apart from either
// backend's code so that a new backend or device rule touches this file only.
#pragma once

#include <cstdint>
#include <string>

#include <vulkan/vulkan_core.h>

#include "broad/sampling_types.hpp"

namespace vkcollide::vk {
struct Device;
}

namespace vkcollide::passes {

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
// scene covering about half the image four layers deep). Thresholds: spirv/common/config.h.
// A device without subgroup ballot and arithmetic in compute shaders gets raster (and an
// error if Compute is requested).
BackendChoice chooseSamplingBackend(const VkPhysicalDeviceProperties& device, bool compute_supported,
                                    SamplingBackend requested, std::uint32_t resolution, std::uint32_t triangles,
                                    double fragments_per_triangle);

// Whether the device runs the compute backend: subgroup ballot and arithmetic in compute,
// and at most 16 sub-pixel bits.
bool computeSamplingSupported(const vk::Device& device);

}  // namespace vkcollide::passes
