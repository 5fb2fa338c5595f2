// vkcollide: host-side triangle meshes (what the readers and generators produce).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vkcollide/export.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

// An indexed triangle mesh in host memory. Triangles wind counter-clockwise seen from
// outside (outward normals) when the mesh is a closed surface.
struct HostMesh {
    std::string name;
    std::vector<Float3> positions;
    std::vector<std::uint32_t> indices;  // 3 per triangle

    std::size_t triangleCount() const noexcept { return indices.size() / 3; }
};

// Checks the rules every mesh must meet before vkcollide uses it: at least one
// triangle, an index count that is a multiple of three, every index below the vertex
// count and every vertex finite. The error names the mesh and the first broken rule.
VKCOLLIDE_API Result<void> validateMesh(const HostMesh& mesh);

}  // namespace vkcollide
