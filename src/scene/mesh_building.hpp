// What the scene generators (generators.cpp, shapes.cpp) share: pi, their error, a
// triangle appended to a mesh. One definition, so that a unity build may put both files
// in one batch.
#pragma once

#include <cstdint>
#include <numbers>
#include <string>
#include <utility>

#include "vkcollide/scene.hpp"

namespace vkcollide::mesh_building {

inline constexpr double kPi = std::numbers::pi;

inline Error invalid(std::string what) { return Error(ErrorCode::InvalidArgument, std::move(what)); }

inline void pushTriangle(HostMesh& io_mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    io_mesh.indices.insert(io_mesh.indices.end(), {a, b, c});
}

}  // namespace vkcollide::mesh_building
