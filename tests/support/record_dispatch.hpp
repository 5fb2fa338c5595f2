// One compute dispatch recorded in a graph pass, as the tests that run one shader pass
// alone record it: bind the pipeline, push the constants, dispatch.
#pragma once

#include <cstdint>

#include "graph/pass_context.hpp"

namespace vkcollide::test {

template <class Push>
void recordDispatch(graph::PassContext& pc, VkPipeline pipeline, VkPipelineLayout layout, const Push& push, std::uint32_t groups = 1) {
    pc.fns().vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    pc.fns().vkCmdPushConstants(pc.cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    pc.fns().vkCmdDispatch(pc.cmd, groups, 1, 1);
}

}  // namespace vkcollide::test
