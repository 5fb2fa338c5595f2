// CommandTape, replay: its words (graph/tape_words.hpp) read back into the same Vulkan calls
// with the same parameters, in order.
#include "graph/command_tape.hpp"

#include <bit>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "graph/tape_words.hpp"

namespace vkcollide::graph {

using namespace tape;

void CommandTape::replay(const vk::DeviceFunctions& f, VkCommandBuffer cmd, std::size_t from) {
    Reader in{words_.data() + from};
    const std::uint64_t* const end = words_.data() + words_.size();
    while (in.p < end) {
        switch (in.next()) {
            case kBindPipeline: {
                const auto point = static_cast<VkPipelineBindPoint>(in.next());
                f.vkCmdBindPipeline(cmd, point, in.nextHandle<VkPipeline>());
                break;
            }
            case kPushConstants: {
                const auto layout = in.nextHandle<VkPipelineLayout>();
                const std::uint64_t w = in.next();
                const auto size = static_cast<std::uint32_t>(in.next());
                f.vkCmdPushConstants(cmd, layout, lo(w), hi(w), size, in.p);  // the bytes, in place
                in.p += wordsFor(size);
                break;
            }
            case kPushDescriptorSet: {
                const std::uint64_t point_set = in.next();
                const auto layout = in.nextHandle<VkPipelineLayout>();
                const std::uint64_t count = in.next();
                writes_.clear();
                buffer_infos_.clear();
                image_infos_.clear();
                texel_views_.clear();
                // Infos first, pointers once every vector has its final size.
                struct Start {
                    DescriptorKind kind;
                    std::size_t first;
                };
                std::vector<Start> starts;
                for (std::uint64_t i = 0; i < count; ++i) {
                    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                    const std::uint64_t b = in.next(), c = in.next();
                    w.dstBinding = lo(b);
                    w.dstArrayElement = hi(b);
                    w.descriptorCount = lo(c);
                    w.descriptorType = static_cast<VkDescriptorType>(hi(c));
                    const DescriptorKind kind = kindOf(w.descriptorType);
                    starts.push_back({kind, kind == DescriptorKind::Buffer  ? buffer_infos_.size()
                                            : kind == DescriptorKind::Image ? image_infos_.size()
                                                                            : texel_views_.size()});
                    for (std::uint32_t e = 0; e < w.descriptorCount; ++e) {
                        if (kind == DescriptorKind::Buffer) {
                            const auto buffer = in.nextHandle<VkBuffer>();
                            const VkDeviceSize offset = in.next();
                            buffer_infos_.push_back({buffer, offset, in.next()});
                        } else if (kind == DescriptorKind::Image) {
                            const auto sampler = in.nextHandle<VkSampler>();
                            const auto view = in.nextHandle<VkImageView>();
                            image_infos_.push_back({sampler, view, static_cast<VkImageLayout>(in.next())});
                        } else {
                            texel_views_.push_back(in.nextHandle<VkBufferView>());
                        }
                    }
                    writes_.push_back(w);
                }
                for (std::size_t i = 0; i < writes_.size(); ++i) {
                    if (starts[i].kind == DescriptorKind::Buffer) writes_[i].pBufferInfo = buffer_infos_.data() + starts[i].first;
                    else if (starts[i].kind == DescriptorKind::Image) writes_[i].pImageInfo = image_infos_.data() + starts[i].first;
                    else writes_[i].pTexelBufferView = texel_views_.data() + starts[i].first;
                }
                f.vkCmdPushDescriptorSetKHR(cmd, static_cast<VkPipelineBindPoint>(lo(point_set)), layout, hi(point_set),
                                            static_cast<std::uint32_t>(writes_.size()), writes_.data());
                break;
            }
            case kDispatch: {
                const std::uint64_t xy = in.next();
                f.vkCmdDispatch(cmd, lo(xy), hi(xy), static_cast<std::uint32_t>(in.next()));
                break;
            }
            case kDispatchIndirect: {
                const auto buffer = in.nextHandle<VkBuffer>();
                f.vkCmdDispatchIndirect(cmd, buffer, in.next());
                break;
            }
            case kDraw: {
                const std::uint64_t a = in.next(), b = in.next();
                f.vkCmdDraw(cmd, lo(a), hi(a), lo(b), hi(b));
                break;
            }
            case kFillBuffer: {
                const auto buffer = in.nextHandle<VkBuffer>();
                const VkDeviceSize offset = in.next(), size = in.next();
                f.vkCmdFillBuffer(cmd, buffer, offset, size, static_cast<std::uint32_t>(in.next()));
                break;
            }
            case kCopyBuffer: {
                const auto src = in.nextHandle<VkBuffer>();
                const auto dst = in.nextHandle<VkBuffer>();
                const std::uint64_t count = in.next();
                copies_.clear();
                for (std::uint64_t i = 0; i < count; ++i) {
                    VkBufferCopy c{};
                    c.srcOffset = in.next();
                    c.dstOffset = in.next();
                    c.size = in.next();
                    copies_.push_back(c);
                }
                f.vkCmdCopyBuffer(cmd, src, dst, static_cast<std::uint32_t>(count), copies_.data());
                break;
            }
            case kPipelineBarrier: {
                const std::uint64_t a = in.next(), b = in.next();
                memory_barriers_.clear();
                buffer_barriers_.clear();
                image_barriers_.clear();
                const auto stages = [&in](auto& barrier) {
                    barrier.srcStageMask = in.next();
                    barrier.srcAccessMask = in.next();
                    barrier.dstStageMask = in.next();
                    barrier.dstAccessMask = in.next();
                };
                for (std::uint32_t i = 0; i < lo(a); ++i) {
                    VkMemoryBarrier2 m{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
                    stages(m);
                    memory_barriers_.push_back(m);
                }
                for (std::uint32_t i = 0; i < hi(a); ++i) {
                    VkBufferMemoryBarrier2 m{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
                    stages(m);
                    const std::uint64_t q = in.next();
                    m.srcQueueFamilyIndex = lo(q);
                    m.dstQueueFamilyIndex = hi(q);
                    m.buffer = in.nextHandle<VkBuffer>();
                    m.offset = in.next();
                    m.size = in.next();
                    buffer_barriers_.push_back(m);
                }
                for (std::uint32_t i = 0; i < lo(b); ++i) {
                    VkImageMemoryBarrier2 m{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
                    stages(m);
                    const std::uint64_t layouts = in.next(), q = in.next();
                    m.oldLayout = static_cast<VkImageLayout>(lo(layouts));
                    m.newLayout = static_cast<VkImageLayout>(hi(layouts));
                    m.srcQueueFamilyIndex = lo(q);
                    m.dstQueueFamilyIndex = hi(q);
                    m.image = in.nextHandle<VkImage>();
                    const std::uint64_t r0 = in.next(), r1 = in.next();
                    m.subresourceRange = {lo(r0), hi(r0), lo(r1), hi(r1), static_cast<std::uint32_t>(in.next())};
                    image_barriers_.push_back(m);
                }
                VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                d.dependencyFlags = hi(b);
                d.memoryBarrierCount = lo(a);
                d.pMemoryBarriers = memory_barriers_.data();
                d.bufferMemoryBarrierCount = hi(a);
                d.pBufferMemoryBarriers = buffer_barriers_.data();
                d.imageMemoryBarrierCount = lo(b);
                d.pImageMemoryBarriers = image_barriers_.data();
                f.vkCmdPipelineBarrier2(cmd, &d);
                break;
            }
            case kBeginRendering: {
                VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
                const std::uint64_t fl = in.next(), off = in.next(), ext = in.next(), vc = in.next(), ds = in.next();
                ri.flags = lo(fl);
                ri.layerCount = hi(fl);
                ri.renderArea = {{std::bit_cast<std::int32_t>(lo(off)), std::bit_cast<std::int32_t>(hi(off))}, {lo(ext), hi(ext)}};
                ri.viewMask = lo(vc);
                ri.colorAttachmentCount = hi(vc);
                const std::uint32_t total = hi(vc) + (lo(ds) ? 1 : 0) + (hi(ds) ? 1 : 0);
                attachments_.clear();
                for (std::uint32_t i = 0; i < total; ++i) {
                    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                    a.imageView = in.nextHandle<VkImageView>();
                    const std::uint64_t lr = in.next();
                    a.imageLayout = static_cast<VkImageLayout>(lo(lr));
                    a.resolveMode = static_cast<VkResolveModeFlagBits>(hi(lr));
                    a.resolveImageView = in.nextHandle<VkImageView>();
                    const std::uint64_t rl = in.next();
                    a.resolveImageLayout = static_cast<VkImageLayout>(lo(rl));
                    a.loadOp = static_cast<VkAttachmentLoadOp>(hi(rl));
                    a.storeOp = static_cast<VkAttachmentStoreOp>(in.next());
                    std::memcpy(&a.clearValue, in.p, sizeof a.clearValue);
                    in.p += wordsFor(sizeof a.clearValue);
                    attachments_.push_back(a);
                }
                ri.pColorAttachments = attachments_.data();
                std::uint32_t next = hi(vc);
                if (lo(ds)) ri.pDepthAttachment = &attachments_[next++];
                if (hi(ds)) ri.pStencilAttachment = &attachments_[next];
                f.vkCmdBeginRendering(cmd, &ri);
                break;
            }
            case kEndRendering: f.vkCmdEndRendering(cmd); break;
            case kSetViewport: {
                const std::uint64_t xy = in.next(), wh = in.next(), d = in.next();
                const auto fl = [](std::uint32_t u) { return std::bit_cast<float>(u); };
                const VkViewport v{fl(lo(xy)), fl(hi(xy)), fl(lo(wh)), fl(hi(wh)), fl(lo(d)), fl(hi(d))};
                f.vkCmdSetViewport(cmd, 0, 1, &v);
                break;
            }
            case kSetScissor: {
                const std::uint64_t off = in.next(), ext = in.next();
                const VkRect2D s{{std::bit_cast<std::int32_t>(lo(off)), std::bit_cast<std::int32_t>(hi(off))}, {lo(ext), hi(ext)}};
                f.vkCmdSetScissor(cmd, 0, 1, &s);
                break;
            }
            case kWriteTimestamp: {
                const VkPipelineStageFlags2 stage = in.next();
                const auto pool = in.nextHandle<VkQueryPool>();
                f.vkCmdWriteTimestamp2(cmd, stage, pool, static_cast<std::uint32_t>(in.next()));
                break;
            }
            case kSignalHost: {
                const auto event = in.nextHandle<VkEvent>();
                // The writes so far made visible to the host; the event's first scope holds
                // that barrier, so a host that sees it set reads what they wrote.
                VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
                to_host.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
                to_host.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
                to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
                to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
                VkDependencyInfo barrier{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                barrier.memoryBarrierCount = 1;
                barrier.pMemoryBarriers = &to_host;
                f.vkCmdPipelineBarrier2(cmd, &barrier);
                VkMemoryBarrier2 before{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
                before.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
                before.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
                VkDependencyInfo set{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                set.memoryBarrierCount = 1;
                set.pMemoryBarriers = &before;
                f.vkCmdSetEvent2(cmd, event, &set);
                break;
            }
            case kBeginLabel: {
                const std::uint64_t size = in.next();
                VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
                label.pLabelName = reinterpret_cast<const char*>(in.p);  // NUL-terminated in place
                in.p += wordsFor(size);
                f.vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
                break;
            }
            case kEndLabel: f.vkCmdEndDebugUtilsLabelEXT(cmd); break;
            default: std::abort();  // not a command: the tape is corrupt
        }
    }
}

}  // namespace vkcollide::graph
