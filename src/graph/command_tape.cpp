// CommandTape: each command is an opcode word followed by its fields, one 64-bit word
// each, or two 32-bit fields packed into one (pack()). Arrays follow their count.
#include "graph/command_tape.hpp"

#include <bit>
#include <cstdlib>
#include <cstring>
#include <type_traits>

namespace vkcollide::graph {
namespace {

enum Op : std::uint64_t {
    kBindPipeline = 1,
    kPushConstants,
    kPushDescriptorSet,
    kDispatch,
    kDispatchIndirect,
    kDraw,
    kFillBuffer,
    kCopyBuffer,
    kPipelineBarrier,
    kBeginRendering,
    kEndRendering,
    kSetViewport,
    kSetScissor,
    kWriteTimestamp,
};

template <class H>
std::uint64_t bits(H h) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<std::uintptr_t>(h);
    else return static_cast<std::uint64_t>(h);
}

template <class H>
H handle(std::uint64_t word) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<H>(static_cast<std::uintptr_t>(word));
    else return static_cast<H>(word);
}

std::uint64_t pack(std::uint32_t lo, std::uint32_t hi) { return std::uint64_t{lo} | std::uint64_t{hi} << 32; }
std::uint32_t lo(std::uint64_t w) { return static_cast<std::uint32_t>(w); }
std::uint32_t hi(std::uint64_t w) { return static_cast<std::uint32_t>(w >> 32); }
std::uint64_t packFloats(float a, float b) { return pack(std::bit_cast<std::uint32_t>(a), std::bit_cast<std::uint32_t>(b)); }

std::size_t wordsFor(std::size_t bytes) { return (bytes + 7) / 8; }

// Dropping a pNext would record something else than was asked: stop in every build.
void requireNoChain(const void* next) {
    if (next) std::abort();
}

enum class DescriptorKind { Buffer, Image, Texel };

DescriptorKind kindOf(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC:
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC: return DescriptorKind::Buffer;
        case VK_DESCRIPTOR_TYPE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT: return DescriptorKind::Image;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: return DescriptorKind::Texel;
        default: std::abort();  // inline uniforms and acceleration structures come in a pNext
    }
}

// Reads a tape's words in order.
struct Reader {
    const std::uint64_t* p;
    std::uint64_t next() { return *p++; }
    template <class H>
    H nextHandle() { return handle<H>(*p++); }
};

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
            default: std::abort();  // not a command: the tape is corrupt
        }
    }
}

}  // namespace vkcollide::graph
