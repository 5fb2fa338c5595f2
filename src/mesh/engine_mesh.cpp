#include "mesh/engine_mesh.hpp"

namespace vkcollide::passes {

GpuMesh describeEngineMesh(const GpuMeshDesc& d, VkDeviceAddress vertices, VkDeviceAddress indices, bool open) {
    GpuMesh m;
    m.vertices = vertices;
    m.indices = indices;
    m.vertex_stride = d.vertex_stride;
    m.vertex_count = d.vertex_count;
    m.index16 = d.index_type == VK_INDEX_TYPE_UINT16;
    m.triangle_count = d.index_count / 3;
    m.open = open;
    m.check_on_gpu = true;  // index and vertex values live only on the GPU: check them there
    return m;
}

}  // namespace vkcollide::passes
