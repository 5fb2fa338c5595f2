// Buffers the library leaves on the GPU for the engine (device pairs, device proximity),
// copied into host memory as an engine would read them: one command buffer on the
// Context's queue after the detection, ordered after its shader writes by the barrier the
// docs ask for, then waited for.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vk/device.hpp"

namespace vkcollide::test {

struct BufferRead {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize bytes = 0;  // from offset 0; 0: nothing copied
};

// One vector of bytes per read, in order. Fails the test (REQUIRE) on a Vulkan error.
std::vector<std::vector<std::uint8_t>> copyToHost(vk::Device& dev, std::span<const BufferRead> reads);

}  // namespace vkcollide::test
