// CommandTape on the host: equal commands give equal tapes, any changed parameter a
// different one, and replay() makes exactly the recorded calls (through a table of
// functions that log what they get, no device).
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "graph/command_tape.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;

namespace {

template <class H>
H fakeHandle(std::uintptr_t value) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<H>(value);
    else return static_cast<H>(value);
}

// What the fake vkCmd* functions saw, one line per call.
std::vector<std::string>& calls() {
    static std::vector<std::string> log;
    return log;
}

std::string h(const void* p) { return std::to_string(reinterpret_cast<std::uintptr_t>(p)); }

vk::DeviceFunctions loggingTable() {
    vk::DeviceFunctions f{};
    f.vkCmdBindPipeline = [](VkCommandBuffer, VkPipelineBindPoint point, VkPipeline p) {
        calls().push_back("bind " + std::to_string(point) + " " + h(p));
    };
    f.vkCmdPushConstants = [](VkCommandBuffer, VkPipelineLayout layout, VkShaderStageFlags stages, std::uint32_t offset,
                              std::uint32_t size, const void* values) {
        std::string bytes;
        for (std::uint32_t i = 0; i < size; ++i) bytes += std::to_string(static_cast<const unsigned char*>(values)[i]) + ",";
        calls().push_back("push " + h(layout) + " " + std::to_string(stages) + " " + std::to_string(offset) + " " + bytes);
    };
    f.vkCmdPushDescriptorSetKHR = [](VkCommandBuffer, VkPipelineBindPoint, VkPipelineLayout, std::uint32_t set,
                                     std::uint32_t count, const VkWriteDescriptorSet* writes) {
        std::string s = "descriptors set " + std::to_string(set);
        for (std::uint32_t i = 0; i < count; ++i) {
            const VkWriteDescriptorSet& w = writes[i];
            s += " [" + std::to_string(w.dstBinding) + " " + std::to_string(w.descriptorType);
            for (std::uint32_t e = 0; e < w.descriptorCount; ++e)
                s += w.pImageInfo ? " view " + h(w.pImageInfo[e].imageView) + " layout " + std::to_string(w.pImageInfo[e].imageLayout)
                                  : " buffer " + h(w.pBufferInfo[e].buffer) + " " + std::to_string(w.pBufferInfo[e].offset) +
                                        " " + std::to_string(w.pBufferInfo[e].range);
            s += "]";
        }
        calls().push_back(s);
    };
    f.vkCmdBeginDebugUtilsLabelEXT = [](VkCommandBuffer, const VkDebugUtilsLabelEXT* label) {
        calls().push_back(std::string("label ") + label->pLabelName);
    };
    f.vkCmdEndDebugUtilsLabelEXT = [](VkCommandBuffer) { calls().emplace_back("end label"); };
    f.vkCmdDispatch = [](VkCommandBuffer, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        calls().push_back("dispatch " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z));
    };
    f.vkCmdDispatchIndirect = [](VkCommandBuffer, VkBuffer b, VkDeviceSize offset) {
        calls().push_back("indirect " + h(b) + " " + std::to_string(offset));
    };
    f.vkCmdDraw = [](VkCommandBuffer, std::uint32_t v, std::uint32_t i, std::uint32_t fv, std::uint32_t fi) {
        calls().push_back("draw " + std::to_string(v) + " " + std::to_string(i) + " " + std::to_string(fv) + " " + std::to_string(fi));
    };
    f.vkCmdFillBuffer = [](VkCommandBuffer, VkBuffer b, VkDeviceSize offset, VkDeviceSize size, std::uint32_t data) {
        calls().push_back("fill " + h(b) + " " + std::to_string(offset) + " " + std::to_string(size) + " " + std::to_string(data));
    };
    f.vkCmdCopyBuffer = [](VkCommandBuffer, VkBuffer src, VkBuffer dst, std::uint32_t count, const VkBufferCopy* r) {
        std::string s = "copy " + h(src) + " " + h(dst);
        for (std::uint32_t i = 0; i < count; ++i)
            s += " " + std::to_string(r[i].srcOffset) + ">" + std::to_string(r[i].dstOffset) + ":" + std::to_string(r[i].size);
        calls().push_back(s);
    };
    f.vkCmdPipelineBarrier2 = [](VkCommandBuffer, const VkDependencyInfo* d) {
        std::string s = "barrier";
        for (std::uint32_t i = 0; i < d->memoryBarrierCount; ++i)
            s += " mem " + std::to_string(d->pMemoryBarriers[i].srcStageMask) + ">" + std::to_string(d->pMemoryBarriers[i].dstAccessMask);
        for (std::uint32_t i = 0; i < d->bufferMemoryBarrierCount; ++i) {
            const VkBufferMemoryBarrier2& b = d->pBufferMemoryBarriers[i];
            s += " buf " + h(b.buffer) + " " + std::to_string(b.dstStageMask) + " " + std::to_string(b.size) + " q" +
                 std::to_string(b.srcQueueFamilyIndex);
        }
        for (std::uint32_t i = 0; i < d->imageMemoryBarrierCount; ++i) {
            const VkImageMemoryBarrier2& b = d->pImageMemoryBarriers[i];
            s += " img " + h(b.image) + " " + std::to_string(b.oldLayout) + ">" + std::to_string(b.newLayout) + " mips " +
                 std::to_string(b.subresourceRange.baseMipLevel) + "+" + std::to_string(b.subresourceRange.levelCount);
        }
        calls().push_back(s);
    };
    f.vkCmdBeginRendering = [](VkCommandBuffer, const VkRenderingInfo* ri) {
        std::string s = "rendering " + std::to_string(ri->renderArea.extent.width) + "x" + std::to_string(ri->renderArea.extent.height);
        for (std::uint32_t i = 0; i < ri->colorAttachmentCount; ++i)
            s += " color " + h(ri->pColorAttachments[i].imageView) + " clear " + std::to_string(ri->pColorAttachments[i].clearValue.color.uint32[0]);
        if (ri->pDepthAttachment)
            s += " depth " + h(ri->pDepthAttachment->imageView) + " clear " + std::to_string(ri->pDepthAttachment->clearValue.depthStencil.depth);
        calls().push_back(s);
    };
    f.vkCmdEndRendering = [](VkCommandBuffer) { calls().push_back("end rendering"); };
    f.vkCmdSetViewport = [](VkCommandBuffer, std::uint32_t, std::uint32_t, const VkViewport* v) {
        calls().push_back("viewport " + std::to_string(v->width) + " " + std::to_string(v->maxDepth));
    };
    f.vkCmdSetScissor = [](VkCommandBuffer, std::uint32_t, std::uint32_t, const VkRect2D* r) {
        calls().push_back("scissor " + std::to_string(r->offset.x) + " " + std::to_string(r->extent.height));
    };
    f.vkCmdWriteTimestamp2 = [](VkCommandBuffer, VkPipelineStageFlags2 stage, VkQueryPool pool, std::uint32_t q) {
        calls().push_back("timestamp " + std::to_string(stage) + " " + h(pool) + " " + std::to_string(q));
    };
    return f;
}

