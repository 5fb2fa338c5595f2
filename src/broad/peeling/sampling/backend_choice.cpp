#include "broad/peeling/sampling/backend_choice.hpp"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include "vk/device.hpp"

namespace vkcollide::passes {
namespace {

constexpr std::uint32_t kNvidiaVendor = 0x10DE;

bool contains(std::string_view haystack, std::string_view needle) { return haystack.find(needle) != std::string_view::npos; }

}  // namespace

bool computeSamplingSupported(const vk::Device& device) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &subgroup;
    device.instance_fns.vkGetPhysicalDeviceProperties2(device.physical, &props);
    const VkSubgroupFeatureFlags needed = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) && (subgroup.supportedOperations & needed) == needed &&
           props.properties.limits.subPixelPrecisionBits <= 16;
}

BackendChoice chooseSamplingBackend(const VkPhysicalDeviceProperties& device, bool compute_supported,
                                    SamplingBackend requested, std::uint32_t resolution, std::uint32_t triangles,
                                    double fragments_per_triangle) {
    if (requested == SamplingBackend::Raster) return {SamplingBackend::Raster, "requested"};
    if (requested == SamplingBackend::Compute) return {SamplingBackend::Compute, "requested"};
    if (!compute_supported) return {SamplingBackend::Raster, "auto: no subgroup ballot/arithmetic in compute, raster"};
    const std::string_view name = device.deviceName;
    if (device.vendorID == kNvidiaVendor) {
        for (std::string_view part : {"H100", "H200", "H800", "GH200", "H20"})
            if (contains(name, part))
                return {SamplingBackend::Compute,
                        "auto: " + std::string(part) + " (GH100) runs graphics on 2 of its TPCs; compute uses every SM"};
    }
    const bool measured = fragments_per_triangle >= 0;
    const double fpt = measured ? fragments_per_triangle
                                : 2.0 * double(resolution) * double(resolution) / double(std::max(triangles, 1u));
    char text[160];
    if (device.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
        const bool small = fpt < gpu::kCpuComputeFragments;
        std::snprintf(text, sizeof(text), "auto: CPU device, triangles of %.1f px (%s): %s", fpt, measured ? "measured" : "estimated",
                      small ? "compute" : "raster");
        return {small ? SamplingBackend::Compute : SamplingBackend::Raster, text};
    }
    if (fpt < gpu::kTinyTriangleFragments) {
        std::snprintf(text, sizeof(text), "auto: GPU with raster hardware but tiny triangles (%.2f px each, %s)", fpt,
                      measured ? "measured" : "estimated");
        return {SamplingBackend::Compute, text};
    }
    std::snprintf(text, sizeof(text), "auto: GPU with raster hardware, triangles of %.1f px (%s)", fpt,
                  measured ? "measured" : "estimated");
    return {SamplingBackend::Raster, text};
}

}  // namespace vkcollide::passes
