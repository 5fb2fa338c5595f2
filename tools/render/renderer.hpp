// A tiny headless renderer: draws meshes into an offscreen image with one colour per
// object and the colliding triangles highlighted, and reads the image back for a PNG.
//
// It draws straight from vertex buffers, the engine's own included: a GPU mesh that a
// compute shader writes is drawn from the same buffer vkcollide reads (addGpuMesh), so
// the picture shows exactly the geometry that was tested.
#pragma once

#include "render/engine.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/scene.hpp"

namespace render {

using Rgb = std::array<float, 3>;

// A colour per object index (muted, so highlighted triangles stand out).
Rgb objectColour(std::size_t index);

struct Camera {
    vkcollide::Float3 eye{0, 2, 6};
    vkcollide::Float3 target{0, 0, 0};
    vkcollide::Float3 up{0, 1, 0};
    float fov_degrees = 40.0f;
    float near_plane = 0.05f, far_plane = 200.0f;
};

using DrawId = std::uint32_t;

struct Box {
    vkcollide::Float3 min, max;
};

class Renderer {
public:
    Renderer(Engine& engine, std::uint32_t width, std::uint32_t height);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // A host mesh, uploaded. `dynamic`: its vertices change (updateVertices).
    DrawId addMesh(const vkcollide::HostMesh& mesh, Rgb colour, bool dynamic = false);
    // Another copy of a mesh already added (same buffers), with its own colour,
    // transform and highlights.
    DrawId addInstance(DrawId of, Rgb colour);
    // Positions the GPU writes: x, y, z floats of vertex i at byte offset + i * stride of
    // `vertices`; `indices` holds 3 uint32 per triangle. The buffers stay the caller's.
    DrawId addGpuMesh(const Buffer& vertices, VkDeviceSize offset, std::uint32_t stride, const Buffer& indices,
                      VkDeviceSize index_offset, std::uint32_t triangle_count, Rgb colour);
    void updateVertices(DrawId id, std::span<const vkcollide::Float3> positions);
    // New geometry for a mesh added with addMesh (any size; its highlights are cleared).
    void replaceMesh(DrawId id, const vkcollide::HostMesh& mesh);
    void setTransform(DrawId id, const vkcollide::Transform3x4& object_to_world);

    // Colliding triangles of the next frame. They are drawn in the highlight colour, and
    // those small on the screen again on top of everything with a halo a few pixels wide,
    // so that a contact hidden behind a surface or smaller than a pixel still shows.
    void clearHighlights();
    void highlight(DrawId id, std::uint32_t triangle);
    // The world box of the highlighted triangles as drawn (with their draws' transforms and
    // current vertices, the GPU's included), measured on the GPU; none without highlights.
    std::optional<Box> highlightBox();

    // Renders every mesh and returns the image, RGBA8, rows top to bottom.
    const std::vector<std::uint8_t>& render(const Camera& camera);
    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }

private:
    struct Draw {
        Buffer own_vertices, own_indices, highlights;  // own_*: empty for GPU meshes and instances
        VkDeviceAddress vertices = 0, indices = 0;
        std::uint32_t first_float = 0, stride_floats = 3, triangles = 0;
        Rgb colour{};
        vkcollide::Transform3x4 transform{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        std::uint32_t hot = 0;  // triangles highlighted
    };
    DrawId addDraw(Draw draw);
    void uploadMesh(Draw& draw, const vkcollide::HostMesh& mesh, bool dynamic);
    VkPipeline createPipeline(bool depth_tested);
    // Frame parameters, then one DrawParams per draw, into params_.
    void writeParams(const Camera& camera);

    Engine& engine_;
    std::uint32_t width_, height_;
    VkImage colour_ = VK_NULL_HANDLE, depth_ = VK_NULL_HANDLE;
    VkDeviceMemory colour_memory_ = VK_NULL_HANDLE, depth_memory_ = VK_NULL_HANDLE;
    VkImageView colour_view_ = VK_NULL_HANDLE, depth_view_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE, hot_pipeline_ = VK_NULL_HANDLE;
    Engine::ComputePipeline box_pipeline_;
    Buffer readback_, params_, box_words_;
    std::vector<Draw> draws_;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace render
