// The benchmark scene set (issue 7), shared by vkcollide's sweep and the peers' benchmark
// so that every library runs on the same meshes and frames: generated spheres and packaged
// CGAL meshes (tools/fetch_cgal_data.sh) from 10K to over 1M triangles, rigid and
// deforming (every vertex moves every frame). Meshes are built in world space.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/scene.hpp"

namespace vkcollide::bench {

enum class Motion { Rigid, Deforming };

struct SceneSpec {
    std::string name;
    Motion motion;
    std::string what;  // one line for --list and the table
    // Builds the meshes of frame `frame` (rigid scenes ignore it).
    std::function<Result<std::vector<HostMesh>>(int frame)> build;
};

// Every scene; `data` is the folder of the CGAL meshes (default data/cgal).
std::vector<SceneSpec> allScenes(const std::string& data);

Transform3x4 rotationTranslation(double axis_x, double axis_y, double axis_z, double angle, Float3 t);

}  // namespace vkcollide::bench
