// An engine-owned copy of a host mesh for the API tests: positions in a (strided) vertex
// buffer, 16- or 32-bit indices, in host-visible memory the test can rewrite.
#pragma once

#include <cstring>

#include <catch2/catch.hpp>

#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {

struct EngineMesh {
    vk::Buffer vertices, indices;
    GpuMeshDesc desc;
};

inline EngineMesh engineCopy(vk::Device& dev, const HostMesh& m, std::uint32_t stride = 12,
                             VkFormat format = VK_FORMAT_R32G32B32_SFLOAT, bool index16 = false) {
    EngineMesh e;
    auto vb = vk::Buffer::create(dev, m.positions.size() * stride, 0, vk::MemoryKind::Upload, "engine-vertices");
    REQUIRE(vb);
    auto* dst = static_cast<std::uint8_t*>(vb->mapped());
    std::memset(dst, 0, m.positions.size() * stride);
    for (std::size_t i = 0; i < m.positions.size(); ++i) std::memcpy(dst + i * stride, &m.positions[i], 12);
    vb->flush();
    const std::size_t index_bytes = index16 ? (m.indices.size() * 2 + 3) / 4 * 4 : m.indices.size() * 4;
    auto ib = vk::Buffer::create(dev, index_bytes, 0, vk::MemoryKind::Upload, "engine-indices");
    REQUIRE(ib);
    if (index16) {
        auto* idx = static_cast<std::uint16_t*>(ib->mapped());
        for (std::size_t k = 0; k < m.indices.size(); ++k) idx[k] = static_cast<std::uint16_t>(m.indices[k]);
    } else {
        std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
    }
    ib->flush();
    e.desc.vertex_buffer = vb->handle();
    e.desc.vertex_buffer_size = vb->size();
    e.desc.vertex_stride = stride;
    e.desc.vertex_count = static_cast<std::uint32_t>(m.positions.size());
    e.desc.position_format = format;
    e.desc.index_buffer = ib->handle();
    e.desc.index_buffer_size = ib->size();
    e.desc.index_type = index16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;
    e.desc.index_count = static_cast<std::uint32_t>(m.indices.size());
    e.vertices = std::move(*vb);
    e.indices = std::move(*ib);
    return e;
}

}  // namespace vkcollide::test
