#include "vk/resources.hpp"

#include <algorithm>

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
    b.device_ = &device;
    b.size_ = size;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    const auto& f = device.fns;
    VkResult r = f.vkCreateBuffer(device.device, &ci, nullptr, &b.buffer_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateBuffer for '" + name + "'");
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
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.pNext = &flags;
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = *type;
    r = f.vkAllocateMemory(device.device, &ai, nullptr, &b.memory_);
    if (r != VK_SUCCESS)
        return vulkanError(r, "vkAllocateMemory of " + std::to_string(req.size) + " bytes for '" + name + "'");
    b.allocation_size_ = req.size;
    device.memory_in_use.fetch_add(req.size, std::memory_order_relaxed);
    r = f.vkBindBufferMemory(device.device, b.buffer_, b.memory_, 0);
    if (r != VK_SUCCESS) return vulkanError(r, "vkBindBufferMemory for '" + name + "'");
    VkMemoryPropertyFlags props = device.memory.memoryTypes[*type].propertyFlags;
    b.coherent_ = (props & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    if (props & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        r = f.vkMapMemory(device.device, b.memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_);
        if (r != VK_SUCCESS) return vulkanError(r, "vkMapMemory for '" + name + "'");
    }
    VkBufferDeviceAddressInfo addr{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addr.buffer = b.buffer_;
    b.address_ = f.vkGetBufferDeviceAddress(device.device, &addr);
    return b;
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, nullptr);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(o.size_, 0);
        allocation_size_ = std::exchange(o.allocation_size_, 0);
        address_ = std::exchange(o.address_, 0);
        mapped_ = std::exchange(o.mapped_, nullptr);
        coherent_ = o.coherent_;
    }
    return *this;
}

VkMappedMemoryRange Buffer::atomRange(VkDeviceSize offset, VkDeviceSize size) const {
    // Non-coherent ranges start and end on multiples of nonCoherentAtomSize, or end at the
    // end of the allocation (VUID-VkMappedMemoryRange-offset-00687, -size-01390).
    const VkDeviceSize atom = std::max<VkDeviceSize>(device_->properties.limits.nonCoherentAtomSize, 1);
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = memory_;
    range.offset = std::min(offset, size_) / atom * atom;
    const VkDeviceSize end = size == VK_WHOLE_SIZE || size >= size_ - std::min(offset, size_) ? size_ : offset + size;
    const VkDeviceSize end_up = (end + atom - 1) / atom * atom;
    range.size = end_up >= allocation_size_ ? VK_WHOLE_SIZE : end_up - range.offset;
    return range;
}

void Buffer::invalidate(VkDeviceSize offset, VkDeviceSize size) const {
    if (coherent_ || !mapped_) return;
    const VkMappedMemoryRange range = atomRange(offset, size);
    device_->fns.vkInvalidateMappedMemoryRanges(device_->device, 1, &range);
}

void Buffer::flush(VkDeviceSize offset, VkDeviceSize size) const {
    if (coherent_ || !mapped_) return;
    const VkMappedMemoryRange range = atomRange(offset, size);
    device_->fns.vkFlushMappedMemoryRanges(device_->device, 1, &range);
}

