// Compute and graphics pipelines with their layouts, shared by every world of a device.
// Every pipeline is created through Device::pipeline_cache (the engine's or the Context's
// own) and with the engine's allocation callbacks; each holds a DeviceRef (see resources.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vk/device.hpp"

namespace vkcollide::vk {

// What one pipeline is made of, destroyed together when the last Pipeline sharing it goes.
struct PipelineHandles {
    DeviceRef device;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineBindPoint bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
    ~PipelineHandles();
};

// A compute or graphics pipeline with its layout. Without bindings the layout has no
// descriptor set (push constants and device addresses only: every detection pipeline);
// with bindings the set is pushed, which needs VK_KHR_push_descriptor enabled
// (Device::push_descriptor), else creation fails with UnsupportedFeature.
// Pipelines made from the same program and state on one device are one pipeline, shared
// (Device::pipelines): a second world on a Context creates none of its own.
class Pipeline {
public:
    Pipeline() = default;
    struct Binding {
        std::uint32_t binding;
        VkDescriptorType type;
    };
    // What createCompute checks before it compiles, without compiling: a device below the
    // program's workgroup size or shared memory fails by name (UnsupportedFeature).
    static Result<void> checkComputeLimits(const Device& device, std::span<const std::uint32_t> spirv, const std::string& name);
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

    VkPipeline handle() const noexcept { return handles_ ? handles_->pipeline : VK_NULL_HANDLE; }
    VkPipelineLayout layout() const noexcept { return handles_ ? handles_->layout : VK_NULL_HANDLE; }
    VkPipelineBindPoint bindPoint() const noexcept { return handles_ ? handles_->bind_point : VK_PIPELINE_BIND_POINT_COMPUTE; }
    void reset() noexcept { handles_.reset(); }

private:
    // The device's pipeline made from `key` if one is alive, else a new one that `make` fills.
    using Make = std::function<Result<void>(PipelineHandles&)>;
    static Result<Pipeline> share(Device& device, const std::string& key, const Make& make);
    explicit Pipeline(std::shared_ptr<const PipelineHandles> handles) : handles_(std::move(handles)) {}
    std::shared_ptr<const PipelineHandles> handles_;
};

}  // namespace vkcollide::vk
