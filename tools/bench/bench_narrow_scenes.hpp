// Scenes of bench_narrow kept apart from bench_narrow.cpp: resting contact between
// finely tessellated boxes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/scene.hpp"

namespace vkcollide::bench {

// One object of a generated scene: an object-space mesh and its object -> world transform
// (row-major 3x4). World positions are M * p in double, rounded once to float.
struct SceneObject {
    HostMesh mesh;
    Transform3x4 transform{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
};

// `touching`: 3 x 2 x 2 unit boxes stacked face to face, each face an n x n grid with n
// the power of two nearest sqrt(size / 144) (n = 32: 147,456 triangles), so every
// coordinate is a multiple of 1/(2n) and the contacts are exactly coplanar, as in the GPU
// bench's stack-touching. `touching-tilted`: the same boxes through one shear-and-turn
// with dyadic entries (a linear map, so exactly the same pairs intersect, but no contact
// plane is axis-aligned: the predicates' zero shortcut never applies and every coplanar
// test takes the exact path). nullopt for other names.
std::optional<std::vector<SceneObject>> touchingScene(const std::string& scene, std::size_t size);

}  // namespace vkcollide::bench
