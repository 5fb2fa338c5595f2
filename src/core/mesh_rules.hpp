// The rules of validateMesh (vkcollide/mesh.hpp) with messages that do not name the mesh,
// for callers that name it their own way (the API: "object 3 ('cloth'): ...").
#pragma once

#include "vkcollide/mesh.hpp"

namespace vkcollide {

Result<void> checkMeshRules(const HostMesh& mesh);

}  // namespace vkcollide
