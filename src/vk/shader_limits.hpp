// What a compute shader asks of the device's compute limits, read from its SPIR-V: the
// workgroup size and the bytes of workgroup (shared) memory its variables take. Vulkan
// guarantees only 16 KB of shared memory and 128 invocations per workgroup; the cell stage's
// deep sweep takes about 29 KB and most shaders 256 invocations. Pipeline::createCompute
// compares them with the device's limits, so a device below them fails by name at creation
// instead of through a validation message (or worse) at the first dispatch.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {

struct ComputeNeeds {
    std::uint32_t local_size[3] = {1, 1, 1};
    bool local_size_known = false;  // false: not declared, or by ids of constants not read here
    // Workgroup variables' sizes added up, packed as the Khronos validation layer counts
    // them against the limit (a vector is its components, an array length x element, a
    // struct its members). Drivers may pad (a uvec3 to 16 bytes); the limit is checked
    // against this count, as the layer does.
    std::uint64_t shared_bytes = 0;
};

// Reads the needs of a compute shader's SPIR-V; an error names what could not be read.
Result<ComputeNeeds> readComputeNeeds(std::span<const std::uint32_t> spirv);

// The first of the device's compute limits the needs exceed, worded with the pipeline's
// name and the limit's; nothing when they fit.
std::optional<std::string> exceededComputeLimit(const ComputeNeeds& needs, const VkPhysicalDeviceLimits& limits,
                                                const std::string& name);

}  // namespace vkcollide::vk
