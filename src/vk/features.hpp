// The device features vkcollide needs or can use, as one flat set with one table of names.
// The same set describes what a physical device offers (querySupported), what vkcollide
// enables on the device it creates (DeviceCreateChain) and what an engine says it enabled
// on a device it lends to Context::adopt (readEnabledChain). context.hpp documents the
// same list for engines; enableRequiredFeatures() there fills it from this table.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "vk/dispatch.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::vk {

enum class Feature : std::uint8_t {
    // Required (Context refuses a device without any of them).
    ShaderInt64,               // VkPhysicalDeviceFeatures
    FragmentStoresAndAtomics,  // VkPhysicalDeviceFeatures
    BufferDeviceAddress,       // Vulkan 1.2
    ScalarBlockLayout,         // Vulkan 1.2
    ShaderBufferInt64Atomics,  // Vulkan 1.2
    HostQueryReset,            // Vulkan 1.2: the executor resets query pools from the host
    DynamicRendering,          // Vulkan 1.3
    Synchronization2,          // Vulkan 1.3
    Maintenance4,              // Vulkan 1.3: the compute shaders use LocalSizeId
    // Optional (used where enabled).
    ShaderFloat64,        // VkPhysicalDeviceFeatures: double-precision GPU filters
    RobustBufferAccess,   // VkPhysicalDeviceFeatures: bounds-checked descriptor accesses
    RobustBufferAccess2,  // VK_EXT_robustness2 (needs RobustBufferAccess)
    TimelineSemaphore,    // Vulkan 1.2: engine timelines in submit() waits/signals and in
                          // recording into an engine command buffer (see context.hpp)
    Count
};

inline constexpr std::size_t kFeatureCount = static_cast<std::size_t>(Feature::Count);

// Vulkan's own member name ("hostQueryReset"), so an error names what to enable.
const char* featureName(Feature feature) noexcept;
bool isRequired(Feature feature) noexcept;

class FeatureSet {
public:
    bool has(Feature feature) const noexcept { return on_[static_cast<std::size_t>(feature)]; }
    void set(Feature feature, bool on = true) noexcept { on_[static_cast<std::size_t>(feature)] = on; }
    // Names of the required features this set lacks, in table order; empty when none.
    std::vector<std::string> missingRequired() const;

private:
    std::array<bool, kFeatureCount> on_{};
};

// What `physical` supports. `has_robustness2_extension`: the device exposes
// VK_EXT_robustness2, so its feature struct may be queried.
FeatureSet querySupported(const InstanceFunctions& fns, VkPhysicalDevice physical, bool has_robustness2_extension);

// Reads an engine's VkDeviceCreateInfo feature chain: a VkPhysicalDeviceFeatures2 and,
// through pNext, any of VkPhysicalDeviceVulkan11/12/13Features, the promoted single-feature
// structs (VkPhysicalDeviceHostQueryResetFeatures, ...) and
// VkPhysicalDeviceRobustness2FeaturesEXT; other structs are skipped. A feature counts as
// enabled when any struct in the chain enables it.
// Errors: InvalidArgument when `chain` is null, does not start with
// VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, or has more than 256 links (a loop).
Result<FeatureSet> readEnabledChain(const VkPhysicalDeviceFeatures2* chain);

// The VkDeviceCreateInfo::pNext chain that enables exactly `features` (vkcollide's own
// device). `with_robustness2`: also chain VkPhysicalDeviceRobustness2FeaturesEXT (only
// when the extension is enabled on the device).
class DeviceCreateChain {
public:
    DeviceCreateChain(const FeatureSet& features, bool with_robustness2);
    DeviceCreateChain(const DeviceCreateChain&) = delete;
    DeviceCreateChain& operator=(const DeviceCreateChain&) = delete;
    const VkPhysicalDeviceFeatures2* head() const noexcept { return &core_; }

private:
    VkPhysicalDeviceFeatures2 core_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features v12_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
};

}  // namespace vkcollide::vk
