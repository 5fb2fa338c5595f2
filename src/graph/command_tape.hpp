// A command tape: the commands of one submission as plain data (every parameter by value,
// descriptor infos and barriers deep-copied), so that the executor can tell whether this
// detection records exactly what the command buffer it holds already contains, and then
// submit that command buffer again instead of recording it (recording costs the driver
// 30-80 us a detection; building and comparing the tape a few). Replaying a tape into a
// command buffer records the same commands with the same parameters, in order.
//
// Host only (no device): the tape never calls Vulkan except through replay()'s table.
// Equal tapes name the same handles; whether those handles still name the same objects
// is the caller's question (the executor checks vk::Device::resource_generation).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vk/dispatch.hpp"

namespace vkcollide::graph {

class CommandTape {
public:
    // Each call appends one command. Structures are copied field by field; pNext chains
    // are not supported (every pNext must be null: std::abort otherwise, in every build,
    // because dropping one would record something else than was asked).
    void bindPipeline(VkPipelineBindPoint bind_point, VkPipeline pipeline);
    void pushConstants(VkPipelineLayout layout, VkShaderStageFlags stages, std::uint32_t offset, std::uint32_t size,
                       const void* values);
    // Buffer, image and texel-buffer descriptors (VK_KHR_push_descriptor).
    void pushDescriptorSet(VkPipelineBindPoint bind_point, VkPipelineLayout layout, std::uint32_t set,
                           std::span<const VkWriteDescriptorSet> writes);
    void dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z);
    void dispatchIndirect(VkBuffer buffer, VkDeviceSize offset);
    void draw(std::uint32_t vertices, std::uint32_t instances, std::uint32_t first_vertex, std::uint32_t first_instance);
    void fillBuffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, std::uint32_t data);
    void copyBuffer(VkBuffer src, VkBuffer dst, std::span<const VkBufferCopy> regions);
    void pipelineBarrier(const VkDependencyInfo& dependency);
    void beginRendering(const VkRenderingInfo& info);
    void endRendering();
    void setViewport(const VkViewport& viewport);
    void setScissor(const VkRect2D& scissor);
    void writeTimestamp(VkPipelineStageFlags2 stage, VkQueryPool pool, std::uint32_t query);
    // Every earlier command's writes made visible to the host (a barrier to HOST_READ), then
    // `event` set (vkCmdSetEvent2 over every earlier command): PassContext::signalHost.
    void signalHost(VkEvent event);
    // A VK_EXT_debug_utils label named prefix + name (stored with its NUL, so that replay
    // passes it in place) until the matching endLabel().
    void beginLabel(std::string_view prefix, std::string_view name);
    void endLabel();

    void clear() noexcept {
        words_.clear();
        signals_ = 0;
    }
    // How many signalHost() commands it holds.
    std::size_t signals() const noexcept { return signals_; }
    // Position after the last command (replay() starts from one).
    std::size_t size() const noexcept { return words_.size(); }
    bool empty() const noexcept { return words_.empty(); }
    // The same commands with the same parameters.
    friend bool operator==(const CommandTape& a, const CommandTape& b) noexcept { return a.words_ == b.words_; }

    // Records the commands from position `from` (0, or a size() taken earlier) to the end
    // into `cmd`, which is recording. Needs fns.vkCmdPushDescriptorSetKHR only when the
    // tape pushes descriptors, the debug-utils label functions only when it has labels.
    void replay(const vk::DeviceFunctions& fns, VkCommandBuffer cmd, std::size_t from = 0);

private:
    void put(std::uint64_t word) { words_.push_back(word); }
    void putBytes(const void* bytes, std::size_t size);

    // One word per field (two 32-bit fields share one where noted in the .cpp): a layout
    // without padding, so that equal commands are equal words.
    std::vector<std::uint64_t> words_;
    std::size_t signals_ = 0;
    // replay()'s scratch, kept between replays.
    std::vector<VkMemoryBarrier2> memory_barriers_;
    std::vector<VkBufferMemoryBarrier2> buffer_barriers_;
    std::vector<VkImageMemoryBarrier2> image_barriers_;
    std::vector<VkWriteDescriptorSet> writes_;
    std::vector<VkDescriptorBufferInfo> buffer_infos_;
    std::vector<VkDescriptorImageInfo> image_infos_;
    std::vector<VkBufferView> texel_views_;
    std::vector<VkBufferCopy> copies_;
    std::vector<VkRenderingAttachmentInfo> attachments_;
};

}  // namespace vkcollide::graph
