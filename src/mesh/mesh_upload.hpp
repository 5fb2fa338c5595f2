// Host meshes copied into host-visible GPU buffers and described as GpuMesh, the form the
// broad phase reads (and the form an engine's own vertex/index buffers take).
#pragma once

#include <vector>

#include "broad/broad_phase_types.hpp"
#include "vk/resources.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide::passes {

struct MeshUploadOptions {
    std::vector<bool> open;          // per mesh; missing entries are closed surfaces
    bool index16 = false;            // store indices as uint16 (padded to whole words)
    std::uint32_t vertex_stride = 12;  // bytes per vertex, >= 12 and a multiple of 4
};

struct UploadedMeshes {
    std::vector<vk::Buffer> buffers;  // own the memory the meshes' addresses point into
    std::vector<GpuMesh> meshes;
};

// Uploads each mesh. Preconditions (the API checks them, validation.cpp; asserted here):
// every mesh passes validateMesh, the stride is >= 12 and a multiple of 4, and with index16
// no mesh has more than 65536 vertices. Errors: buffer creation only (OutOfMemory, ...).
Result<UploadedMeshes> uploadMeshes(vk::Device& device, const std::vector<const HostMesh*>& meshes,
                                    const MeshUploadOptions& options = {});

}  // namespace vkcollide::passes
