#include "graph/use_info.hpp"

namespace vkcollide::graph {
namespace {

VkPipelineStageFlags2 shaderStages(PassKind kind) {
    return kind == PassKind::Raster ? (VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT)
                                    : VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
}

}  // namespace

UseInfo describe(Use use, PassKind kind) {
    const VkPipelineStageFlags2 shader = shaderStages(kind);
    switch (use) {
        case Use::ColorAttachment:
            return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0, true};
        case Use::DepthAttachment:
            return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, 0, true};
        case Use::Sampled:
            return {shader, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_IMAGE_USAGE_SAMPLED_BIT, 0, false};
        case Use::StorageRead:
            return {shader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_USAGE_STORAGE_BIT,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false};
        case Use::StorageWrite:
            return {shader, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_USAGE_STORAGE_BIT,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true};
        case Use::StorageReadWrite:
            return {shader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_USAGE_STORAGE_BIT, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true};
        case Use::IndirectRead:
            return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, 0, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, false};
        case Use::TransferSrc:
            return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false};
        case Use::TransferDst:
            return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                    VK_BUFFER_USAGE_TRANSFER_DST_BIT, true};
    }
    return {};
}

const char* toString(Use use) noexcept {
    switch (use) {
        case Use::ColorAttachment: return "color attachment";
        case Use::DepthAttachment: return "depth attachment";
        case Use::Sampled: return "sampled";
        case Use::StorageRead: return "storage read";
        case Use::StorageWrite: return "storage write";
        case Use::StorageReadWrite: return "storage read-write";
        case Use::IndirectRead: return "indirect";
        case Use::TransferSrc: return "transfer source";
        case Use::TransferDst: return "transfer destination";
    }
    return "?";
}

bool isWrite(Use use) noexcept { return describe(use, PassKind::Compute).write; }

}  // namespace vkcollide::graph
