#include "vk/features.hpp"

#include "vkcollide/context.hpp"

namespace vkcollide::vk {
namespace {

struct FeatureRow {
    const char* name;
    bool required;
};

// Indexed by Feature; the names are the Vulkan struct members.
constexpr std::array<FeatureRow, kFeatureCount> kFeatureTable = {{
    {"shaderInt64", true},
    {"fragmentStoresAndAtomics", true},
    {"bufferDeviceAddress", true},
    {"scalarBlockLayout", true},
    {"shaderBufferInt64Atomics", true},
    {"hostQueryReset", true},
    {"dynamicRendering", true},
    {"synchronization2", true},
    {"maintenance4", true},
    {"shaderFloat64", false},
    {"robustBufferAccess", false},
    {"robustBufferAccess2", false},
    // Optional, not required: vkcollide's own work synchronises with fences; timeline
    // semaphores only appear when an engine passes its own, and an engine can create one
    // only on a device where it enabled the feature. Vulkan 1.2+ devices all support it,
    // so vkcollide's own device always turns it on (tests and engines reading
    // Device::timeline_semaphore see it).
    {"timelineSemaphore", false},
}};

constexpr std::size_t kMaxChainLinks = 256;

template <typename T>
const T& as(const VkBaseInStructure* link) {
    return *reinterpret_cast<const T*>(link);
}

void readCore(const VkPhysicalDeviceFeatures& f, FeatureSet& io) {
    if (f.shaderInt64) io.set(Feature::ShaderInt64);
    if (f.fragmentStoresAndAtomics) io.set(Feature::FragmentStoresAndAtomics);
    if (f.shaderFloat64) io.set(Feature::ShaderFloat64);
    if (f.robustBufferAccess) io.set(Feature::RobustBufferAccess);
}

void readV12(const VkPhysicalDeviceVulkan12Features& f, FeatureSet& io) {
    if (f.bufferDeviceAddress) io.set(Feature::BufferDeviceAddress);
    if (f.scalarBlockLayout) io.set(Feature::ScalarBlockLayout);
    if (f.shaderBufferInt64Atomics) io.set(Feature::ShaderBufferInt64Atomics);
    if (f.hostQueryReset) io.set(Feature::HostQueryReset);
    if (f.timelineSemaphore) io.set(Feature::TimelineSemaphore);
}

void readV13(const VkPhysicalDeviceVulkan13Features& f, FeatureSet& io) {
    if (f.dynamicRendering) io.set(Feature::DynamicRendering);
    if (f.synchronization2) io.set(Feature::Synchronization2);
    if (f.maintenance4) io.set(Feature::Maintenance4);
}

// One struct of the chain; structs vkcollide has nothing to read from are skipped.
void readLink(const VkBaseInStructure* link, FeatureSet& io) {
    switch (link->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
            readV12(as<VkPhysicalDeviceVulkan12Features>(link), io);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
            readV13(as<VkPhysicalDeviceVulkan13Features>(link), io);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES:
            if (as<VkPhysicalDeviceBufferDeviceAddressFeatures>(link).bufferDeviceAddress) io.set(Feature::BufferDeviceAddress);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SCALAR_BLOCK_LAYOUT_FEATURES:
            if (as<VkPhysicalDeviceScalarBlockLayoutFeatures>(link).scalarBlockLayout) io.set(Feature::ScalarBlockLayout);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES:
            if (as<VkPhysicalDeviceShaderAtomicInt64Features>(link).shaderBufferInt64Atomics)
                io.set(Feature::ShaderBufferInt64Atomics);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES:
            if (as<VkPhysicalDeviceHostQueryResetFeatures>(link).hostQueryReset) io.set(Feature::HostQueryReset);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
            if (as<VkPhysicalDeviceDynamicRenderingFeatures>(link).dynamicRendering) io.set(Feature::DynamicRendering);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
            if (as<VkPhysicalDeviceSynchronization2Features>(link).synchronization2) io.set(Feature::Synchronization2);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
            if (as<VkPhysicalDeviceMaintenance4Features>(link).maintenance4) io.set(Feature::Maintenance4);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES:
            if (as<VkPhysicalDeviceTimelineSemaphoreFeatures>(link).timelineSemaphore) io.set(Feature::TimelineSemaphore);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT:
            if (as<VkPhysicalDeviceRobustness2FeaturesEXT>(link).robustBufferAccess2) io.set(Feature::RobustBufferAccess2);
            break;
        default: break;
    }
}

}  // namespace

const char* featureName(Feature feature) noexcept {
    const auto i = static_cast<std::size_t>(feature);
    return i < kFeatureCount ? kFeatureTable[i].name : "(unknown feature)";
}

bool isRequired(Feature feature) noexcept {
    const auto i = static_cast<std::size_t>(feature);
    return i < kFeatureCount && kFeatureTable[i].required;
}

std::vector<std::string> FeatureSet::missingRequired() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < kFeatureCount; ++i)
        if (kFeatureTable[i].required && !on_[i]) out.emplace_back(kFeatureTable[i].name);
    return out;
}

