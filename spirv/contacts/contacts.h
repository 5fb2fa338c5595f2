// Data shared by the contact stage's shaders (GLSL) and its host side (C++,
// src/contacts/): buffer layouts, limits and flags. docs/contacts.md has the method.
//
// Grid space: x, y, z = (dot(axis, world) - origin) / h for the axes u, v, d of the sampling
// basis (orthonormal, d the ray direction) and h the pixel side in world units, so the
// three coordinates share one unit and pixel (i, j)'s ray runs along z through
// (i + 0.5, j + 0.5). Sums are accumulated in grid units and scaled to world units on
// the host.
#ifndef VKCOLLIDE_CONTACTS_H
#define VKCOLLIDE_CONTACTS_H

#include "common/broadphase.h"  // VKC_ADDRESS, VKC_CONST, ObjectGpu

#ifdef __cplusplus
namespace vkcollide::gpu {
using int64_t = std::int64_t;
#endif

// Resolutions accepted (rays across the longer side of the region where closed objects'
// boxes overlap) and the automatic one: 128 keeps the volume of two overlapping spheres
// within 1 % and the normal within a degree (docs/contacts.md), at 16K rays.
VKC_CONST kMinContactResolution = 16;
VKC_CONST kMaxContactResolution = 4096;
VKC_CONST kDefaultContactResolution = 128;
// A fragment stands for 1 / |cos| pixels of surface (the surface seen at an angle); capped
// here, at 87 degrees from the ray, so that surfaces seen edge-on do not dominate the
// boundary normal with few, noisy samples.
VKC_CONST_FLOAT kContactMaxWeight = 20.0;

// Workgroup size of every contact-stage shader (the tile pass: one invocation per pixel
// of a kContactsTile x kContactsTile tile).
VKC_CONST kContactsGroupSize = 64;
VKC_CONST kContactsTile = 8;
// A triangle whose pixel box has at most this many pixels is drawn by the invocation that
// set it up; bigger ones are cut into tiles, one workgroup each.
VKC_CONST kContactsSmallBox = 64;
// A big triangle takes at most this many work items of the tile pass; beyond, each item
// draws several consecutive tiles (contactTilesPerItem). The setup pass writes a
// triangle's items in one loop, and llvmpipe ends a shader invocation's loops past 65,535
// iterations without an error (DeviceInfo::loop_iteration_limit): a triangle over a
// 4096^2 ray grid has 262,144 tiles, 64 per item with this.
VKC_CONST kContactsMaxTriangleItems = 4096;
// Closed objects a ray may be inside at once; deeper nesting ignores the extra objects on
// that ray (counted in ContactsHeader::nested_rays).
VKC_CONST kContactsMaxInside = 16;
// Object pairs a ray accumulates locally before it hands its sums to the table; further
// pairs on the same ray are added to the table at once (slower, same result).
VKC_CONST kContactsRayPairs = 4;
// ContactsPair::sums
VKC_CONST kSumVolume = 0u;    // sum of overlap lengths (grid units^3: pixel area = 1)
VKC_CONST kSumMoment = 1u;    // 1..3: first moments x, y, z (centroid = moment / volume)
VKC_CONST kSumNormal = 4u;    // 4..6: boundary normals of A inside B minus B inside A (u, v, d)
VKC_CONST kSumArea = 7u;      // boundary area sampled (both surfaces)
VKC_CONST kSumCount = 8u;

// ContactsHeader::flags: a buffer was too small; the host grows it and runs again.
VKC_CONST kContactsOverflowLayers = 1u;  // a ray had more fragments than `layers`
VKC_CONST kContactsOverflowItems = 2u;   // more tile work items than `item_capacity`
// ... and an error: a ray's sort and walk need more loop iterations than `loop_guard`.
VKC_CONST kContactsLoopLimit = 4u;

// CtTriangle::key
VKC_CONST kCtKeyObject = 0x7FFFFFFFu;
VKC_CONST kCtKeyEntering = 0x80000000u;  // front facing: the ray enters the object here
VKC_CONST kCtSkipped = 0xFFFFFFFFu;      // key of a triangle not drawn (inactive object, no area)

struct ContactsParams {
    VKC_ADDRESS(uint64_t) objects;        // ObjectGpu[object_count]
    VKC_ADDRESS(uint64_t) object_active;  // uint[object_count]: 1 = closed and in a candidate pair
    VKC_ADDRESS(uint64_t) bounds;         // uint[6 * object_count]: ordered-float world boxes, all minima (x, y, z) then all maxima
    VKC_ADDRESS(uint64_t) triangles;      // CtTriangle[triangle_count]
    VKC_ADDRESS(uint64_t) items;          // uvec2[item_capacity]: (triangle, first tile)
    VKC_ADDRESS(uint64_t) counts;         // uint[width * height]: fragments per ray
    VKC_ADDRESS(uint64_t) entries;        // uvec2[width * height * layers]: (depth bits, triangle), ray-major
    VKC_ADDRESS(uint64_t) table;          // ContactsPair[table_mask + 1]
    VKC_ADDRESS(uint64_t) header;         // ContactsHeader
    VKC_ADDRESS(uint64_t) args;           // uint[3]: the tile pass's indirect dispatch
    vec4 grid[3];                         // world -> grid: row k = (axis_k / h, -origin_k / h)
    uint width, height;                   // rays per side (x, y)
    uint layers;                          // entry slots per ray
    uint item_capacity;
    uint table_mask;                      // table size - 1 (a power of two)
    uint triangle_count;
    uint object_count;
    uint max_groups_x;                    // dispatch rows (maxComputeWorkGroupCount[0])
    float max_weight;                     // cap of 1 / |cos| for a fragment's area
    float fixed_scale;                    // grid-unit sums -> int64 fixed point
    // Most loop iterations a subgroup of the walk may run (~0: no bound): set below
    // DeviceInfo::loop_iteration_limit where the device ends longer loops silently.
    uint loop_guard;
    uint pad1;
};

struct ContactsHeader {
    uint flags;
    uint max_fragments;  // most fragments on one ray (the layers a rerun needs)
    uint items_needed;   // tile work items wanted
    uint item_count;     // tile work items appended
    uint nested_rays;    // rays inside more than kContactsMaxInside objects at once
    uint fragments;      // fragments drawn
    uint overlap_rays;   // rays that crossed an overlap of two objects
    uint pad;
};

// One triangle after setup (72 bytes), in grid space.
struct CtTriangle {
    float x[3], y[3];  // projected vertices
    float z0, gx, gy;  // depth plane: z = z0 + gx x + gy y
    float n[3];        // unit outward normal (u, v, d)
    float weight;      // boundary area per covered pixel: 1 / |cos(normal, ray)|, capped
    uint key;          // object | kCtKeyEntering, or kCtSkipped
    int box[4];        // covered pixel box: x0, y0, x1, y1 (inclusive)
};

// One object pair (a < b, indices of the run's objects) of the open-addressing table,
// 80 bytes. The host writes the keys (b_plus_one = 0: empty slot) and zero sums; the
// walk adds fixed-point sums (two's complement in uint64 atomics) and, in its second
// pass, the extent of the overlap along the normal as ordered floats.
struct ContactsPair {
    uint a, b_plus_one;
    uint extent_min, extent_max;  // ordered floats, grid units
    int64_t sums[kSumCount];
};

#ifdef __cplusplus
}  // namespace vkcollide::gpu
#endif
#endif
