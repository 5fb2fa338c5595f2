// What each sample's pictures show: the scene with its colliding triangles highlighted
// (the renderer draws them in red on top of everything, with a white halo, both objects'
// triangles), the camera aimed at the box of those triangles, and a caption with the
// method, the pair count and the detection's times.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <string>

#include "common/options.hpp"
#include "common/render.hpp"
#include "vkcollide/world.hpp"

namespace samples {

class Picture {
public:
    // overview: the whole scene, shown while no two objects touch (an object touching only
    // itself, as the CGAL camel does at rest, is highlighted but not framed); the camera
    // keeps its direction when it moves in on a contact. closest: the smallest radius around a
    // contact it frames (world units), so that the contact is seen with what surrounds it.
    Picture(Renderer& renderer, const CommonOptions& options, std::string scene, const Camera& overview, float closest);

    // When the frame is written (writesFrame): aims the camera, renders, captions and
    // writes OUT/frame_NNNN.png. The highlights must be set (Renderer::highlight). `note`:
    // the scene's own words for the caption (what collides, what happened).
    void write(int frame, const vkcollide::DetectResult& result, const std::string& note = {});

private:
    Camera aim(const vkcollide::DetectResult& result);

    Renderer& renderer_;
    const CommonOptions& options_;
    std::string scene_;
    Camera overview_;
    float closest_;
    Camera now_;
    bool aimed_ = false;  // now_ was aimed at a contact before
};

// "12K" style counts for captions.
std::string shortCount(double value);

}  // namespace samples
