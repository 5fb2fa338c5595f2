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
#include "vk/pipeline.hpp"

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

    // Makes GPU writes to bytes [offset, offset + size) visible to the host; flush() makes
    // host writes there visible to the GPU. Both are no-ops for coherent memory; otherwise
    // the range is widened to whole nonCoherentAtomSize blocks (never past the allocation).
    // size = VK_WHOLE_SIZE: to the end of the buffer.
    void invalidate(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    void flush(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    // The VkMappedMemoryRange invalidate() and flush() pass (public for the tests).
    VkMappedMemoryRange atomRange(VkDeviceSize offset, VkDeviceSize size) const;
    void reset();

private:
    Device* device_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceSize allocation_size_ = 0;  // VkMemoryRequirements::size (>= size_)
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
    VkDeviceSize allocation_size_ = 0;
    VkImageView view_ = VK_NULL_HANDLE;
    std::vector<VkImageView> level_views_;
    ImageDesc desc_;
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
