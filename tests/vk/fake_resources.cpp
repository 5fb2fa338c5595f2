// The fake driver's memory, buffers, images, pipeline caches, shader modules and compute
// pipelines (fake_vulkan_internal.hpp).
#include "vk/fake_vulkan_internal.hpp"

#include <algorithm>
#include <cstring>

namespace vkcollide::test::fake_driver {
namespace {

VKAPI_ATTR VkResult VKAPI_CALL createBuffer(VkDevice, const VkBufferCreateInfo* info, const VkAllocationCallbacks* callbacks, VkBuffer* out) {
    *out = newObject<VkBuffer>(VK_OBJECT_TYPE_BUFFER, fake().buffers_alive, callbacks);
    g_state->buffers[id(*out)] = FakeBuffer{info->size};
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyBuffer(VkDevice, VkBuffer buffer, const VkAllocationCallbacks* callbacks) {
    if (buffer && g_state->buffers.erase(id(buffer))) endObject("vkDestroyBuffer", buffer, fake().buffers_alive, callbacks);
}
VKAPI_ATTR void VKAPI_CALL getBufferMemoryRequirements(VkDevice, VkBuffer buffer, VkMemoryRequirements* out) {
    const VkDeviceSize size = g_state->buffers.at(id(buffer)).size;
    *out = VkMemoryRequirements{(size + 255) / 256 * 256, 256, 1u};
}
VKAPI_ATTR VkResult VKAPI_CALL allocateMemory(VkDevice, const VkMemoryAllocateInfo* info, const VkAllocationCallbacks* callbacks,
                                              VkDeviceMemory* out) {
    *out = newObject<VkDeviceMemory>(VK_OBJECT_TYPE_DEVICE_MEMORY, fake().allocations_alive, callbacks);
    g_state->memory[id(*out)] = std::make_unique<std::byte[]>(info->allocationSize);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL freeMemory(VkDevice, VkDeviceMemory memory, const VkAllocationCallbacks* callbacks) {
    if (memory && g_state->memory.erase(id(memory))) endObject("vkFreeMemory", memory, fake().allocations_alive, callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL bindBufferMemory(VkDevice, VkBuffer, VkDeviceMemory, VkDeviceSize offset) {
    fake().bind_offsets.push_back(offset);
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL mapMemory(VkDevice, VkDeviceMemory memory, VkDeviceSize offset, VkDeviceSize, VkMemoryMapFlags,
                                         void** out) {
    *out = g_state->memory.at(id(memory)).get() + offset;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL unmapMemory(VkDevice, VkDeviceMemory) {}
VKAPI_ATTR VkDeviceAddress VKAPI_CALL getBufferDeviceAddress(VkDevice, const VkBufferDeviceAddressInfo* info) {
    return id(info->buffer) << 20;
}
VKAPI_ATTR VkResult VKAPI_CALL flushMappedMemoryRanges(VkDevice, std::uint32_t count, const VkMappedMemoryRange* ranges) {
    fake().flushed.insert(fake().flushed.end(), ranges, ranges + count);
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL invalidateMappedMemoryRanges(VkDevice, std::uint32_t count, const VkMappedMemoryRange* ranges) {
    fake().invalidated.insert(fake().invalidated.end(), ranges, ranges + count);
    return VK_SUCCESS;
}

// ---- images -------------------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createImage(VkDevice, const VkImageCreateInfo* info, const VkAllocationCallbacks* callbacks, VkImage* out) {
    *out = newObject<VkImage>(VK_OBJECT_TYPE_IMAGE, fake().images_alive, callbacks);
    g_state->images[id(*out)] = VkDeviceSize(info->extent.width) * info->extent.height * 4 * 2;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyImage(VkDevice, VkImage image, const VkAllocationCallbacks* callbacks) {
    if (image && g_state->images.erase(id(image))) endObject("vkDestroyImage", image, fake().images_alive, callbacks);
}
VKAPI_ATTR void VKAPI_CALL getImageMemoryRequirements(VkDevice, VkImage image, VkMemoryRequirements* out) {
    *out = VkMemoryRequirements{(g_state->images.at(id(image)) + 1023) / 1024 * 1024, 1024, 1u};
}
VKAPI_ATTR VkResult VKAPI_CALL bindImageMemory(VkDevice, VkImage, VkDeviceMemory, VkDeviceSize offset) {
    fake().bind_offsets.push_back(offset);
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL createImageView(VkDevice, const VkImageViewCreateInfo*, const VkAllocationCallbacks* callbacks,
                                               VkImageView* out) {
    *out = newObject<VkImageView>(VK_OBJECT_TYPE_IMAGE_VIEW, fake().image_views_alive, callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyImageView(VkDevice, VkImageView view, const VkAllocationCallbacks* callbacks) {
    if (view) endObject("vkDestroyImageView", view, fake().image_views_alive, callbacks);
}

// ---- pipelines and their cache -------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createPipelineCache(VkDevice, const VkPipelineCacheCreateInfo* info, const VkAllocationCallbacks* callbacks,
                                                   VkPipelineCache* out) {
    *out = newObject<VkPipelineCache>(VK_OBJECT_TYPE_PIPELINE_CACHE, fake().pipeline_caches_alive, callbacks);
    fake().last_pipeline_cache_initial_size = info->initialDataSize;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipelineCache(VkDevice, VkPipelineCache cache, const VkAllocationCallbacks* callbacks) {
    if (cache) endObject("vkDestroyPipelineCache", cache, fake().pipeline_caches_alive, callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL getPipelineCacheData(VkDevice, VkPipelineCache, std::size_t* size, void* data) {
    // The header, then one byte per pipeline created so far (a cache that fills up).
    std::vector<std::byte> all = FakeVulkan::cacheHeader(fake().physical_devices.at(g_state->device_physical));
    all.resize(all.size() + fake().pipelines_cache_used.size(), std::byte{7});
    if (!data) {
        *size = all.size();
        return VK_SUCCESS;
    }
    const std::size_t n = std::min(*size, all.size());
    std::memcpy(data, all.data(), n);
    *size = n;
    return n < all.size() ? VK_INCOMPLETE : VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL createShaderModule(VkDevice, const VkShaderModuleCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                  VkShaderModule* out) {
    *out = newObject<VkShaderModule>(VK_OBJECT_TYPE_SHADER_MODULE, fake().shader_modules_alive, callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyShaderModule(VkDevice, VkShaderModule module, const VkAllocationCallbacks* callbacks) {
    if (module) endObject("vkDestroyShaderModule", module, fake().shader_modules_alive, callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL createPipelineLayout(VkDevice, const VkPipelineLayoutCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                    VkPipelineLayout* out) {
    *out = newObject<VkPipelineLayout>(VK_OBJECT_TYPE_PIPELINE_LAYOUT, fake().pipeline_layouts_alive, callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipelineLayout(VkDevice, VkPipelineLayout layout, const VkAllocationCallbacks* callbacks) {
    if (layout) endObject("vkDestroyPipelineLayout", layout, fake().pipeline_layouts_alive, callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL createComputePipelines(VkDevice, VkPipelineCache cache, std::uint32_t count,
                                                      const VkComputePipelineCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                      VkPipeline* out) {
    for (std::uint32_t i = 0; i < count; ++i) {
        out[i] = newObject<VkPipeline>(VK_OBJECT_TYPE_PIPELINE, fake().pipelines_alive, callbacks);
        fake().pipelines_cache_used.push_back(cache);
    }
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipeline(VkDevice, VkPipeline pipeline, const VkAllocationCallbacks* callbacks) {
    if (pipeline) endObject("vkDestroyPipeline", pipeline, fake().pipelines_alive, callbacks);
}

}  // namespace

EntryMap resourceEntries() {
    return {
        entry("vkCreateBuffer", createBuffer),
        entry("vkDestroyBuffer", destroyBuffer),
        entry("vkGetBufferMemoryRequirements", getBufferMemoryRequirements),
        entry("vkAllocateMemory", allocateMemory),
        entry("vkFreeMemory", freeMemory),
        entry("vkBindBufferMemory", bindBufferMemory),
        entry("vkMapMemory", mapMemory),
        entry("vkUnmapMemory", unmapMemory),
        entry("vkGetBufferDeviceAddress", getBufferDeviceAddress),
        entry("vkFlushMappedMemoryRanges", flushMappedMemoryRanges),
        entry("vkInvalidateMappedMemoryRanges", invalidateMappedMemoryRanges),
        entry("vkCreateImage", createImage),
        entry("vkDestroyImage", destroyImage),
        entry("vkGetImageMemoryRequirements", getImageMemoryRequirements),
        entry("vkBindImageMemory", bindImageMemory),
        entry("vkCreateImageView", createImageView),
        entry("vkDestroyImageView", destroyImageView),
        entry("vkCreatePipelineCache", createPipelineCache),
        entry("vkDestroyPipelineCache", destroyPipelineCache),
        entry("vkGetPipelineCacheData", getPipelineCacheData),
        entry("vkCreateShaderModule", createShaderModule),
        entry("vkDestroyShaderModule", destroyShaderModule),
        entry("vkCreatePipelineLayout", createPipelineLayout),
        entry("vkDestroyPipelineLayout", destroyPipelineLayout),
        entry("vkCreateComputePipelines", createComputePipelines),
        entry("vkDestroyPipeline", destroyPipeline),
    };
}

}  // namespace vkcollide::test::fake_driver
