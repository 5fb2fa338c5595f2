// fuzz_world's engine meshes (world_engine.hpp).
#include "fuzz/world_engine.hpp"

#include <algorithm>
#include <cstring>

#include "fuzz/world_checks.hpp"
#include "fuzz/world_program.hpp"

namespace vkcollide::fuzz {

void writeVertex(EngineBuffers& e, std::uint32_t v, const Float3& p) {
    auto* at = static_cast<std::uint8_t*>(e.vertices.mapped()) + e.vertex_offset + std::size_t{v} * e.stride;
    std::memcpy(at, &p, sizeof p);
    e.vertices.flush();
}
void writeIndex(EngineBuffers& e, std::uint32_t k, std::uint32_t value) {
    auto* at = static_cast<std::uint8_t*>(e.indices.mapped()) + e.index_offset;
    if (e.index16) {
        const auto v16 = static_cast<std::uint16_t>(value);
        std::memcpy(at + 2 * std::size_t{k}, &v16, 2);
    } else {
        std::memcpy(at + 4 * std::size_t{k}, &value, 4);
    }
    e.indices.flush();
}

std::unique_ptr<EngineBuffers> makeEngineBuffers(vk::Device& device, const HostMesh& mesh, std::uint8_t layout, GpuMeshDesc& d) {
    auto e = std::make_unique<EngineBuffers>();
    e->index16 = (layout & kIndex16) != 0;
    e->stride = ((layout & kRgba) ? 16u : 12u) + ((layout & kWideStride) ? 4u : 0u);
    e->vertex_offset = (layout & kVertexOffset) ? 8u : 0u;
    e->index_offset = (layout & kIndexOffset) ? 4u : 0u;
    e->vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
    e->index_count = static_cast<std::uint32_t>(mesh.indices.size());
    const std::size_t vertex_bytes = e->vertex_offset + std::size_t{e->vertex_count} * e->stride;
    const std::size_t index_bytes = (e->index_offset + std::size_t{e->index_count} * (e->index16 ? 2 : 4) + 3) / 4 * 4;
    auto vb = vk::Buffer::create(device, std::max<std::size_t>(vertex_bytes, 4), 0, vk::MemoryKind::Upload, "fuzz-vertices");
    auto ib = vk::Buffer::create(device, std::max<std::size_t>(index_bytes, 4), 0, vk::MemoryKind::Upload, "fuzz-indices");
    if (!vb || !ib) fail("cannot create a small engine buffer");
    e->vertices = std::move(*vb);
    e->indices = std::move(*ib);
    std::memset(e->vertices.mapped(), 0, e->vertices.size());
    std::memset(e->indices.mapped(), 0, e->indices.size());
    for (std::uint32_t v = 0; v < e->vertex_count; ++v) writeVertex(*e, v, mesh.positions[v]);
    for (std::uint32_t k = 0; k < e->index_count; ++k) writeIndex(*e, k, mesh.indices[k]);
    d = GpuMeshDesc{};
    d.vertex_buffer = e->vertices.handle();
    d.vertex_buffer_size = e->vertices.size();
    d.vertex_offset = e->vertex_offset;
    d.vertex_stride = e->stride;
    d.vertex_count = e->vertex_count + ((layout & kDeclareExtraVertex) ? 1 : 0);
    d.position_format = (layout & kRgba) ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32G32B32_SFLOAT;
    d.index_buffer = (layout & kNullIndexBuffer) ? VK_NULL_HANDLE : e->indices.handle();
    d.index_buffer_size = e->indices.size();
    d.index_offset = e->index_offset;
    d.index_type = e->index16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;
    d.index_count = e->index_count;
    if (layout & kNoAddressUsage) d.vertex_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    return e;
}

}  // namespace vkcollide::fuzz
