// Compute and graphics pipelines with their layouts (src/vk/pipeline.hpp).
#include "vk/pipeline.hpp"

#include "vk/debug_names.hpp"
#include "vk/shader_limits.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace vkcollide::vk {

namespace {

Result<void> makeLayout(Device& device, std::span<const Pipeline::Binding> bindings, std::uint32_t push_bytes,
                        VkShaderStageFlags stages, const std::string& name, PipelineHandles& h) {
    // Detection reaches its buffers through device addresses and push constants: its
    // pipelines have no descriptor set at all. Only pipelines with bindings (test shaders)
    // need pushed descriptors, hence VK_KHR_push_descriptor.
    if (!bindings.empty()) {
        if (!device.push_descriptor)
            return Error(ErrorCode::UnsupportedFeature, "pipeline '" + name + "' has descriptor bindings, which need "
                                                        "VK_KHR_push_descriptor; the device has not enabled it");
        std::vector<VkDescriptorSetLayoutBinding> b;
        for (const Pipeline::Binding& x : bindings) b.push_back({x.binding, x.type, 1, stages, nullptr});
        VkDescriptorSetLayoutCreateInfo sl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        sl.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
        sl.bindingCount = static_cast<std::uint32_t>(b.size());
        sl.pBindings = b.data();
        VkResult r = device.fns.vkCreateDescriptorSetLayout(device.device, &sl, device.allocator(), &h.set_layout);
        if (r != VK_SUCCESS) {
            h.set_layout = VK_NULL_HANDLE;
            return vulkanError(r, "vkCreateDescriptorSetLayout for '" + name + "'");
        }
        nameObject(device, h.set_layout, name, " set layout");
    }
    VkPushConstantRange range{stages, 0, push_bytes};
    VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    li.setLayoutCount = h.set_layout ? 1 : 0;
    li.pSetLayouts = h.set_layout ? &h.set_layout : nullptr;
    li.pushConstantRangeCount = push_bytes ? 1 : 0;
    li.pPushConstantRanges = &range;
    VkResult r = device.fns.vkCreatePipelineLayout(device.device, &li, device.allocator(), &h.layout);
    if (r != VK_SUCCESS) {
        h.layout = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreatePipelineLayout for '" + name + "'");
    }
    nameObject(device, h.layout, name, " layout");
    return {};
}

struct ShaderModule {
    Device* device = nullptr;
    VkShaderModule module = VK_NULL_HANDLE;
    ~ShaderModule() {
        if (module) device->fns.vkDestroyShaderModule(device->device, module, device->allocator());
    }
};

Result<void> makeModule(Device& device, std::span<const std::uint32_t> spirv, ShaderModule& out, const std::string& name) {
    out.device = &device;
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size_bytes();
    ci.pCode = spirv.data();
    VkResult r = device.fns.vkCreateShaderModule(device.device, &ci, device.allocator(), &out.module);
    if (r != VK_SUCCESS) {
        out.module = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateShaderModule for '" + name + "'");
    }
    nameObject(device, out.module, name, " shader");
    return {};
}

// Vulkan's two-call query: the count, then that many structures of type s_type.
template <typename T, typename Query>
bool queryAll(VkStructureType s_type, std::vector<T>& out, Query query) {
    std::uint32_t n = 0;
    if (query(&n, static_cast<T*>(nullptr)) != VK_SUCCESS) return false;
    T blank{};
    blank.sType = s_type;
    out.assign(n, blank);
    if (query(&n, out.data()) != VK_SUCCESS) return false;
    out.resize(n);
    return true;
}

// ContextCreateInfo::pipeline_statistics: what the driver says of each executable of a new
// pipeline, kept on the device (its caller holds pipelines_mutex). A query that fails
// leaves an entry with what it could read: statistics are for tuning, never an error.
void captureStatistics(Device& device, VkPipeline pipeline, const std::string& name) {
    VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    std::vector<VkPipelineExecutablePropertiesKHR> executables;
    if (!queryAll(VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR, executables, [&](std::uint32_t* n, auto* data) {
            return device.get_executable_properties(device.device, &info, n, data);
        }))
        return;
    for (std::uint32_t e = 0; e < executables.size(); ++e) {
        PipelineStatistics& out = device.pipeline_statistics.emplace_back();
        out.pipeline = name;
        out.executable = executables[e].name;
        VkPipelineExecutableInfoKHR which{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        which.pipeline = pipeline;
        which.executableIndex = e;
        std::vector<VkPipelineExecutableStatisticKHR> stats;
        if (!queryAll(VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR, stats, [&](std::uint32_t* n, auto* data) {
                return device.get_executable_statistics(device.device, &which, n, data);
            }))
            continue;
        for (std::size_t k = 0; k < stats.size(); ++k) {
            double value = 0;
            switch (stats[k].format) {
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: value = stats[k].value.b32 ? 1 : 0; break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: value = static_cast<double>(stats[k].value.i64); break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: value = static_cast<double>(stats[k].value.u64); break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: value = stats[k].value.f64; break;
                default: continue;
            }
            out.statistics.push_back({stats[k].name, stats[k].description, value});
        }
    }
}

// The end of either pipeline kind's creation: a failed create may have written its handle,
// which must not reach ~PipelineHandles.
Result<void> finishPipeline(Device& device, VkResult r, const char* create_call, VkPipelineBindPoint bind_point, const std::string& name,
                            PipelineHandles& h) {
    if (r != VK_SUCCESS) {
        h.pipeline = VK_NULL_HANDLE;
        return vulkanError(r, std::string(create_call) + " for '" + name + "'");
    }
    nameObject(device, h.pipeline, name);
    h.bind_point = bind_point;
    if (device.capture_statistics) captureStatistics(device, h.pipeline, name);
    return {};
}

// What a pipeline is made from, as a key: the program (an embedded array: its address and
// size), its bindings and push constant size, and for raster pipelines their fixed state.
std::string bindingKey(std::span<const Pipeline::Binding> bindings, std::uint32_t push_bytes) {
    std::string key = "push " + std::to_string(push_bytes);
    for (const Pipeline::Binding& b : bindings) key += " b" + std::to_string(b.binding) + ":" + std::to_string(int(b.type));
    return key;
}

std::string programKey(std::span<const std::uint32_t> spirv) {
    return std::to_string(reinterpret_cast<std::uintptr_t>(spirv.data())) + "+" + std::to_string(spirv.size());
}

Result<void> makeRaster(Device& device, const Pipeline::RasterDesc& desc, std::span<const Pipeline::Binding> bindings,
                        std::uint32_t push_constant_bytes, const std::string& name, PipelineHandles& h);

}  // namespace

Result<Pipeline> Pipeline::share(Device& device, const std::string& key, const Make& make) {
    std::lock_guard lock(device.pipelines_mutex);
    std::weak_ptr<const PipelineHandles>& slot = device.pipelines[key];
    if (auto alive = slot.lock()) return Pipeline(std::move(alive));
    auto h = std::make_shared<PipelineHandles>();
    h->device = device.ref();
    if (auto ok = make(*h); !ok) return ok.error();  // h destroys what was made
    ++device.pipelines_created;
    slot = h;
    if (device.keep_pipelines) device.kept_pipelines.push_back(h);
    return Pipeline(std::move(h));
}

Result<void> Pipeline::checkComputeLimits(const Device& device, std::span<const std::uint32_t> spirv, const std::string& name) {
    auto needs = readComputeNeeds(spirv);
    if (!needs) return Error(ErrorCode::InvalidArgument, "compute pipeline '" + name + "': " + needs.error().message());
    if (auto over = exceededComputeLimit(*needs, device.properties.limits, name))
        return Error(ErrorCode::UnsupportedFeature, *over + " on " + device.info.name);
    return {};
}

Result<Pipeline> Pipeline::createCompute(Device& device, std::span<const std::uint32_t> spirv,
                                         std::span<const Binding> bindings, std::uint32_t push_constant_bytes,
                                         const std::string& name) {
    // A device below the shader's workgroup size or shared memory fails here, by name.
    if (auto ok = checkComputeLimits(device, spirv, name); !ok) return ok.error();
    const std::string key = "compute " + programKey(spirv) + " " + bindingKey(bindings, push_constant_bytes);
    return share(device, key, [&](PipelineHandles& h) -> Result<void> {
        if (auto ok = makeLayout(device, bindings, push_constant_bytes, VK_SHADER_STAGE_COMPUTE_BIT, name, h); !ok) return ok;
        ShaderModule module;
        if (auto ok = makeModule(device, spirv, module, name); !ok) return ok;
        VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = module.module;
        ci.stage.pName = "main";
        ci.layout = h.layout;
        if (device.capture_statistics) ci.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
        VkResult r = device.fns.vkCreateComputePipelines(device.device, device.pipeline_cache, 1, &ci, device.allocator(), &h.pipeline);
        return finishPipeline(device, r, "vkCreateComputePipelines", VK_PIPELINE_BIND_POINT_COMPUTE, name, h);
    });
}

Result<Pipeline> Pipeline::createRaster(Device& device, const RasterDesc& desc, std::span<const Binding> bindings,
                                        std::uint32_t push_constant_bytes, const std::string& name) {
    std::string key = "raster " + programKey(desc.vertex_spirv) + " " + programKey(desc.fragment_spirv) + " " +
                      bindingKey(bindings, push_constant_bytes) + " depth " + std::to_string(int(desc.depth_format)) + " " +
                      std::to_string(int(desc.depth_test)) + std::to_string(int(desc.depth_write)) + " " +
                      std::to_string(int(desc.depth_compare)) + " cull " + std::to_string(desc.cull) + " " +
                      std::to_string(int(desc.front_face)) + " conservative " + std::to_string(int(desc.conservative)) + " colour";
    for (VkFormat f : desc.color_formats) key += " " + std::to_string(int(f));
    return share(device, key, [&](PipelineHandles& h) { return makeRaster(device, desc, bindings, push_constant_bytes, name, h); });
}

namespace {

Result<void> makeRaster(Device& device, const Pipeline::RasterDesc& desc, std::span<const Pipeline::Binding> bindings,
                        std::uint32_t push_constant_bytes, const std::string& name, PipelineHandles& h) {
    if (auto ok = makeLayout(device, bindings, push_constant_bytes, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, name, h);
        !ok)
        return ok;
    ShaderModule vs, fs;
    if (auto ok = makeModule(device, desc.vertex_spirv, vs, name + ".vert"); !ok) return ok;
    if (auto ok = makeModule(device, desc.fragment_spirv, fs, name + ".frag"); !ok) return ok;
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs.module;
    stages[0].pName = "main";
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs.module;
    stages[1].pName = "main";

    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = desc.cull;
    raster.frontFace = desc.front_face;
    raster.lineWidth = 1.0f;
    VkPipelineRasterizationConservativeStateCreateInfoEXT conservative{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_CONSERVATIVE_STATE_CREATE_INFO_EXT};
    conservative.conservativeRasterizationMode = VK_CONSERVATIVE_RASTERIZATION_MODE_OVERESTIMATE_EXT;
    if (desc.conservative) {
        if (!device.conservative_rasterization)
            return Error(ErrorCode::UnsupportedFeature, "pipeline '" + name + "' asks for conservative rasterisation, which the device has not enabled");
        raster.pNext = &conservative;
    }
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = desc.depth_test;
    ds.depthWriteEnable = desc.depth_write;
    ds.depthCompareOp = desc.depth_compare;
    std::vector<VkPipelineColorBlendAttachmentState> blend(desc.color_formats.size());
    for (auto& b : blend) b.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<std::uint32_t>(blend.size());
    cb.pAttachments = blend.data();
    VkDynamicState dyn_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = 2;
    dyn.pDynamicStates = dyn_states;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.color_formats.size());
    rendering.pColorAttachmentFormats = desc.color_formats.data();
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.pNext = &rendering;
    if (device.capture_statistics) ci.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vertex_input;
    ci.pInputAssemblyState = &assembly;
    ci.pViewportState = &viewport;
    ci.pRasterizationState = &raster;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dyn;
    ci.layout = h.layout;
    VkResult r = device.fns.vkCreateGraphicsPipelines(device.device, device.pipeline_cache, 1, &ci, device.allocator(), &h.pipeline);
    return finishPipeline(device, r, "vkCreateGraphicsPipelines", VK_PIPELINE_BIND_POINT_GRAPHICS, name, h);
}

}  // namespace

PipelineHandles::~PipelineHandles() {
    if (!device) return;
    const auto& f = device->fns;
    const VkAllocationCallbacks* a = device->allocator();
    if (pipeline) f.vkDestroyPipeline(device->device, pipeline, a);
    if (layout) f.vkDestroyPipelineLayout(device->device, layout, a);
    if (set_layout) f.vkDestroyDescriptorSetLayout(device->device, set_layout, a);
    if (pipeline || layout || set_layout) device->resource_generation.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace vkcollide::vk
