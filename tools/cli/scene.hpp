// The scene `vkcollide detect` reads: its objects from the files (an OBJ's o/g groups, or
// one object per OFF/PLY file) with their options, and, with --sequence, each later
// frame's positions, checked to have the first frame's topology.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/options.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/world.hpp"

namespace cli {

struct SceneObject {
    vkcollide::HostMesh mesh;           // object space, as read (this frame's positions)
    vkcollide::ObjectOptions options;   // the final name, flags and transform
    std::size_t slot = 0;               // the file (place in the frame) it came from
    bool gpu_mesh = false;              // added as engine-owned buffers
    std::uint64_t first_triangle = 0;   // global number of its triangle 0
};

struct Scene {
    std::vector<SceneObject> objects;  // in command-line then file order: object i has ObjectId i
    std::uint64_t triangles = 0;
    std::vector<std::string> names() const;
    // The world-space box of every object (transforms applied): min x, y, z, max x, y, z.
    std::array<float, 6> worldBounds() const;
};

// Frame 0 (all files without --sequence). Errors name the file and the problem.
vkcollide::Result<Scene> readScene(const CommandLine& line);
// Replaces the positions with frame `frame`'s (frame >= 1 of a --sequence). Error when a
// file cannot be read or its topology differs from frame 0's: it names both frames' files
// and what differs (objects, vertices or a triangle's indices).
vkcollide::Result<void> readFrame(const CommandLine& line, std::size_t frame, Scene& io_scene);

}  // namespace cli
