#include "vk/engine_buffer.hpp"

namespace vkcollide::vk {

Result<VkDeviceAddress> checkEngineBuffer(const Device& device, const EngineBufferUse& use, const std::string& what) {
    const auto fail = [&](ErrorCode code, const std::string& rule) { return Error(code, what + " " + rule); };
    if (use.buffer == VK_NULL_HANDLE) return fail(ErrorCode::InvalidArgument, "is VK_NULL_HANDLE");
    if (!(use.declared_usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT))
        return fail(ErrorCode::InvalidArgument,
                    "was not declared with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT (vkcollide reads it through its "
                    "device address; create it with that usage and declare the usage it was created with)");
    if (use.alignment > 1 && use.offset % use.alignment != 0)
        return fail(ErrorCode::InvalidArgument, "offset " + std::to_string(use.offset) + " is not a multiple of " +
                                                    std::to_string(use.alignment));
    if (use.bytes == 0) return fail(ErrorCode::InvalidArgument, "has nothing to read (0 bytes)");
    if (use.offset > use.declared_size || use.bytes > use.declared_size - use.offset)
        return fail(ErrorCode::BufferTooSmall, "of " + std::to_string(use.declared_size) + " bytes is smaller than the " +
                                                   std::to_string(use.offset) + " + " + std::to_string(use.bytes) +
                                                   " bytes read from it");
    // Any buffer answers this; a buffer's memory requirement is never smaller than its size.
    VkMemoryRequirements req{};
    device.fns.vkGetBufferMemoryRequirements(device.device, use.buffer, &req);
    if (req.size < use.declared_size)
        return fail(ErrorCode::BufferTooSmall, "is declared as " + std::to_string(use.declared_size) +
                                                   " bytes but holds at most " + std::to_string(req.size));
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = use.buffer;
    const VkDeviceAddress base = device.fns.vkGetBufferDeviceAddress(device.device, &info);
    if (base == 0)
        return fail(ErrorCode::InvalidArgument, "has no device address (bind it to memory allocated with "
                                                "VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT before adding it)");
    return base + use.offset;
}

}  // namespace vkcollide::vk
