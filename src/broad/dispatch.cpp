#include "broad/dispatch.hpp"

#include <algorithm>
#include <cstdlib>

namespace vkcollide::passes {

void bindAndPush(const graph::PassContext& pc, const vk::Pipeline& p, VkDeviceAddress frame, std::uint32_t object,
                 std::uint32_t step, std::uint32_t level, std::uint32_t coverage) {
    gpu::Push push{frame, object, step, level, coverage};
    pc.bindPipeline(p.bindPoint(), p.handle());
    const VkShaderStageFlags stages = p.bindPoint() == VK_PIPELINE_BIND_POINT_COMPUTE
                                          ? VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT)
                                          : VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    pc.pushConstants(p.layout(), stages, 0, sizeof(push), &push);
}

std::uint32_t groups(std::uint64_t items, std::uint32_t size) { return static_cast<std::uint32_t>((items + size - 1) / size); }

DispatchShape dispatchShape(std::uint64_t groups, std::uint32_t max_x, std::uint32_t max_y) {
    if (groups == 0) return {0, 1};
    const std::uint64_t x = std::min<std::uint64_t>(groups, std::max(max_x, 1u));
    const std::uint64_t y = (groups + x - 1) / x;
    if (y > max_y) return {};
    return {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)};
}

void dispatchGroups(const graph::PassContext& pc, std::uint64_t groups, std::uint32_t max_x) {
    const std::uint32_t* limit = pc.device->properties.limits.maxComputeWorkGroupCount;
    const DispatchShape shape = dispatchShape(groups, std::min(max_x, limit[0]), limit[1]);
    // Never for vkcollide's counts (see the header); recording nothing would be silent, so
    // stop here in every build.
    if (shape.x == 0 && groups != 0) std::abort();
    if (shape.x == 0) return;
    pc.dispatch(shape.x, shape.y, 1);
}

void recordBlockScan(const graph::PassContext& pc, const vk::Pipeline& p, VkDeviceAddress frame, std::uint64_t blocks,
                     std::uint32_t max_x, std::uint32_t first_step, std::uint32_t level) {
    bindAndPush(pc, p, frame, 0, first_step, level);
    dispatchGroups(pc, blocks, max_x);
    pc.shaderBarrier();
    bindAndPush(pc, p, frame, 0, first_step + 1, level);
    pc.dispatch(1, 1, 1);
    pc.shaderBarrier();
    bindAndPush(pc, p, frame, 0, first_step + 2, level);
    dispatchGroups(pc, blocks, max_x);
    pc.shaderBarrier();
}

void dispatchGroups(const graph::PassContext& pc, std::uint64_t groups) {
    dispatchGroups(pc, groups, pc.device->properties.limits.maxComputeWorkGroupCount[0]);
}

void dispatchItems(const graph::PassContext& pc, std::uint64_t items, std::uint32_t size) {
    dispatchGroups(pc, (items + size - 1) / size);
}

void makeEngineWritesVisible(const graph::PassContext& pc) {
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    pc.pipelineBarrier(dep);
}

Result<void> makeCompute(vk::Device& device, vk::Pipeline& out, std::span<const std::uint32_t> spirv, const char* name) {
    auto p = vk::Pipeline::createCompute(device, spirv, {}, sizeof(gpu::Push), name);
    if (!p) return p.error();
    out = std::move(*p);
    return {};
}

}  // namespace vkcollide::passes