void Buffer::reset() {
    if (!device_) return;
    const auto& f = device_->fns;
    if (buffer_) f.vkDestroyBuffer(device_->device, buffer_, nullptr);
    if (memory_) {
        f.vkFreeMemory(device_->device, memory_, nullptr);  // unmaps implicitly
        device_->memory_in_use.fetch_sub(allocation_size_, std::memory_order_relaxed);
    }
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    device_ = nullptr;
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
    img.device_ = &device;
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
    VkResult r = f.vkCreateImage(device.device, &ci, nullptr, &img.image_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateImage for '" + name + "'");
    VkMemoryRequirements req;
    f.vkGetImageMemoryRequirements(device.device, img.image_, &req);
    auto type = device.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) type = device.findMemoryType(req.memoryTypeBits, 0);
    if (!type) return Error(ErrorCode::UnsupportedFeature, "no memory type fits image '" + name + "'");
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = *type;
    r = f.vkAllocateMemory(device.device, &ai, nullptr, &img.memory_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkAllocateMemory for image '" + name + "'");
    img.allocation_size_ = req.size;
    device.memory_in_use.fetch_add(req.size, std::memory_order_relaxed);
    r = f.vkBindImageMemory(device.device, img.image_, img.memory_, 0);
    if (r != VK_SUCCESS) return vulkanError(r, "vkBindImageMemory for '" + name + "'");

    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img.image_;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = desc.format;
    vi.subresourceRange = {aspectOf(desc.format), 0, desc.mip_levels, 0, 1};
    r = f.vkCreateImageView(device.device, &vi, nullptr, &img.view_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateImageView for '" + name + "'");
    for (std::uint32_t level = 0; level < desc.mip_levels; ++level) {
        vi.subresourceRange.baseMipLevel = level;
        vi.subresourceRange.levelCount = 1;
        VkImageView view = VK_NULL_HANDLE;
        r = f.vkCreateImageView(device.device, &vi, nullptr, &view);
        if (r != VK_SUCCESS) return vulkanError(r, "vkCreateImageView (level) for '" + name + "'");
        img.level_views_.push_back(view);
    }
    return img;
}

Image& Image::operator=(Image&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, nullptr);
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        allocation_size_ = std::exchange(o.allocation_size_, 0);
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
    for (VkImageView v : level_views_) f.vkDestroyImageView(device_->device, v, nullptr);
    level_views_.clear();
    if (view_) f.vkDestroyImageView(device_->device, view_, nullptr);
    if (image_) f.vkDestroyImage(device_->device, image_, nullptr);
    if (memory_) {
        f.vkFreeMemory(device_->device, memory_, nullptr);
        device_->memory_in_use.fetch_sub(allocation_size_, std::memory_order_relaxed);
    }
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    device_ = nullptr;
}

// ---- Submission -----------------------------------------------------------

Result<Submission> Submission::create(Device& device) {
    Submission s;
    s.device_ = &device;
    const auto& f = device.fns;
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pi.queueFamilyIndex = device.queue_family;
    VkResult r = f.vkCreateCommandPool(device.device, &pi, nullptr, &s.pool_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = s.pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    r = f.vkAllocateCommandBuffers(device.device, &ai, &s.cmd_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    r = f.vkCreateFence(device.device, &fi, nullptr, &s.fence_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateFence");
    return s;
}

Submission& Submission::operator=(Submission&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, nullptr);
        pool_ = std::exchange(o.pool_, VK_NULL_HANDLE);
        cmd_ = std::exchange(o.cmd_, VK_NULL_HANDLE);
        fence_ = std::exchange(o.fence_, VK_NULL_HANDLE);
        pending_ = std::exchange(o.pending_, false);
    }
    return *this;
}

Result<VkCommandBuffer> Submission::begin() {
    if (pending_) {
        if (auto ok = wait(); !ok) return ok.error();
    }
    const auto& f = device_->fns;
    VkResult r = f.vkResetCommandPool(device_->device, pool_, 0);
    if (r != VK_SUCCESS) return vulkanError(r, "vkResetCommandPool");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    r = f.vkBeginCommandBuffer(cmd_, &bi);
    if (r != VK_SUCCESS) return vulkanError(r, "vkBeginCommandBuffer");
    return cmd_;
}

Result<void> Submission::submit() {
    const auto& f = device_->fns;
    VkResult r = f.vkEndCommandBuffer(cmd_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkEndCommandBuffer");
    r = f.vkResetFences(device_->device, 1, &fence_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkResetFences");
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = cmd_;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    r = f.vkQueueSubmit2(device_->queue, 1, &si, fence_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkQueueSubmit2");
    pending_ = true;
    return {};
}

Result<void> Submission::wait(std::uint64_t timeout_ns) {
    if (!pending_) return {};
    VkResult r = device_->fns.vkWaitForFences(device_->device, 1, &fence_, VK_TRUE, timeout_ns);
    if (r == VK_TIMEOUT) return Error(ErrorCode::VulkanError, "GPU work did not finish within the timeout", r);
    pending_ = false;
    if (r != VK_SUCCESS) return vulkanError(r, "vkWaitForFences");
    return {};
}

void Submission::reset() {
    if (!device_) return;
    if (pending_) device_->fns.vkWaitForFences(device_->device, 1, &fence_, VK_TRUE, UINT64_MAX);
    const auto& f = device_->fns;
    if (fence_) f.vkDestroyFence(device_->device, fence_, nullptr);
    if (pool_) f.vkDestroyCommandPool(device_->device, pool_, nullptr);
    fence_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    device_ = nullptr;
}

}  // namespace vkcollide::vk
