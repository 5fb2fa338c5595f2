// What a pass records through: the context's barriers and direct command buffer, and the
// graph's imported buffers (they need the device layer, so they are not host code).
#include "graph/executor.hpp"

namespace vkcollide::graph {

ResourceId Graph::importBuffer(std::string name, vk::Buffer& buffer, bool host_readback) {
    ResourceId id = importBuffer(std::move(name), buffer.size(), host_readback);
    resources_[id.index].external_buffer = &buffer;
    return id;
}

void PassContext::shaderBarrier() const {
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.memoryBarrierCount = 1;
    di.pMemoryBarriers = &mb;
    tape_->pipelineBarrier(di);
}

PassContext::DirectCommandBuffer::operator VkCommandBuffer() const { return ctx_->executor_->directCommands(); }

}  // namespace vkcollide::graph