FeatureSet querySupported(const InstanceFunctions& fns, VkPhysicalDevice physical, bool has_robustness2_extension) {
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    v13.pNext = has_robustness2_extension ? &robustness2 : nullptr;
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    v12.pNext = &v13;
    VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    core.pNext = &v12;
    fns.vkGetPhysicalDeviceFeatures2(physical, &core);
    FeatureSet out;
    readCore(core.features, out);
    readV12(v12, out);
    readV13(v13, out);
    if (has_robustness2_extension && robustness2.robustBufferAccess2) out.set(Feature::RobustBufferAccess2);
    return out;
}

Result<FeatureSet> readEnabledChain(const VkPhysicalDeviceFeatures2* chain) {
    if (!chain)
        return Error(ErrorCode::InvalidArgument,
                     "AdoptedDevice::enabled_features is null: pass the VkPhysicalDeviceFeatures2 chain the device was created with");
    if (chain->sType != VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
        return Error(ErrorCode::InvalidArgument, "AdoptedDevice::enabled_features must point to a VkPhysicalDeviceFeatures2 "
                                                 "(sType " + std::to_string(static_cast<int>(chain->sType)) + " found)");
    FeatureSet out;
    readCore(chain->features, out);
    std::size_t links = 0;
    for (auto* link = static_cast<const VkBaseInStructure*>(chain->pNext); link; link = link->pNext) {
        if (++links > kMaxChainLinks)
            return Error(ErrorCode::InvalidArgument, "AdoptedDevice::enabled_features: the pNext chain has more than " +
                                                         std::to_string(kMaxChainLinks) + " structs (does it loop?)");
        readLink(link, out);
    }
    return out;
}

DeviceCreateChain::DeviceCreateChain(const FeatureSet& f, bool with_robustness2) {
    core_.pNext = &v12_;
    v12_.pNext = &v13_;
    v13_.pNext = with_robustness2 ? &robustness2_ : nullptr;
    const auto on = [&](Feature x) -> VkBool32 { return f.has(x) ? VK_TRUE : VK_FALSE; };
    core_.features.shaderInt64 = on(Feature::ShaderInt64);
    core_.features.fragmentStoresAndAtomics = on(Feature::FragmentStoresAndAtomics);
    core_.features.shaderFloat64 = on(Feature::ShaderFloat64);
    core_.features.robustBufferAccess = on(Feature::RobustBufferAccess);
    v12_.bufferDeviceAddress = on(Feature::BufferDeviceAddress);
    v12_.scalarBlockLayout = on(Feature::ScalarBlockLayout);
    v12_.shaderBufferInt64Atomics = on(Feature::ShaderBufferInt64Atomics);
    v12_.hostQueryReset = on(Feature::HostQueryReset);
    v12_.timelineSemaphore = on(Feature::TimelineSemaphore);
    v13_.dynamicRendering = on(Feature::DynamicRendering);
    v13_.synchronization2 = on(Feature::Synchronization2);
    v13_.maintenance4 = on(Feature::Maintenance4);
    // robustBufferAccess2 requires robustBufferAccess (VUID-VkPhysicalDeviceRobustness2FeaturesEXT-robustBufferAccess2-04000).
    robustness2_.robustBufferAccess2 = (f.has(Feature::RobustBufferAccess2) && f.has(Feature::RobustBufferAccess)) ? VK_TRUE : VK_FALSE;
}

}  // namespace vkcollide::vk

namespace vkcollide {

void enableRequiredFeatures(VkPhysicalDeviceFeatures2& io_features, VkPhysicalDeviceVulkan12Features& io_v12,
                            VkPhysicalDeviceVulkan13Features& io_v13) noexcept {
    // Mirrors the required rows of kFeatureTable; tests/vk/adopt_tests.cpp checks that a
    // chain filled here passes adopt() and that dropping any one feature is refused.
    io_features.features.shaderInt64 = VK_TRUE;
    io_features.features.fragmentStoresAndAtomics = VK_TRUE;
    io_v12.bufferDeviceAddress = VK_TRUE;
    io_v12.scalarBlockLayout = VK_TRUE;
    io_v12.shaderBufferInt64Atomics = VK_TRUE;
    io_v12.hostQueryReset = VK_TRUE;
    io_v13.dynamicRendering = VK_TRUE;
    io_v13.synchronization2 = VK_TRUE;
    io_v13.maintenance4 = VK_TRUE;
}

}  // namespace vkcollide
