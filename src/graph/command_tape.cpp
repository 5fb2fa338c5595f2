// CommandTape, recording: each call appends its command's words (graph/tape_words.hpp has
// the layout); replay is in command_tape_replay.cpp.
#include "graph/command_tape.hpp"

#include <cstdlib>
#include <cstring>

#include "graph/tape_words.hpp"

namespace vkcollide::graph {

using namespace tape;

namespace {

// Dropping a pNext would record something else than was asked: stop in every build.
void requireNoChain(const void* next) {
    if (next) std::abort();
}

}  // namespace

void CommandTape::putBytes(const void* bytes, std::size_t size) {
    const std::size_t at = words_.size();
    words_.resize(at + wordsFor(size), 0);  // the last word's unused bytes stay 0
    if (size) std::memcpy(words_.data() + at, bytes, size);
}

void CommandTape::bindPipeline(VkPipelineBindPoint bind_point, VkPipeline pipeline) {
    put(kBindPipeline);
    put(bind_point);
    put(bits(pipeline));
}

void CommandTape::pushConstants(VkPipelineLayout layout, VkShaderStageFlags stages, std::uint32_t offset,
                                std::uint32_t size, const void* values) {
    put(kPushConstants);
    put(bits(layout));
    put(pack(stages, offset));
    put(size);
    putBytes(values, size);
}

void CommandTape::pushDescriptorSet(VkPipelineBindPoint bind_point, VkPipelineLayout layout, std::uint32_t set,
                                    std::span<const VkWriteDescriptorSet> writes) {
    put(kPushDescriptorSet);
    put(pack(bind_point, set));
    put(bits(layout));
    put(writes.size());
    for (const VkWriteDescriptorSet& w : writes) {
        requireNoChain(w.pNext);
        put(pack(w.dstBinding, w.dstArrayElement));
        put(pack(w.descriptorCount, w.descriptorType));
        for (std::uint32_t i = 0; i < w.descriptorCount; ++i) {
            switch (kindOf(w.descriptorType)) {
                case DescriptorKind::Buffer:
                    put(bits(w.pBufferInfo[i].buffer));
                    put(w.pBufferInfo[i].offset);
                    put(w.pBufferInfo[i].range);
                    break;
                case DescriptorKind::Image:
                    put(bits(w.pImageInfo[i].sampler));
                    put(bits(w.pImageInfo[i].imageView));
                    put(w.pImageInfo[i].imageLayout);
                    break;
                case DescriptorKind::Texel: put(bits(w.pTexelBufferView[i])); break;
            }
        }
    }
}

void CommandTape::dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    put(kDispatch);
    put(pack(x, y));
    put(z);
}

void CommandTape::dispatchIndirect(VkBuffer buffer, VkDeviceSize offset) {
    put(kDispatchIndirect);
    put(bits(buffer));
    put(offset);
}

void CommandTape::draw(std::uint32_t vertices, std::uint32_t instances, std::uint32_t first_vertex,
                       std::uint32_t first_instance) {
    put(kDraw);
    put(pack(vertices, instances));
    put(pack(first_vertex, first_instance));
}

void CommandTape::fillBuffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, std::uint32_t data) {
    put(kFillBuffer);
    put(bits(buffer));
    put(offset);
    put(size);
    put(data);
}

void CommandTape::copyBuffer(VkBuffer src, VkBuffer dst, std::span<const VkBufferCopy> regions) {
    put(kCopyBuffer);
    put(bits(src));
    put(bits(dst));
    put(regions.size());
    for (const VkBufferCopy& r : regions) {
        put(r.srcOffset);
        put(r.dstOffset);
        put(r.size);
    }
}

