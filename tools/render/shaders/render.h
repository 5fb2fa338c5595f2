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
};

#ifdef __cplusplus
struct RenderPush {
    std::uint64_t frame;
    std::uint64_t draw;
};
}  // namespace render::gpu
#endif

#endif
