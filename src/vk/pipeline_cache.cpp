// The one VkPipelineCache every vkcollide pipeline goes through (context.hpp, Pipelines):
// the engine's, borrowed, or the Context's own, filled from data saved by an earlier run.
#include <cstring>
#include <vector>

#include "vk/debug_names.hpp"
#include "vk/device.hpp"

namespace vkcollide::vk {

bool pipelineCacheDataMatches(const Device& device, std::span<const std::byte> data) noexcept {
    // Vulkan says a driver must ignore data of another device, but some have crashed on
    // stale caches; the header check is cheap and makes "ignored" visible (an Info message).
    VkPipelineCacheHeaderVersionOne header{};
    if (data.size() < sizeof(header)) return false;
    std::memcpy(&header, data.data(), sizeof(header));
    return header.headerSize >= sizeof(header) && header.headerSize <= data.size() &&
           header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header.vendorID == device.properties.vendorID &&
           header.deviceID == device.properties.deviceID &&
           std::memcmp(header.pipelineCacheUUID, device.properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

Result<void> setUpPipelineCache(Device& device, VkPipelineCache borrowed, std::span<const std::byte> initial_data) {
    if (borrowed) {
        device.pipeline_cache = borrowed;
        device.owns_pipeline_cache = false;
        return {};
    }
    VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    if (!initial_data.empty()) {
        if (pipelineCacheDataMatches(device, initial_data)) {
            ci.initialDataSize = initial_data.size();
            ci.pInitialData = initial_data.data();
        } else {
            device.message(MessageSeverity::Info, "pipeline_cache_data was saved for another device or driver; starting with an empty cache");
        }
    }
    VkResult r = device.fns.vkCreatePipelineCache(device.device, &ci, device.allocator(), &device.pipeline_cache);
    if (r != VK_SUCCESS) {
        device.pipeline_cache = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreatePipelineCache");
    }
    nameObject(device, device.pipeline_cache, "pipeline cache");
    device.owns_pipeline_cache = true;
    return {};
}

}  // namespace vkcollide::vk

namespace vkcollide {

Result<std::vector<std::byte>> Context::pipelineCacheData() const {
    const vk::Device& d = *device_;
    std::vector<std::byte> data;
    // The cache can grow between the two calls (another world creating pipelines):
    // VK_INCOMPLETE then means "ask again".
    for (int attempt = 0; attempt < 4; ++attempt) {
        std::size_t size = 0;
        VkResult r = d.fns.vkGetPipelineCacheData(d.device, d.pipeline_cache, &size, nullptr);
        if (r != VK_SUCCESS) return vk::vulkanError(r, "vkGetPipelineCacheData (size)");
        data.resize(size);
        r = d.fns.vkGetPipelineCacheData(d.device, d.pipeline_cache, &size, data.data());
        if (r == VK_SUCCESS) {
            data.resize(size);
            return data;
        }
        if (r != VK_INCOMPLETE) return vk::vulkanError(r, "vkGetPipelineCacheData");
    }
    return Error(ErrorCode::VulkanError, "vkGetPipelineCacheData kept returning VK_INCOMPLETE (the cache grows while it is read)",
                 static_cast<std::int32_t>(VK_INCOMPLETE));
}

Result<std::vector<PipelineStatistics>> Context::pipelineStatistics() const {
    vk::Device& d = *device_;
    if (!d.capture_statistics) return Error(ErrorCode::UnsupportedFeature, "pipeline statistics: " + d.statistics_unavailable);
    std::lock_guard lock(d.pipelines_mutex);
    return d.pipeline_statistics;
}

}  // namespace vkcollide
