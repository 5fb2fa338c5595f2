// Move-only owners of buffers and images (Submission, the command and fence state, is in
// vk/submission.hpp, included here for the code that expects it with them).
// Memory comes from vk/memory.hpp: one VkDeviceMemory per resource by default, or a range
// of the engine's memory through its DeviceMemoryHooks; each owner frees exactly what it
// created. Each owner holds a DeviceRef from creation to its destructor (reset() frees
// the Vulkan objects but keeps the reference, so code that still holds a raw Device* next
// to a reset owner stays valid until the owner itself goes).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vk/device.hpp"
#include "vk/memory.hpp"
#include "vk/pipeline.hpp"
#include "vk/submission.hpp"

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
    void* mapped() const noexcept { return memory_.mapped; }
    bool valid() const noexcept { return buffer_ != VK_NULL_HANDLE; }

    // Makes GPU writes to bytes [offset, offset + size) visible to the host; flush() makes
    // host writes there visible to the GPU. Both are no-ops for coherent memory; otherwise
    // the range is widened to whole nonCoherentAtomSize blocks (never past the allocation).
    // size = VK_WHOLE_SIZE: to the end of the buffer.
    void invalidate(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    void flush(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;
    // The VkMappedMemoryRange invalidate() and flush() pass (public for the tests): in the
    // VkDeviceMemory's offsets, inside this buffer's block.
    VkMappedMemoryRange atomRange(VkDeviceSize offset, VkDeviceSize size) const;
    // Where the buffer is bound: its own VkDeviceMemory, or a range of the engine's.
    VkDeviceMemory memory() const noexcept { return memory_.memory; }
    VkDeviceSize memoryOffset() const noexcept { return memory_.offset; }
    // Bytes of device memory counted for it (Context::deviceMemoryInUse's unit: >= size()).
    VkDeviceSize memoryBytes() const noexcept { return memory_.size; }
    void reset();

private:
    DeviceRef device_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    MemoryBlock memory_;  // memory_.size: VkMemoryRequirements::size, rounded (>= size_)
    VkDeviceSize size_ = 0;
    VkDeviceAddress address_ = 0;
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
    // Bytes of device memory counted for it (Context::deviceMemoryInUse's unit).
    VkDeviceSize memoryBytes() const noexcept { return memory_.size; }
    void reset();

private:
    DeviceRef device_;
    VkImage image_ = VK_NULL_HANDLE;
    MemoryBlock memory_;
    VkImageView view_ = VK_NULL_HANDLE;
    std::vector<VkImageView> level_views_;
    ImageDesc desc_;
};

}  // namespace vkcollide::vk
