#include "mesh/mesh_upload.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <limits>

namespace vkcollide::passes {

Result<UploadedMeshes> uploadMeshes(vk::Device& device, const std::vector<const HostMesh*>& meshes,
                                    const MeshUploadOptions& options) {
    const std::uint32_t stride = options.vertex_stride;
    assert(stride >= 12 && stride % 4 == 0);
    UploadedMeshes out;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const HostMesh& m = *meshes[i];
        assert(validateMesh(m));
        assert(!options.index16 || m.positions.size() <= std::numeric_limits<std::uint16_t>::max() + 1u);
        auto vb = vk::Buffer::create(device, m.positions.size() * stride, 0, vk::MemoryKind::Upload, m.name + "-vertices");
        if (!vb) return vb.error();
        auto* dst = static_cast<std::uint8_t*>(vb->mapped());
        for (std::size_t v = 0; v < m.positions.size(); ++v) std::memcpy(dst + v * stride, &m.positions[v], sizeof(Float3));
        // 16-bit indices are read in whole 4-byte words, so round the size up.
        const std::size_t index_bytes = options.index16 ? (m.indices.size() * 2 + 3) / 4 * 4 : m.indices.size() * 4;
        auto ib = vk::Buffer::create(device, index_bytes, 0, vk::MemoryKind::Upload, m.name + "-indices");
        if (!ib) return ib.error();
        if (options.index16) {
            auto* idx = static_cast<std::uint16_t*>(ib->mapped());
            for (std::size_t k = 0; k < m.indices.size(); ++k) idx[k] = static_cast<std::uint16_t>(m.indices[k]);
        } else {
            std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
        }
        vb->flush();
        ib->flush();
        GpuMesh g;
        g.vertices = vb->address();
        g.vertex_stride = stride;
        g.vertex_count = static_cast<std::uint32_t>(m.positions.size());
        g.indices = ib->address();
        g.index16 = options.index16;
        g.triangle_count = static_cast<std::uint32_t>(m.triangleCount());
        g.open = i < options.open.size() && options.open[i];
        out.meshes.push_back(g);
        out.buffers.push_back(std::move(*vb));
        out.buffers.push_back(std::move(*ib));
    }
    return out;
}

}  // namespace vkcollide::passes
