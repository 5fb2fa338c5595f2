// Layouts shared by the renderer (C++) and its shaders (GLSL, scalar layout).
#ifndef VKCOLLIDE_TOOLS_RENDER_H
#define VKCOLLIDE_TOOLS_RENDER_H

#ifdef __cplusplus
#include <cstdint>
namespace render::gpu {
using uint = std::uint32_t;
struct vec4 { float x, y, z, w; };
struct mat4 { float m[16]; };  // column-major, as GLSL reads it
#define RENDER_REF(type) std::uint64_t
#else
#define RENDER_REF(type) type
#endif

#ifndef __cplusplus
layout(buffer_reference, scalar) readonly buffer Floats { float f[]; };
layout(buffer_reference, scalar) readonly buffer Uints { uint u[]; };
#endif

// One mesh to draw: positions pulled from any buffer (the engine's GPU meshes too), one
// highlight bit per triangle, an object colour and an object-to-world transform.
#ifdef __cplusplus
struct DrawParams {
#else
layout(buffer_reference, scalar) readonly buffer DrawParams {
#endif
    RENDER_REF(Floats) vertices;    // vertex i's x, y, z at floats first_float + i * stride_floats
    RENDER_REF(Uints) indices;      // 3 per triangle
    RENDER_REF(Uints) highlights;   // bit t of word t / 32: triangle t collides
    uint first_float;
    uint stride_floats;
    vec4 colour;
    vec4 model[3];                   // rows of the 3x4 object-to-world transform
};

#ifdef __cplusplus
struct FrameParams {
#else
layout(buffer_reference, scalar) readonly buffer FrameParams {
#endif
    mat4 view_proj;
    vec4 light;      // direction towards the light, world space
    vec4 highlight;  // colour of colliding triangles
    vec4 halo;       // colour of the halo drawn around them
};

// What one draw call draws (RenderPush::pass): every triangle (depth-tested), or only the
// colliding ones on top of everything: grown by the halo's width in the halo colour, then
// as they are in the highlight colour.
#define RENDER_PASS_ALL 0u
#define RENDER_PASS_HALO 1u
#define RENDER_PASS_HOT 2u

// The box of the colliding triangles in world space (highlight_box.comp): min x, y, z then
// max x, y, z, each a float mapped to a uint that orders as the float does.
#ifndef __cplusplus
layout(buffer_reference, scalar) buffer BoxWords { uint v[6]; };
#endif

#ifdef __cplusplus
struct RenderPush {
    std::uint64_t frame;
    std::uint64_t draw;
    uint pass;         // RENDER_PASS_*
    float halo_width;  // pixels
    float width, height;  // of the image, pixels
};
struct BoxPush {
    std::uint64_t draw;
    std::uint64_t box;
    uint triangles;
};
}  // namespace render::gpu
#endif

#endif
