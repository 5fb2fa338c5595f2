#include "passes/engine_mesh.hpp"

#include "vk/device.hpp"

namespace vkcollide::passes {

VkDeviceSize engineBufferCapacity(const vk::Device& device, VkBuffer buffer) {
    VkMemoryRequirements req{};
    device.fns.vkGetBufferMemoryRequirements(device.device, buffer, &req);
    return req.size;
}

GpuMesh describeEngineMesh(const vk::Device& device, const GpuMeshDesc& d, bool open) {
    VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    GpuMesh m;
    ai.buffer = d.vertex_buffer;
    m.vertices = device.fns.vkGetBufferDeviceAddress(device.device, &ai) + d.vertex_offset;
    ai.buffer = d.index_buffer;
    m.indices = device.fns.vkGetBufferDeviceAddress(device.device, &ai) + d.index_offset;
    m.vertex_stride = d.vertex_stride;
    m.vertex_count = d.vertex_count;
    m.index16 = d.index_type == VK_INDEX_TYPE_UINT16;
    m.triangle_count = d.index_count / 3;
    m.open = open;
    m.check_on_gpu = true;  // index and vertex values live only on the GPU: check them there
    return m;
}

}  // namespace vkcollide::passes
