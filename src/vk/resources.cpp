#include "vk/resources.hpp"

#include <algorithm>

#include "vk/debug_names.hpp"

namespace vkcollide::vk {

// ---- Buffer ---------------------------------------------------------------

Result<Buffer> Buffer::create(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryKind kind,
                              const std::string& name) {
    if (size == 0) return Error(ErrorCode::InvalidArgument, "buffer '" + name + "' has size 0");
    if (size > device.max_buffer_size || size > device.max_allocation_size)
        return Error(ErrorCode::OutOfMemory, "buffer '" + name + "' of " + std::to_string(size) + " bytes exceeds the device's limit of " +
                                                 std::to_string(std::min(device.max_buffer_size, device.max_allocation_size)) +
                                                 " bytes per buffer (maxBufferSize / maxMemoryAllocationSize)");
    Buffer b;
    b.device_ = device.ref();
    b.size_ = size;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    const auto& f = device.fns;
    VkResult r = f.vkCreateBuffer(device.device, &ci, device.allocator(), &b.buffer_);
    if (r != VK_SUCCESS) {
        b.buffer_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateBuffer for '" + name + "'");
    }
    nameObject(device, b.buffer_, name);
    VkMemoryRequirements req;
    f.vkGetBufferMemoryRequirements(device.device, b.buffer_, &req);

    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (kind) {
        case MemoryKind::DeviceLocal: required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
        case MemoryKind::Upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryKind::Readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    auto type = device.findMemoryType(req.memoryTypeBits, required, preferred);
    if (!type && kind == MemoryKind::DeviceLocal) type = device.findMemoryType(req.memoryTypeBits, 0);
    if (!type) return Error(ErrorCode::UnsupportedFeature, "no memory type fits buffer '" + name + "'");
    // Every buffer is read through its device address; host-visible ones (on some devices
    // device-local memory is host-visible too) are mapped for the host's reads and writes.
    auto memory = allocateMemory(device, {.requirements = req, .memory_type = *type, .device_address = true, .map = true}, name);
    if (!memory) return memory.error();
    b.memory_ = *memory;
    r = f.vkBindBufferMemory(device.device, b.buffer_, b.memory_.memory, b.memory_.offset);
    if (r != VK_SUCCESS) return vulkanError(r, "vkBindBufferMemory for '" + name + "'");
    VkBufferDeviceAddressInfo addr{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addr.buffer = b.buffer_;
    b.address_ = f.vkGetBufferDeviceAddress(device.device, &addr);
    return b;
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::move(o.device_);
        o.device_.reset();
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, MemoryBlock{});
        size_ = std::exchange(o.size_, 0);
        address_ = std::exchange(o.address_, 0);
    }
    return *this;
}

VkMappedMemoryRange Buffer::atomRange(VkDeviceSize offset, VkDeviceSize size) const {
    // Non-coherent ranges start and end on multiples of nonCoherentAtomSize, or end at the
    // end of the allocation (VUID-VkMappedMemoryRange-offset-00687, -size-01390). A range
    // of the engine's memory starts on an atom and has a whole number of atoms
    // (allocateMemory asks for that), so the widened range stays inside it.
    const VkDeviceSize atom = std::max<VkDeviceSize>(device_->properties.limits.nonCoherentAtomSize, 1);
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = memory_.memory;
    const VkDeviceSize start = std::min(offset, size_) / atom * atom;
    const VkDeviceSize end = size == VK_WHOLE_SIZE || size >= size_ - std::min(offset, size_) ? size_ : offset + size;
    const VkDeviceSize end_up = (end + atom - 1) / atom * atom;
    range.offset = memory_.offset + start;
    if (end_up >= memory_.size)
        range.size = memory_.whole_memory ? VK_WHOLE_SIZE : memory_.size - start;
    else
        range.size = end_up - start;
    return range;
}

void Buffer::invalidate(VkDeviceSize offset, VkDeviceSize size) const {
    if (memory_.coherent || !memory_.mapped) return;
    const VkMappedMemoryRange range = atomRange(offset, size);
    device_->fns.vkInvalidateMappedMemoryRanges(device_->device, 1, &range);
}

void Buffer::flush(VkDeviceSize offset, VkDeviceSize size) const {
    if (memory_.coherent || !memory_.mapped) return;
    const VkMappedMemoryRange range = atomRange(offset, size);
    device_->fns.vkFlushMappedMemoryRanges(device_->device, 1, &range);
}

void Buffer::reset() {
    if (!device_) return;
    if (buffer_) {
        device_->fns.vkDestroyBuffer(device_->device, buffer_, device_->allocator());
        device_->resource_generation.fetch_add(1, std::memory_order_relaxed);
    }
    freeMemory(*device_, memory_);
    buffer_ = VK_NULL_HANDLE;
    address_ = 0;
    size_ = 0;
}

// ---- Image ----------------------------------------------------------------

VkImageAspectFlags aspectOf(VkFormat format) noexcept {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_D24_UNORM_S8_UINT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT;
        default: return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

Result<Image> Image::create(Device& device, const ImageDesc& desc, const std::string& name) {
    if (desc.width == 0 || desc.height == 0 || desc.mip_levels == 0)
        return Error(ErrorCode::InvalidArgument, "image '" + name + "' has a zero dimension or no mip level");
    Image img;
    img.device_ = device.ref();
    img.desc_ = desc;
    const auto& f = device.fns;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = desc.format;
    ci.extent = {desc.width, desc.height, 1};
    ci.mipLevels = desc.mip_levels;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = desc.usage;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkResult r = f.vkCreateImage(device.device, &ci, device.allocator(), &img.image_);
    if (r != VK_SUCCESS) {
        img.image_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateImage for '" + name + "'");
    }
    nameObject(device, img.image_, name);
    VkMemoryRequirements req;
    f.vkGetImageMemoryRequirements(device.device, img.image_, &req);
    auto type = device.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) type = device.findMemoryType(req.memoryTypeBits, 0);
    if (!type) return Error(ErrorCode::UnsupportedFeature, "no memory type fits image '" + name + "'");
    auto memory = allocateMemory(device, {.requirements = req, .memory_type = *type, .image = true}, "image '" + name + "'");
    if (!memory) return memory.error();
    img.memory_ = *memory;
    r = f.vkBindImageMemory(device.device, img.image_, img.memory_.memory, img.memory_.offset);
    if (r != VK_SUCCESS) return vulkanError(r, "vkBindImageMemory for '" + name + "'");

    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img.image_;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = desc.format;
    vi.subresourceRange = {aspectOf(desc.format), 0, desc.mip_levels, 0, 1};
    r = f.vkCreateImageView(device.device, &vi, device.allocator(), &img.view_);
    if (r != VK_SUCCESS) {
        img.view_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateImageView for '" + name + "'");
    }
    nameObject(device, img.view_, name, " view");
    for (std::uint32_t level = 0; level < desc.mip_levels; ++level) {
        vi.subresourceRange.baseMipLevel = level;
        vi.subresourceRange.levelCount = 1;
        VkImageView view = VK_NULL_HANDLE;
        r = f.vkCreateImageView(device.device, &vi, device.allocator(), &view);
        if (r != VK_SUCCESS) return vulkanError(r, "vkCreateImageView (level) for '" + name + "'");
        img.level_views_.push_back(view);
        if (device.debug_utils) nameObject(device, view, name, " level " + std::to_string(level));
    }
    return img;
}

Image& Image::operator=(Image&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::move(o.device_);
        o.device_.reset();
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, MemoryBlock{});
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
        level_views_ = std::move(o.level_views_);
        o.level_views_.clear();
        desc_ = o.desc_;
    }
    return *this;
}

void Image::reset() {
    if (!device_) return;
    const auto& f = device_->fns;
    for (VkImageView v : level_views_) f.vkDestroyImageView(device_->device, v, device_->allocator());
    level_views_.clear();
    if (view_) f.vkDestroyImageView(device_->device, view_, device_->allocator());
    if (image_) {
        f.vkDestroyImage(device_->device, image_, device_->allocator());
        device_->resource_generation.fetch_add(1, std::memory_order_relaxed);
    }
    freeMemory(*device_, memory_);
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
}

}  // namespace vkcollide::vk
