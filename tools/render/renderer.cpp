#include "render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "highlight_box_comp.h"
#include "render.h"
#include "render_frag.h"
#include "render_vert.h"

namespace render {
namespace {

constexpr VkFormat kColourFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

using vkcollide::Float3;

Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
float dot(Float3 a, Float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Float3 cross(Float3 a, Float3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Float3 normalize(Float3 a) {
    const float l = std::sqrt(dot(a, a));
    return l > 0 ? Float3{a.x / l, a.y / l, a.z / l} : a;
}

// Projection * view, column-major, for Vulkan's clip space (y down, depth 0..1).
gpu::mat4 viewProjection(const Camera& c, float aspect) {
    const Float3 z = normalize(sub(c.eye, c.target));
    const Float3 x = normalize(cross(c.up, z));
    const Float3 y = cross(z, x);
    const float view[4][4] = {{x.x, x.y, x.z, -dot(x, c.eye)},
                              {y.x, y.y, y.z, -dot(y, c.eye)},
                              {z.x, z.y, z.z, -dot(z, c.eye)},
                              {0, 0, 0, 1}};
    const float f = 1.0f / std::tan(c.fov_degrees * 3.14159265f / 360.0f);
    const float n = c.near_plane, fa = c.far_plane;
    const float proj[4][4] = {{f / aspect, 0, 0, 0}, {0, -f, 0, 0}, {0, 0, fa / (n - fa), n * fa / (n - fa)}, {0, 0, -1, 0}};
    gpu::mat4 out{};
    for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 4; ++col) {
            float s = 0;
            for (int k = 0; k < 4; ++k) s += proj[r][k] * view[k][col];
            out.m[col * 4 + r] = s;
        }
    return out;
}

}  // namespace

Rgb objectColour(std::size_t index) {
    static const Rgb kPalette[] = {{0.45f, 0.62f, 0.85f}, {0.55f, 0.78f, 0.52f}, {0.72f, 0.60f, 0.85f}, {0.85f, 0.80f, 0.55f},
                                   {0.50f, 0.78f, 0.78f}, {0.80f, 0.62f, 0.72f}, {0.62f, 0.66f, 0.70f}, {0.70f, 0.78f, 0.45f}};
    return kPalette[index % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

Renderer::Renderer(Engine& engine, std::uint32_t width, std::uint32_t height)
    : engine_(engine), width_(width), height_(height) {
    VkDevice dev = engine_.device();
    auto make_image = [&](VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage& image,
                          VkDeviceMemory& memory, VkImageView& view) {
        VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ici.imageType = VK_IMAGE_TYPE_2D;
        ici.format = format;
        ici.extent = {width_, height_, 1};
        ici.mipLevels = ici.arrayLayers = 1;
        ici.samples = VK_SAMPLE_COUNT_1_BIT;
        ici.tiling = VK_IMAGE_TILING_OPTIMAL;
        ici.usage = usage;
        check(vkCreateImage(dev, &ici, nullptr, &image), "vkCreateImage");
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(dev, image, &req);
        memory = engine_.allocate(req, Memory::Device);
        check(vkBindImageMemory(dev, image, memory, 0), "vkBindImageMemory");
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = image;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = format;
        vci.subresourceRange = {aspect, 0, 1, 0, 1};
        check(vkCreateImageView(dev, &vci, nullptr, &view), "vkCreateImageView");
    };
    make_image(kColourFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
               colour_, colour_memory_, colour_view_);
    make_image(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, depth_, depth_memory_,
               depth_view_);
    readback_ = engine_.createBuffer(VkDeviceSize{width_} * height_ * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Host);

    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(gpu::RenderPush)};
    VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    lci.pushConstantRangeCount = 1;
    lci.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(dev, &lci, nullptr, &layout_), "vkCreatePipelineLayout");

    pipeline_ = createPipeline(true);
    // The highlighted triangles again, on top: no depth test.
    hot_pipeline_ = createPipeline(false);
    box_pipeline_ = engine_.createComputePipeline(kHighlightBoxComp, sizeof(gpu::BoxPush));
    box_words_ = engine_.createBuffer(6 * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
}

VkPipeline Renderer::createPipeline(bool depth_tested) {
    VkDevice dev = engine_.device();
    VkShaderModule vert = engine_.createShaderModule(kRenderVert);
    VkShaderModule frag = engine_.createShaderModule(kRenderFrag);
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = ds.depthWriteEnable = depth_tested ? VK_TRUE : VK_FALSE;
    ds.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = 1;
    cb.pAttachments = &blend;
    const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = 2;
    dyn.pDynamicStates = dynamic;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &kColourFormat;
    rendering.depthAttachmentFormat = kDepthFormat;
    VkGraphicsPipelineCreateInfo pci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    pci.pNext = &rendering;
    pci.stageCount = 2;
    pci.pStages = stages;
    pci.pVertexInputState = &vin;
    pci.pInputAssemblyState = &ia;
    pci.pViewportState = &vp;
    pci.pRasterizationState = &rs;
    pci.pMultisampleState = &ms;
    pci.pDepthStencilState = &ds;
    pci.pColorBlendState = &cb;
    pci.pDynamicState = &dyn;
    pci.layout = layout_;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline), "vkCreateGraphicsPipelines");
    vkDestroyShaderModule(dev, vert, nullptr);
    vkDestroyShaderModule(dev, frag, nullptr);
    return pipeline;
}

Renderer::~Renderer() {
    VkDevice dev = engine_.device();
    vkDeviceWaitIdle(dev);
    for (Draw& d : draws_) {
        engine_.destroy(d.own_vertices);
        engine_.destroy(d.own_indices);
        engine_.destroy(d.highlights);
    }
    engine_.destroy(readback_);
    engine_.destroy(params_);
    engine_.destroy(box_words_);
    engine_.destroy(box_pipeline_);
    vkDestroyPipeline(dev, pipeline_, nullptr);
    vkDestroyPipeline(dev, hot_pipeline_, nullptr);
    vkDestroyPipelineLayout(dev, layout_, nullptr);
    vkDestroyImageView(dev, colour_view_, nullptr);
    vkDestroyImageView(dev, depth_view_, nullptr);
    vkDestroyImage(dev, colour_, nullptr);
    vkDestroyImage(dev, depth_, nullptr);
    vkFreeMemory(dev, colour_memory_, nullptr);
    vkFreeMemory(dev, depth_memory_, nullptr);
}

DrawId Renderer::addDraw(Draw draw) {
    const VkDeviceSize words = (draw.triangles + 31) / 32;
    draw.highlights = engine_.createBuffer(words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
    std::memset(draw.highlights.mapped, 0, words * 4);
    draws_.push_back(draw);
    return static_cast<DrawId>(draws_.size() - 1);
}

DrawId Renderer::addMesh(const vkcollide::HostMesh& mesh, Rgb colour, bool dynamic) {
    Draw d;
    uploadMesh(d, mesh, dynamic);
    d.colour = colour;
    return addDraw(d);
}

void Renderer::uploadMesh(Draw& d, const vkcollide::HostMesh& mesh, bool dynamic) {
    const VkDeviceSize vbytes = mesh.positions.size() * sizeof(Float3), ibytes = mesh.indices.size() * 4;
    d.own_vertices = engine_.createBuffer(vbytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, dynamic ? Memory::Host : Memory::Device);
    if (dynamic) std::memcpy(d.own_vertices.mapped, mesh.positions.data(), vbytes);
    else engine_.upload(d.own_vertices, mesh.positions.data(), vbytes);
    d.own_indices = engine_.createBuffer(ibytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Device);
    engine_.upload(d.own_indices, mesh.indices.data(), ibytes);
    d.vertices = d.own_vertices.address;
    d.indices = d.own_indices.address;
    d.triangles = static_cast<std::uint32_t>(mesh.triangleCount());
}

void Renderer::replaceMesh(DrawId id, const vkcollide::HostMesh& mesh) {
    Draw& d = draws_.at(id);
    if (!d.own_indices.buffer) die("Renderer::replaceMesh: draw " + std::to_string(id) + " was not added with addMesh");
    // No frame still reads them: render() waits for its submission (Engine::submit).
    engine_.destroy(d.own_vertices);
    engine_.destroy(d.own_indices);
    engine_.destroy(d.highlights);
    uploadMesh(d, mesh, false);
    const VkDeviceSize words = (d.triangles + 31) / 32;
    d.highlights = engine_.createBuffer(words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
    std::memset(d.highlights.mapped, 0, words * 4);
}

DrawId Renderer::addInstance(DrawId of, Rgb colour) {
    const Draw& source = draws_.at(of);
    Draw d;
    d.vertices = source.vertices;
    d.indices = source.indices;
    d.first_float = source.first_float;
    d.stride_floats = source.stride_floats;
    d.triangles = source.triangles;
    d.colour = colour;
    return addDraw(d);
}

DrawId Renderer::addGpuMesh(const Buffer& vertices, VkDeviceSize offset, std::uint32_t stride, const Buffer& indices,
                            VkDeviceSize index_offset, std::uint32_t triangle_count, Rgb colour) {
    Draw d;
    d.vertices = vertices.address;
    d.first_float = static_cast<std::uint32_t>(offset / 4);
    d.stride_floats = stride / 4;
    d.indices = indices.address + index_offset;
    d.triangles = triangle_count;
    d.colour = colour;
    return addDraw(d);
}

void Renderer::updateVertices(DrawId id, std::span<const Float3> positions) {
    Draw& d = draws_.at(id);
    if (!d.own_vertices.mapped || positions.size_bytes() > d.own_vertices.size)
        die("Renderer::updateVertices: draw " + std::to_string(id) + " is not a dynamic mesh of that size");
    std::memcpy(d.own_vertices.mapped, positions.data(), positions.size_bytes());
}

void Renderer::setTransform(DrawId id, const vkcollide::Transform3x4& object_to_world) { draws_.at(id).transform = object_to_world; }

void Renderer::clearHighlights() {
    for (Draw& d : draws_) {
        std::memset(d.highlights.mapped, 0, d.highlights.size);
        d.hot = 0;
    }
}

void Renderer::highlight(DrawId id, std::uint32_t triangle) {
    Draw& d = draws_.at(id);
    if (triangle >= d.triangles) return;
    std::uint32_t& word = static_cast<std::uint32_t*>(d.highlights.mapped)[triangle / 32];
    const std::uint32_t bit = 1u << (triangle % 32);
    if (!(word & bit)) ++d.hot;
    word |= bit;
}

std::optional<Box> Renderer::highlightBox() {
    bool any = false;
    for (const Draw& d : draws_) any = any || d.hot > 0;
    if (!any) return std::nullopt;
    writeParams(Camera{});
    auto* words = static_cast<std::uint32_t*>(box_words_.mapped);
    for (int a = 0; a < 3; ++a) words[a] = ~0u, words[a + 3] = 0;
    engine_.submit([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, box_pipeline_.pipeline);
        for (std::size_t i = 0; i < draws_.size(); ++i) {
            if (draws_[i].hot == 0) continue;
            const gpu::BoxPush push{params_.address + sizeof(gpu::FrameParams) + i * sizeof(gpu::DrawParams), box_words_.address,
                                    draws_[i].triangles};
            vkCmdPushConstants(cmd, box_pipeline_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, (draws_[i].triangles + 63) / 64, 1, 1);
        }
        VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        to_host.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        to_host.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &to_host;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    // Back from the order-preserving uint (highlight_box.comp) to the float.
    auto value = [&](int slot) {
        const std::uint32_t u = words[slot];
        const std::uint32_t bits = (u & 0x80000000u) ? u & 0x7fffffffu : ~u;
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    };
    if (words[0] == ~0u) return std::nullopt;  // every corner was NaN or infinite
    return Box{{value(0), value(1), value(2)}, {value(3), value(4), value(5)}};
}

void Renderer::writeParams(const Camera& camera) {
    const VkDeviceSize need = sizeof(gpu::FrameParams) + draws_.size() * sizeof(gpu::DrawParams);
    if (params_.size < need) {
        engine_.destroy(params_);
        params_ = engine_.createBuffer(need, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
    }
    auto* frame = static_cast<gpu::FrameParams*>(params_.mapped);
    frame->view_proj = viewProjection(camera, static_cast<float>(width_) / static_cast<float>(height_));
    const Float3 light = normalize({0.35f, 0.85f, 0.4f});
    frame->light = {light.x, light.y, light.z, 0};
    frame->highlight = {1.0f, 0.1f, 0.05f, 1};
    // White: the command-line tool draws its collision rays yellow.
    frame->halo = {1.0f, 1.0f, 1.0f, 1};
    auto* params = reinterpret_cast<gpu::DrawParams*>(frame + 1);
    for (std::size_t i = 0; i < draws_.size(); ++i) {
        const Draw& d = draws_[i];
        gpu::DrawParams& p = params[i];
        p.vertices = d.vertices;
        p.indices = d.indices;
        p.highlights = d.highlights.address;
        p.first_float = d.first_float;
        p.stride_floats = d.stride_floats;
        p.colour = {d.colour[0], d.colour[1], d.colour[2], 1};
        for (int r = 0; r < 3; ++r) p.model[r] = {d.transform[r * 4], d.transform[r * 4 + 1], d.transform[r * 4 + 2], d.transform[r * 4 + 3]};
    }
}

const std::vector<std::uint8_t>& Renderer::render(const Camera& camera) {
    writeParams(camera);

    engine_.submit([&](VkCommandBuffer cmd) {
        VkImageMemoryBarrier2 to_attachment[2] = {{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2}, {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2}};
        to_attachment[0].srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        to_attachment[0].srcAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
        to_attachment[0].dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        to_attachment[0].dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        to_attachment[0].oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        to_attachment[0].newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        to_attachment[0].image = colour_;
        to_attachment[0].subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        to_attachment[1].srcStageMask = VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        to_attachment[1].srcAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        to_attachment[1].dstStageMask = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        to_attachment[1].dstAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
        to_attachment[1].oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        to_attachment[1].newLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        to_attachment[1].image = depth_;
        to_attachment[1].subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 2;
        dep.pImageMemoryBarriers = to_attachment;
        vkCmdPipelineBarrier2(cmd, &dep);

        VkRenderingAttachmentInfo colour_att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colour_att.imageView = colour_view_;
        colour_att.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colour_att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        colour_att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colour_att.clearValue.color = {{0.11f, 0.12f, 0.14f, 1.0f}};
        VkRenderingAttachmentInfo depth_att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth_att.imageView = depth_view_;
        depth_att.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth_att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth_att.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        depth_att.clearValue.depthStencil = {1.0f, 0};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {width_, height_}};
        ri.layerCount = 1;
        ri.colorAttachmentCount = 1;
        ri.pColorAttachments = &colour_att;
        ri.pDepthAttachment = &depth_att;
        vkCmdBeginRendering(cmd, &ri);
        VkViewport viewport{0, 0, static_cast<float>(width_), static_cast<float>(height_), 0, 1};
        VkRect2D scissor{{0, 0}, {width_, height_}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        auto draw_all = [&](std::uint32_t pass) {
            for (std::size_t i = 0; i < draws_.size(); ++i) {
                if (draws_[i].triangles == 0 || (pass != RENDER_PASS_ALL && draws_[i].hot == 0)) continue;
                // Three pixels of halo at 640 wide; at least one and a half on a thumbnail.
                const gpu::RenderPush push{params_.address, params_.address + sizeof(gpu::FrameParams) + i * sizeof(gpu::DrawParams),
                                           pass, std::max(1.5f, float(width_) / 200.0f), float(width_), float(height_)};
                vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
                vkCmdDraw(cmd, draws_[i].triangles * 3, 1, 0, 0);
            }
        };
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        draw_all(RENDER_PASS_ALL);
        // Every halo first, then every highlighted triangle: no halo covers a contact.
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, hot_pipeline_);
        draw_all(RENDER_PASS_HALO);
        draw_all(RENDER_PASS_HOT);
        vkCmdEndRendering(cmd);

        VkImageMemoryBarrier2 to_copy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        to_copy.srcStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        to_copy.srcAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        to_copy.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        to_copy.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
        to_copy.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        to_copy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        to_copy.image = colour_;
        to_copy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &to_copy;
        vkCmdPipelineBarrier2(cmd, &dep);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {width_, height_, 1};
        vkCmdCopyImageToBuffer(cmd, colour_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1, &region);
        VkBufferMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        to_host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        to_host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        to_host.buffer = readback_.buffer;
        to_host.size = VK_WHOLE_SIZE;
        dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.bufferMemoryBarrierCount = 1;
        dep.pBufferMemoryBarriers = &to_host;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    const auto* src = static_cast<const std::uint8_t*>(readback_.mapped);
    pixels_.assign(src, src + readback_.size);
    return pixels_;
}

}  // namespace render