void CommandTape::pipelineBarrier(const VkDependencyInfo& d) {
    requireNoChain(d.pNext);
    put(kPipelineBarrier);
    put(pack(d.memoryBarrierCount, d.bufferMemoryBarrierCount));
    put(pack(d.imageMemoryBarrierCount, d.dependencyFlags));
    const auto stages = [this](const auto& b) {
        requireNoChain(b.pNext);
        put(b.srcStageMask);
        put(b.srcAccessMask);
        put(b.dstStageMask);
        put(b.dstAccessMask);
    };
    for (std::uint32_t i = 0; i < d.memoryBarrierCount; ++i) stages(d.pMemoryBarriers[i]);
    for (std::uint32_t i = 0; i < d.bufferMemoryBarrierCount; ++i) {
        const VkBufferMemoryBarrier2& b = d.pBufferMemoryBarriers[i];
        stages(b);
        put(pack(b.srcQueueFamilyIndex, b.dstQueueFamilyIndex));
        put(bits(b.buffer));
        put(b.offset);
        put(b.size);
    }
    for (std::uint32_t i = 0; i < d.imageMemoryBarrierCount; ++i) {
        const VkImageMemoryBarrier2& b = d.pImageMemoryBarriers[i];
        stages(b);
        put(pack(b.oldLayout, b.newLayout));
        put(pack(b.srcQueueFamilyIndex, b.dstQueueFamilyIndex));
        put(bits(b.image));
        const VkImageSubresourceRange& r = b.subresourceRange;
        put(pack(r.aspectMask, r.baseMipLevel));
        put(pack(r.levelCount, r.baseArrayLayer));
        put(r.layerCount);
    }
}

void CommandTape::beginRendering(const VkRenderingInfo& info) {
    requireNoChain(info.pNext);
    put(kBeginRendering);
    put(pack(info.flags, info.layerCount));
    put(pack(std::bit_cast<std::uint32_t>(info.renderArea.offset.x), std::bit_cast<std::uint32_t>(info.renderArea.offset.y)));
    put(pack(info.renderArea.extent.width, info.renderArea.extent.height));
    put(pack(info.viewMask, info.colorAttachmentCount));
    put(pack(info.pDepthAttachment != nullptr, info.pStencilAttachment != nullptr));
    const auto attachment = [this](const VkRenderingAttachmentInfo& a) {
        requireNoChain(a.pNext);
        put(bits(a.imageView));
        put(pack(a.imageLayout, a.resolveMode));
        put(bits(a.resolveImageView));
        put(pack(a.resolveImageLayout, a.loadOp));
        put(a.storeOp);
        putBytes(&a.clearValue, sizeof a.clearValue);
    };
    for (std::uint32_t i = 0; i < info.colorAttachmentCount; ++i) attachment(info.pColorAttachments[i]);
    if (info.pDepthAttachment) attachment(*info.pDepthAttachment);
    if (info.pStencilAttachment) attachment(*info.pStencilAttachment);
}

void CommandTape::endRendering() { put(kEndRendering); }

void CommandTape::setViewport(const VkViewport& v) {
    put(kSetViewport);
    put(packFloats(v.x, v.y));
    put(packFloats(v.width, v.height));
    put(packFloats(v.minDepth, v.maxDepth));
}

void CommandTape::setScissor(const VkRect2D& s) {
    put(kSetScissor);
    put(pack(std::bit_cast<std::uint32_t>(s.offset.x), std::bit_cast<std::uint32_t>(s.offset.y)));
    put(pack(s.extent.width, s.extent.height));
}

void CommandTape::writeTimestamp(VkPipelineStageFlags2 stage, VkQueryPool pool, std::uint32_t query) {
    put(kWriteTimestamp);
    put(stage);
    put(bits(pool));
    put(query);
}

void CommandTape::signalHost(VkEvent event) {
    put(kSignalHost);
    put(bits(event));
    ++signals_;
}

void CommandTape::beginLabel(std::string_view prefix, std::string_view name) {
    put(kBeginLabel);
    const std::size_t size = prefix.size() + name.size() + 1;
    put(size);
    const std::size_t at = words_.size();
    words_.resize(at + wordsFor(size), 0);  // the NUL and the last word's unused bytes stay 0
    auto* text = reinterpret_cast<char*>(words_.data() + at);
    if (!prefix.empty()) std::memcpy(text, prefix.data(), prefix.size());
    if (!name.empty()) std::memcpy(text + prefix.size(), name.data(), name.size());
}

void CommandTape::endLabel() { put(kEndLabel); }

}  // namespace vkcollide::graph