// A pass's worth of commands with a push constant's `object` and the dispatch's `x` as
// parameters. The push constants are 12 bytes: the tape keeps that size, not a padded one.
void recordSample(CommandTape& t, std::uint32_t object, std::uint32_t x, VkBuffer buffer) {
    t.bindPipeline(VK_PIPELINE_BIND_POINT_COMPUTE, fakeHandle<VkPipeline>(0x10));
    std::byte push[12];
    const std::uint64_t address = 0x1000;
    std::memcpy(push, &address, 8);
    std::memcpy(push + 8, &object, 4);
    t.pushConstants(fakeHandle<VkPipelineLayout>(0x20), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
    t.dispatch(x, 1, 1);
    t.fillBuffer(buffer, 0, 16, 0);
}

}  // namespace

TEST_CASE("equal commands give equal tapes, and a changed push constant, dispatch size or buffer a different one", "[graph][tape]") {
    const VkBuffer a = fakeHandle<VkBuffer>(0x30), b = fakeHandle<VkBuffer>(0x31);
    CommandTape first, same, other;
    recordSample(first, 1, 8, a);
    recordSample(same, 1, 8, a);
    CHECK(first == same);
    CHECK(!first.empty());
    recordSample(other, 2, 8, a);
    CHECK_FALSE(first == other);
    other.clear();
    recordSample(other, 1, 9, a);
    CHECK_FALSE(first == other);
    other.clear();
    recordSample(other, 1, 8, b);
    CHECK_FALSE(first == other);
    // A command more, or one fewer, is a different tape too.
    other.clear();
    recordSample(other, 1, 8, a);
    other.dispatch(1, 1, 1);
    CHECK_FALSE(first == other);
    other.clear();
    CHECK_FALSE(first == other);
}

