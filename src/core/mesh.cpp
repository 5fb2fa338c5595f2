#include <cmath>
#include <string>

#include "core/mesh_rules.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide {

Result<void> checkMeshRules(const HostMesh& mesh) {
    if (mesh.indices.empty()) return Error(ErrorCode::InvalidMesh, "has no triangles (empty mesh)");
    if (mesh.indices.size() % 3 != 0)
        return Error(ErrorCode::InvalidMesh, "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of three");
    if (mesh.positions.empty()) return Error(ErrorCode::InvalidMesh, "has indices but no vertices");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Float3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return Error(ErrorCode::InvalidMesh, "vertex " + std::to_string(i) + " is not finite (NaN or infinite)");
    }
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= mesh.positions.size())
            return Error(ErrorCode::InvalidMesh, "index " + std::to_string(mesh.indices[i]) + " of triangle " + std::to_string(i / 3) +
                                                     " is out of range (" + std::to_string(mesh.positions.size()) + " vertices)");
    }
    return {};
}

Result<void> validateMesh(const HostMesh& mesh) {
    auto ok = checkMeshRules(mesh);
    if (ok) return ok;
    const std::string who = "mesh '" + (mesh.name.empty() ? std::string("(unnamed)") : mesh.name) + "': ";
    return Error(ok.error().code(), who + ok.error().message());
}

}  // namespace vkcollide
