// Compute and graphics pipelines, move-only, with their layouts. Every pipeline is created
// through Device::pipeline_cache (the engine's or the Context's own) and with the
// engine's allocation callbacks; each holds a DeviceRef (see resources.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vk/device.hpp"

namespace vkcollide::vk {

// A compute or graphics pipeline with its layout. Without bindings the layout has no
// descriptor set (push constants and device addresses only: every detection pipeline);
// with bindings the set is pushed, which needs VK_KHR_push_descriptor enabled
// (Device::push_descriptor), else creation fails with UnsupportedFeature.
class Pipeline {
public:
    Pipeline() = default;
    struct Binding {
        std::uint32_t binding;
        VkDescriptorType type;
    };
    static Result<Pipeline> createCompute(Device& device, std::span<const std::uint32_t> spirv,
                                          std::span<const Binding> bindings, std::uint32_t push_constant_bytes,
                                          const std::string& name);
    struct RasterDesc {
        std::span<const std::uint32_t> vertex_spirv;
        std::span<const std::uint32_t> fragment_spirv;
        std::vector<VkFormat> color_formats;
        VkFormat depth_format = VK_FORMAT_UNDEFINED;
        bool depth_test = false;
        bool depth_write = false;
        VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
        VkCullModeFlags cull = VK_CULL_MODE_NONE;
        VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        // Overestimating conservative rasterisation (needs VK_EXT_conservative_rasterization enabled).
        bool conservative = false;
    };
    static Result<Pipeline> createRaster(Device& device, const RasterDesc& desc, std::span<const Binding> bindings,
                                         std::uint32_t push_constant_bytes, const std::string& name);
    ~Pipeline() { reset(); }
    Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }
    Pipeline& operator=(Pipeline&& o) noexcept;

    VkPipeline handle() const noexcept { return pipeline_; }
    VkPipelineLayout layout() const noexcept { return layout_; }
    VkPipelineBindPoint bindPoint() const noexcept { return bind_point_; }
    void reset();

private:
    Result<void> createLayout(Device& device, std::span<const Binding> bindings, std::uint32_t push_bytes,
                              VkShaderStageFlags stages, const std::string& name);
    DeviceRef device_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
};

}  // namespace vkcollide::vk
