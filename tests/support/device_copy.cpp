#include "support/device_copy.hpp"

#include <algorithm>
#include <cstring>

#include <catch2/catch.hpp>

#include "vk/resources.hpp"

namespace vkcollide::test {

std::vector<std::vector<std::uint8_t>> copyToHost(vk::Device& dev, std::span<const BufferRead> reads) {
    std::vector<vk::Buffer> staging;
    for (const BufferRead& r : reads) {
        auto b = vk::Buffer::create(dev, std::max<VkDeviceSize>(r.bytes, 16), 0, vk::MemoryKind::Readback, "test-copy");
        REQUIRE(b);
        staging.push_back(std::move(*b));
    }
    const vk::DeviceFunctions& f = dev.fns;
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.queueFamilyIndex = dev.queue_family;
    VkCommandPool pool = VK_NULL_HANDLE;
    REQUIRE(f.vkCreateCommandPool(dev.device, &pi, nullptr, &pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    REQUIRE(f.vkAllocateCommandBuffers(dev.device, &ai, &cmd) == VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    REQUIRE(f.vkBeginCommandBuffer(cmd, &bi) == VK_SUCCESS);
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    mb.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    f.vkCmdPipelineBarrier2(cmd, &dep);
    for (std::size_t i = 0; i < reads.size(); ++i)
        if (reads[i].bytes) {
            const VkBufferCopy copy{0, 0, reads[i].bytes};
            f.vkCmdCopyBuffer(cmd, reads[i].buffer, staging[i].handle(), 1, &copy);
        }
    VkMemoryBarrier2 hb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    hb.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    hb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    hb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    hb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    dep.pMemoryBarriers = &hb;
    f.vkCmdPipelineBarrier2(cmd, &dep);
    REQUIRE(f.vkEndCommandBuffer(cmd) == VK_SUCCESS);
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    REQUIRE(f.vkCreateFence(dev.device, &fi, nullptr, &fence) == VK_SUCCESS);
    VkCommandBufferSubmitInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    ci.commandBuffer = cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &ci;
    REQUIRE(dev.queueSubmit({&si, 1}, fence) == VK_SUCCESS);
    REQUIRE(f.vkWaitForFences(dev.device, 1, &fence, VK_TRUE, ~0ull) == VK_SUCCESS);
    f.vkDestroyFence(dev.device, fence, nullptr);
    f.vkDestroyCommandPool(dev.device, pool, nullptr);
    std::vector<std::vector<std::uint8_t>> out(reads.size());
    for (std::size_t i = 0; i < reads.size(); ++i) {
        staging[i].invalidate();
        out[i].resize(reads[i].bytes);
        if (reads[i].bytes) std::memcpy(out[i].data(), staging[i].mapped(), reads[i].bytes);
    }
    return out;
}

}  // namespace vkcollide::test
