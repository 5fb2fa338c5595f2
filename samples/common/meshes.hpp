// Meshes for the samples: the CGAL sample meshes (tools/fetch_cgal_data.sh) or generated
// stand-ins, and the few mesh operations the scenes need (simplify, subdivide, close
// small holes, normalise, merge).
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <cstddef>
#include <string>

#include "common/options.hpp"
#include "vkcollide/mesh.hpp"

namespace samples {

// Generated closed shapes that stand in for a CGAL mesh when it is missing (or with
// --stand-ins): the scenes and the tests run on a fresh clone without the data.
enum class StandIn {
    Blob,     // a lumpy sphere (bunny)
    Long,     // a lumpy elongated body (camel)
    Ring,     // a lumpy torus, genus 1 (elephant, dragon)
};

// Reads data/cgal/<file> (options.data) or, when it is missing or --stand-ins is given,
// generates `stand_in` (and says so on stderr). A file's mesh is turned so that `file_up`,
// its up direction, becomes +y (the scenes' up; stand-ins are made that way). The mesh is
// centred on its bounding box's centre and scaled so its largest extent is `size`.
vkcollide::HostMesh loadSceneMesh(const CommonOptions& options, const std::string& file, StandIn stand_in, float size,
                                  vkcollide::Float3 file_up = {0, 1, 0});

// Turns the mesh about the origin so that the direction `from` points along `to`.
void turnMesh(vkcollide::HostMesh& io_mesh, vkcollide::Float3 from, vkcollide::Float3 to);

// Centres on the bounding box and scales to the given largest extent.
void normalizeMesh(vkcollide::HostMesh& io_mesh, float size);

// About `target_triangles` triangles by edge collapse (meshoptimizer), keeping the
// topology; unused vertices are dropped. Returns the mesh unchanged if it is smaller.
vkcollide::HostMesh simplifyMesh(const vkcollide::HostMesh& mesh, std::size_t target_triangles);

// One step of Loop subdivision (4x triangles, smooth), or of sqrt(3) subdivision
// (Kobbelt 2000: 3x triangles, smooth). Closed meshes stay closed; boundary vertices stay put.
vkcollide::HostMesh subdivideLoop(const vkcollide::HostMesh& mesh);
vkcollide::HostMesh subdivideSqrt3(const vkcollide::HostMesh& mesh);
// The mix of Loop and sqrt(3) steps whose triangle count is closest to `target_triangles`
// (in ratio); `steps` receives what was done, e.g. "loop, sqrt3, sqrt3".
vkcollide::HostMesh subdivideTo(const vkcollide::HostMesh& mesh, std::size_t target_triangles, std::string* steps = nullptr);

// Closes each hole (a loop of boundary edges) with a fan around its centroid.
// Returns the number of holes closed.
std::size_t closeHoles(vkcollide::HostMesh& io_mesh);

// Appends `part`'s triangles to `io_mesh` (indices shifted).
void appendMesh(vkcollide::HostMesh& io_mesh, const vkcollide::HostMesh& part);

}  // namespace samples