TEST_CASE("barriers are compared field by field, not by their pointers", "[graph][tape]") {
    const auto tape = [](VkAccessFlags2 dst_access, VkImageLayout new_layout) {
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        mb.dstAccessMask = dst_access;
        VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        ib.image = fakeHandle<VkImage>(0x40);
        ib.newLayout = new_layout;
        ib.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        d.memoryBarrierCount = 1;
        d.pMemoryBarriers = &mb;
        d.imageMemoryBarrierCount = 1;
        d.pImageMemoryBarriers = &ib;
        CommandTape t;
        t.pipelineBarrier(d);  // the structs go out of scope here: the tape keeps copies
        return t;
    };
    CHECK(tape(VK_ACCESS_2_SHADER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL) == tape(VK_ACCESS_2_SHADER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL));
    CHECK_FALSE(tape(VK_ACCESS_2_SHADER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL) == tape(VK_ACCESS_2_SHADER_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL));
    CHECK_FALSE(tape(VK_ACCESS_2_SHADER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL) ==
                tape(VK_ACCESS_2_SHADER_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
}

TEST_CASE("replay makes the recorded calls with the recorded parameters, in order, from any position", "[graph][tape]") {
    const vk::DeviceFunctions f = loggingTable();
    const VkCommandBuffer cmd = fakeHandle<VkCommandBuffer>(0x1);
    CommandTape t;
    recordSample(t, 7, 3, fakeHandle<VkBuffer>(0x30));

    VkDescriptorImageInfo ii{VK_NULL_HANDLE, fakeHandle<VkImageView>(0x50), VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo bi[2] = {{fakeHandle<VkBuffer>(0x31), 0, 64}, {fakeHandle<VkBuffer>(0x32), 16, 32}};
    VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    w[0].dstBinding = 0;
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w[0].pImageInfo = &ii;
    w[1].dstBinding = 1;
    w[1].descriptorCount = 2;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[1].pBufferInfo = bi;
    t.pushDescriptorSet(VK_PIPELINE_BIND_POINT_COMPUTE, fakeHandle<VkPipelineLayout>(0x20), 0, w);

    VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    bb.buffer = fakeHandle<VkBuffer>(0x33);
    bb.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    bb.size = VK_WHOLE_SIZE;
    bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    ib.image = fakeHandle<VkImage>(0x40);
    ib.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    ib.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    ib.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 2, 3, 0, 1};
    VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    d.bufferMemoryBarrierCount = 1;
    d.pBufferMemoryBarriers = &bb;
    d.imageMemoryBarrierCount = 1;
    d.pImageMemoryBarriers = &ib;
    t.pipelineBarrier(d);
    const std::size_t mid = t.size();

    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO}, depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = fakeHandle<VkImageView>(0x51);
    color.clearValue.color.uint32[0] = 9;
    depth.imageView = fakeHandle<VkImageView>(0x52);
    depth.clearValue.depthStencil.depth = 1.0f;
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {64, 32}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &color;
    ri.pDepthAttachment = &depth;
    t.beginRendering(ri);
    t.setViewport({0, 0, 64, 32, 0, 1});
    t.setScissor({{0, 0}, {64, 32}});
    t.draw(6, 1, 0, 0);
    t.endRendering();
    const VkBufferCopy regions[2] = {{0, 8, 4}, {16, 0, 8}};
    t.copyBuffer(fakeHandle<VkBuffer>(0x34), fakeHandle<VkBuffer>(0x35), regions);
    t.dispatchIndirect(fakeHandle<VkBuffer>(0x36), 24);
    t.writeTimestamp(VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, fakeHandle<VkQueryPool>(0x60), 5);

    calls().clear();
    t.replay(f, cmd);
    const std::vector<std::string> all = calls();
    const std::vector<std::string> expected = {
        "bind 1 16",
        "push 32 32 0 0,16,0,0,0,0,0,0,7,0,0,0,",
        "dispatch 3 1 1",
        "fill 48 0 16 0",
        "descriptors set 0 [0 3 view 80 layout 1] [1 7 buffer 49 0 64 buffer 50 16 32]",
        "barrier buf 51 " + std::to_string(VK_PIPELINE_STAGE_2_COPY_BIT) + " " + std::to_string(VK_WHOLE_SIZE) + " q" +
            std::to_string(VK_QUEUE_FAMILY_IGNORED) + " img 64 0>1 mips 2+3",
        "rendering 64x32 color 81 clear 9 depth 82 clear 1.000000",
        "viewport 64.000000 1.000000",
        "scissor 0 32",
        "draw 6 1 0 0",
        "end rendering",
        "copy 52 53 0>8:4 16>0:8",
        "indirect 54 24",
        "timestamp " + std::to_string(VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT) + " 96 5",
    };
    CHECK(all == expected);

    // From a position taken between commands: only what came after it.
    calls().clear();
    t.replay(f, cmd, mid);
    CHECK(calls() == std::vector<std::string>(expected.begin() + 6, expected.end()));
    calls().clear();
    t.replay(f, cmd, t.size());
    CHECK(calls().empty());
}

TEST_CASE("labels are tape commands: compared by their text, replayed in place around the commands they hold", "[graph][tape]") {
    const auto tape = [](std::string_view name) {
        CommandTape t;
        t.beginLabel("vkcollide: ", name);
        t.dispatch(1, 1, 1);
        t.endLabel();
        return t;
    };
    CHECK(tape("cells-sweep") == tape("cells-sweep"));
    CHECK_FALSE(tape("cells-sweep") == tape("cells-fill"));
    // Names of every length up to two words of text, so the NUL lands in every byte of a word.
    for (std::size_t n = 0; n <= 16; ++n) {
        const std::string name(n, 'x');
        const vk::DeviceFunctions f = loggingTable();
        CommandTape t = tape(name);
        calls().clear();
        t.replay(f, fakeHandle<VkCommandBuffer>(0x10));
        CHECK(calls() == std::vector<std::string>{"label vkcollide: " + name, "dispatch 1 1 1", "end label"});
    }
}
