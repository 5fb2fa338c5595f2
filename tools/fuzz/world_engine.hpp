// fuzz_world's engine meshes: an engine's vertex and index buffers (host-visible, so the
// program can rewrite them between detections) in the layouts world_program.hpp lists,
// with descriptions that are right or break one rule.
#pragma once

#include <cstdint>
#include <memory>

#include "vk/resources.hpp"
#include "vkcollide/gpu_mesh.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide::fuzz {

struct EngineBuffers {
    vk::Buffer vertices, indices;
    std::uint32_t stride = 12, vertex_offset = 0, index_offset = 0, vertex_count = 0, index_count = 0;
    bool index16 = false;
};

// Buffers of exactly the size `mesh` needs in `layout` (world_program.hpp's layout bits),
// and in `desc` their description: the real buffer sizes always (a wrong one would be the
// engine's bug), the rest as the layout asks, rule-breaking bits included.
std::unique_ptr<EngineBuffers> makeEngineBuffers(vk::Device& device, const HostMesh& mesh, std::uint8_t layout, GpuMeshDesc& desc);
// The engine rewriting vertex v's position or index k (flushed).
void writeVertex(EngineBuffers& e, std::uint32_t v, const Float3& p);
void writeIndex(EngineBuffers& e, std::uint32_t k, std::uint32_t value);

}  // namespace vkcollide::fuzz
