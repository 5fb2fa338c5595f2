// --png: the scene drawn by the shared headless renderer (tools/render), one colour per
// object, the triangles of the colliding pairs highlighted, and with --rays the collision
// rays as thin yellow sticks. The camera frames frame 0's scene once, so the pictures of a
// --sequence line up.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <optional>
#include <string>
#include <vector>

#include "cli/devices.hpp"
#include "cli/scene.hpp"
#include "render/renderer.hpp"

namespace cli {

class Picture {
public:
    // `engine_meshes`: the --gpu-mesh objects' buffers, drawn as they are (null: none).
    Picture(render::Engine& engine, const CommandLine& line, const Scene& scene, const EngineMeshes* engine_meshes);

    // Draws this frame (positions in `scene`, highlights from `result`, optional rays) and
    // writes the PNG. Error: IoError naming the file.
    vkcollide::Result<void> write(const std::string& path, const Scene& scene, const vkcollide::DetectResult& result,
                                  const vkcollide::CollisionRays* rays);

    // "pictures/out.png" -> "pictures/out_0007.png" (a --sequence frame).
    static std::string framePath(const std::string& path, std::size_t frame);

private:
    render::Renderer renderer_;
    render::Camera camera_;
    std::vector<render::DrawId> draws_;    // per object
    std::vector<bool> host_;               // per object: drawn from the renderer's own copy
    bool dynamic_ = false;                 // host copies change (--sequence)
    std::optional<render::DrawId> rays_;
    float screen_pixel_ = 0;               // world size of a screen pixel at the scene's centre
};

}  // namespace cli
