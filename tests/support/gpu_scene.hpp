// Host meshes uploaded into GPU buffers, described as GpuMesh for the broad phase.
#pragma once

#include <cstring>
#include <vector>

#include "passes/broad_phase.hpp"
#include "vk/resources.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide::test {

struct UploadedScene {
    std::vector<vk::Buffer> buffers;
    std::vector<passes::GpuMesh> meshes;
};

// Positions are written with `stride` bytes per vertex (>= 12) to exercise strided input.
inline Result<UploadedScene> uploadScene(vk::Device& device, const std::vector<const HostMesh*>& meshes,
                                         const std::vector<bool>& open = {}, bool index16 = false,
                                         std::uint32_t stride = 12) {
    UploadedScene scene;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const HostMesh& m = *meshes[i];
        auto vb = vk::Buffer::create(device, std::max<std::size_t>(m.positions.size(), 1) * stride, 0, vk::MemoryKind::Upload, m.name + "-vertices");
        if (!vb) return vb.error();
        auto* dst = static_cast<std::uint8_t*>(vb->mapped());
        for (std::size_t v = 0; v < m.positions.size(); ++v) std::memcpy(dst + v * stride, &m.positions[v], 12);
        const std::size_t index_bytes = index16 ? (m.indices.size() * 2 + 3) / 4 * 4 : m.indices.size() * 4;
        auto ib = vk::Buffer::create(device, std::max<std::size_t>(index_bytes, 4), 0, vk::MemoryKind::Upload, m.name + "-indices");
        if (!ib) return ib.error();
        if (index16) {
            auto* idx = static_cast<std::uint16_t*>(ib->mapped());
            for (std::size_t k = 0; k < m.indices.size(); ++k) idx[k] = static_cast<std::uint16_t>(m.indices[k]);
        } else {
            std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
        }
        passes::GpuMesh g;
        g.vertices = vb->address();
        g.vertex_stride = stride;
        g.vertex_count = static_cast<std::uint32_t>(m.positions.size());
        g.indices = ib->address();
        g.index16 = index16;
        g.triangle_count = static_cast<std::uint32_t>(m.triangleCount());
        g.open = i < open.size() && open[i];
        scene.meshes.push_back(g);
        scene.buffers.push_back(std::move(*vb));
        scene.buffers.push_back(std::move(*ib));
    }
    return scene;
}

}  // namespace vkcollide::test
