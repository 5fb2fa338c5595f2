// Move-only owners of buffers, images, pipelines and command submission state.
// One VkDeviceMemory per resource: simple and enough for the few large buffers the
// pipeline uses; each owner frees exactly what it created.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vk/device.hpp"

namespace vkcollide::vk {

enum class MemoryKind {
    DeviceLocal,  // GPU-only working memory
    Upload,       // host-visible, written by the host, read by shaders
    Readback,     // host-visible (cached where possible), written by the GPU, read by the host
};

class Buffer {
public:
    Buffer() = default;
    // Buffers always get SHADER_DEVICE_ADDRESS, STORAGE and TRANSFER usage besides `usage`.
    static Result<Buffer> create(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryKind kind,
                                 const std::string& name);
    ~Buffer() { reset(); }
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;

    VkBuffer handle() const noexcept { return buffer_; }
    VkDeviceSize size() const noexcept { return size_; }
    VkDeviceAddress address() const noexcept { return address_; }
    void* mapped() const noexcept { return mapped_; }
    bool valid() const noexcept { return buffer_ != VK_NULL_HANDLE; }

    // Makes GPU writes visible to the host (no-op for coherent memory).
    void invalidate(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    // Makes host writes visible to the GPU (no-op for coherent memory).
    void flush(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    void reset();

private:
    Device* device_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

// The aspect that views and barriers of an image of this format use.
VkImageAspectFlags aspectOf(VkFormat format) noexcept;

struct ImageDesc {
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::uint32_t width = 0, height = 0;
    std::uint32_t mip_levels = 1;
    VkImageUsageFlags usage = 0;
};

class Image {
public:
    Image() = default;
    static Result<Image> create(Device& device, const ImageDesc& desc, const std::string& name);
    ~Image() { reset(); }
    Image(Image&& o) noexcept { *this = std::move(o); }
    Image& operator=(Image&& o) noexcept;

    VkImage handle() const noexcept { return image_; }
    // A view of every mip level, and one view per level (for storage writes to a level).
    VkImageView view() const noexcept { return view_; }
    VkImageView levelView(std::uint32_t level) const { return level_views_.at(level); }
    const ImageDesc& desc() const noexcept { return desc_; }
    bool valid() const noexcept { return image_ != VK_NULL_HANDLE; }
    void reset();

private:
    Device* device_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    std::vector<VkImageView> level_views_;
    ImageDesc desc_;
};

// A compute or graphics pipeline with its layout; descriptors are pushed (VK_KHR_push_descriptor).
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
                              VkShaderStageFlags stages);
    Device* device_ = nullptr;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
};

// Command pool + one primary command buffer + fence: one submission in flight.
class Submission {
public:
    Submission() = default;
    static Result<Submission> create(Device& device);
    ~Submission() { reset(); }
    Submission(Submission&& o) noexcept { *this = std::move(o); }
    Submission& operator=(Submission&& o) noexcept;

    // Waits for the previous use, resets the pool and begins recording.
    Result<VkCommandBuffer> begin();
    Result<void> submit();
    // Waits up to timeout_ns; VK_TIMEOUT is reported as DeviceLost-free Error(VulkanError).
    Result<void> wait(std::uint64_t timeout_ns = 60ull * 1000 * 1000 * 1000);
    bool pending() const noexcept { return pending_; }
    bool valid() const noexcept { return pool_ != VK_NULL_HANDLE; }
    void reset();

private:
    Device* device_ = nullptr;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool pending_ = false;
};

}  // namespace vkcollide::vk
