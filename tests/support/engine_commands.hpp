// A command buffer of the engine's, for tests that hand vkcollide an EngineCommandBuffer:
// the engine's own pool on the Context's queue family, one primary command buffer begun at
// construction, ended and submitted (signalling the engine's timeline) by submit(); the
// pool is destroyed with the object (after the caller waited for the work).
#pragma once

#include <span>

#include <catch2/catch.hpp>

#include "vk/device.hpp"

namespace vkcollide::test {

struct EngineCommands {
    vk::Device& dev;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    explicit EngineCommands(vk::Device& d) : dev(d) {
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.queueFamilyIndex = dev.queue_family;
        REQUIRE(dev.fns.vkCreateCommandPool(dev.device, &pi, nullptr, &pool) == VK_SUCCESS);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        REQUIRE(dev.fns.vkAllocateCommandBuffers(dev.device, &ai, &cmd) == VK_SUCCESS);
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        REQUIRE(dev.fns.vkBeginCommandBuffer(cmd, &bi) == VK_SUCCESS);
    }
    EngineCommands(const EngineCommands&) = delete;
    EngineCommands& operator=(const EngineCommands&) = delete;
    // Ends and submits it, signalling `timeline` to `value`.
    void submit(VkSemaphore timeline, std::uint64_t value) {
        REQUIRE(dev.fns.vkEndCommandBuffer(cmd) == VK_SUCCESS);
        VkCommandBufferSubmitInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        ci.commandBuffer = cmd;
        VkSemaphoreSubmitInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        si.semaphore = timeline;
        si.value = value;
        si.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit_info.commandBufferInfoCount = 1;
        submit_info.pCommandBufferInfos = &ci;
        submit_info.signalSemaphoreInfoCount = 1;
        submit_info.pSignalSemaphoreInfos = &si;
        REQUIRE(dev.queueSubmit(std::span(&submit_info, 1), VK_NULL_HANDLE) == VK_SUCCESS);
    }
    ~EngineCommands() { dev.fns.vkDestroyCommandPool(dev.device, pool, nullptr); }
};

}  // namespace vkcollide::test
