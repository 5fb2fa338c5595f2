#include <cmath>
#include <string>

#include "vkcollide/mesh.hpp"

namespace vkcollide {

Result<void> validateMesh(const HostMesh& mesh) {
    const std::string who = "mesh '" + (mesh.name.empty() ? std::string("(unnamed)") : mesh.name) + "': ";
    if (mesh.indices.empty()) return Error(ErrorCode::InvalidMesh, who + "has no triangles (empty mesh)");
    if (mesh.indices.size() % 3 != 0)
        return Error(ErrorCode::InvalidMesh, who + "index count " + std::to_string(mesh.indices.size()) +
                                                 " is not a multiple of three");
    if (mesh.positions.empty()) return Error(ErrorCode::InvalidMesh, who + "has indices but no vertices");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Float3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return Error(ErrorCode::InvalidMesh, who + "vertex " + std::to_string(i) + " is not finite (NaN or infinite)");
    }
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= mesh.positions.size())
            return Error(ErrorCode::InvalidMesh, who + "index " + std::to_string(mesh.indices[i]) + " of triangle " +
                                                     std::to_string(i / 3) + " is out of range (" +
                                                     std::to_string(mesh.positions.size()) + " vertices)");
    }
    return {};
}

}  // namespace vkcollide
