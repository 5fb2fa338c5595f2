// What a pass's record callback gets: the graph's resources as Vulkan objects, and the
// recording calls. The calls go onto the executor's command tape (graph/command_tape.hpp),
// not straight into a command buffer: a detection that records what the command buffer
// the executor holds already contains submits that buffer again (Executor, "Reuse").
#pragma once

#include <cstdint>
#include <span>

#include "graph/command_tape.hpp"
#include "graph/graph.hpp"
#include "vk/resources.hpp"

namespace vkcollide::graph {

class Executor;

class PassContext {
public:
    // The command buffer itself, for code that calls vkCmd* directly (the tape has no call
    // for it): converting `cmd` to VkCommandBuffer first records everything the tape holds
    // so far, so that the direct command lands in order; convert it anew for each direct
    // call (a copy kept across tape calls would put them out of order). A submission with
    // any direct command is recorded as before and never submitted again.
    class DirectCommandBuffer {
    public:
        operator VkCommandBuffer() const;  // NOLINT(google-explicit-constructor): passed to vkCmd* as is

    private:
        friend class PassContext;
        explicit DirectCommandBuffer(PassContext* ctx) : ctx_(ctx) {}
        PassContext* ctx_;
    };
    DirectCommandBuffer cmd{this};
    vk::Device* device = nullptr;
    std::uint32_t render_width = 0, render_height = 0;  // raster passes

    PassContext() = default;
    PassContext(const PassContext&) = delete;  // `cmd` points back at its context
    PassContext& operator=(const PassContext&) = delete;

    const vk::DeviceFunctions& fns() const { return device->fns; }
    const vk::Buffer& buffer(ResourceId id) const { return *buffers_.at(id.index); }
    VkDeviceAddress address(ResourceId id) const { return buffer(id).address(); }
    const vk::Image& image(ResourceId id) const { return *images_.at(id.index); }

    // Recording (CommandTape's calls, same parameters as the vkCmd* they stand for).
    void bindPipeline(VkPipelineBindPoint point, VkPipeline pipeline) const { tape_->bindPipeline(point, pipeline); }
    void pushConstants(VkPipelineLayout layout, VkShaderStageFlags stages, std::uint32_t offset, std::uint32_t size,
                       const void* values) const {
        tape_->pushConstants(layout, stages, offset, size, values);
    }
    void pushDescriptorSet(VkPipelineBindPoint point, VkPipelineLayout layout, std::uint32_t set,
                           std::span<const VkWriteDescriptorSet> writes) const {
        tape_->pushDescriptorSet(point, layout, set, writes);
    }
    void dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z) const { tape_->dispatch(x, y, z); }
    void dispatchIndirect(VkBuffer buffer, VkDeviceSize offset) const { tape_->dispatchIndirect(buffer, offset); }
    void draw(std::uint32_t vertices, std::uint32_t instances = 1, std::uint32_t first_vertex = 0,
              std::uint32_t first_instance = 0) const {
        tape_->draw(vertices, instances, first_vertex, first_instance);
    }
    void fillBuffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, std::uint32_t data) const {
        tape_->fillBuffer(buffer, offset, size, data);
    }
    void copyBuffer(VkBuffer src, VkBuffer dst, std::span<const VkBufferCopy> regions) const { tape_->copyBuffer(src, dst, regions); }
    void copyBuffer(VkBuffer src, VkBuffer dst, const VkBufferCopy& region) const { tape_->copyBuffer(src, dst, {&region, 1}); }
    void pipelineBarrier(const VkDependencyInfo& dependency) const { tape_->pipelineBarrier(dependency); }
    // Sets `event` once every earlier command has finished, with their writes visible to
    // the host: a milestone the host polls (Executor::setMilestone).
    void signalHost(VkEvent event) const { tape_->signalHost(event); }
    // A barrier between two dependent dispatches or draws inside one pass (mip chains,
    // multi-step scans): all shader writes become visible to later shader reads and writes.
    void shaderBarrier() const;

private:
    friend class Executor;
    std::vector<const vk::Buffer*> buffers_;
    std::vector<const vk::Image*> images_;
    CommandTape* tape_ = nullptr;
    Executor* executor_ = nullptr;
};

}  // namespace vkcollide::graph
