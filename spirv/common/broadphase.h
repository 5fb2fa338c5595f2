// Data shared by the broad-phase shaders (GLSL) and the host (C++): one definition of
// every buffer layout. GLSL sees buffer references; C++ sees 64-bit addresses. The
// tunables (work shape, thresholds, automatic settings) are in config.h.
#ifndef VKCOLLIDE_BROADPHASE_H
#define VKCOLLIDE_BROADPHASE_H

#include "config.h"

#ifdef __cplusplus
#include <cstdint>
namespace vkcollide::gpu {
using uint64_t = std::uint64_t;
struct vec4 { float x, y, z, w; };
#define VKC_ADDRESS(type) std::uint64_t
#else
#define VKC_ADDRESS(type) type
#endif
// Key layout, low word: bit 31 = back-facing, bit 30 = open surface, bits 0..29 = triangle.
VKC_CONST kKeyBackFacing = 0x80000000u;
VKC_CONST kKeyOpen = 0x40000000u;
VKC_CONST kKeyTriangleMask = 0x3FFFFFFFu;
VKC_CONST kMaxTriangles = 0x40000000u;
// Per-ray fragment counts as the sampling passes count them (Frame::ray_fragments, one
// uint64 per ray): closed surfaces in bits 0..30, bit 31 set when a thin triangle touches
// the ray (coverage on), open surfaces in bits 32..63. No field can overflow: a ray gets at
// most one fragment per triangle, and there are fewer than kMaxTriangles (2^30).
VKC_CONST kFragmentsThin = 0x80000000u;      // in the low word
VKC_CONST kFragmentsClosedMask = 0x7FFFFFFFu;  // the low word's count
// Per-ray counts the peeling passes read (Frame::counts, one uint per ray, written by
// reduce_max from ray_fragments): closed surfaces in the low 15 bits, open ones in the high
// half. Bit 15 (kCountThin) marks a collision ray that needs no peeling: a thin triangle
// touches it, or it has more than kMaxRayFragments (config.h) fragments: too deep to peel.
// Such rays are left out of the peeled depth (conservative: they only add candidates).
VKC_CONST kCountClosedMask = 0x7FFFu;
VKC_CONST kCountThin = 0x8000u;
#ifdef __cplusplus
static_assert(kMaxRayFragments <= kCountClosedMask, "a peeled ray's closed count must fit its 15-bit field");
#endif
// PixelState.flags
VKC_CONST kRayDone = 1u;
VKC_CONST kRayCollision = 2u;
VKC_CONST kParityFront = 4u;
VKC_CONST kParityBack = 8u;
VKC_CONST kRayNear = 16u;  // depth-aware: the ray met a near pair; its interval is in bundle_depth level 0
// ObjectGpu.flags
VKC_CONST kObjectOpen = 1u;
VKC_CONST kObjectIndex16 = 2u;
VKC_CONST kObjectCheckOnGpu = 4u;  // geometry only on the GPU: check indices and positions there
VKC_CONST kObjectSelfCollide = 8u; // its own triangles may collide (depth-aware near pairs)
VKC_CONST kMaxLevels = 16u;
// Push.coverage: how the sampling passes treat thin triangles (kThinInradiusPx in
// config.h; docs/stability.md). With coverage on, every ray a thin triangle touches
// becomes a collision ray (count.frag flags it, peel_init marks it).
VKC_CONST kCoverageCentre = 0u;         // the hardware rule only (pixel centres)
VKC_CONST kCoverageDilate = 1u;         // thin triangles enlarged in sample.vert (any device)
VKC_CONST kCoverageSkipThin = 2u;       // conservative raster, pass 1: every triangle but thin ones
VKC_CONST kCoverageOnlyThin = 3u;       // conservative raster, pass 2 (overestimating pipeline): thin ones

// One registered mesh instance.
struct ObjectGpu {
    VKC_ADDRESS(uint64_t) vertices;  // address of vertex 0's position (offset applied)
    VKC_ADDRESS(uint64_t) indices;   // address of index 0
    uint vertex_stride;              // bytes between positions
    uint vertex_count;
    uint triangle_count;
    uint triangle_base;              // global id of triangle 0
    uint flags;                      // kObjectOpen, kObjectIndex16
    uint vertex_base;                // index of vertex 0 in its bounds batch (CommonStages::recordFront)
    vec4 model[3];                   // rows of the 3x4 object-to-world transform
};

// World -> normalised sampling space: x, y in [0,1] across the image, z in [0,1] depth.
struct Projection {
    vec4 row[3];
    float open_epsilon;  // depth-proximity threshold of open surfaces, in normalised depth
    float world_to_depth;
    float closed_epsilon;  // closed surfaces: a gap this small (normalised depth) between leaving one and entering the next touches
    uint pad1;
};

// Depth-aware separation: one triangle's sampling-space box (x0, y0, x1, y1, as the
// sparse boxes), depth range padded by a bound on its rounding error (kDepthRoundingPad),
// and its plane in pixel units, from the triangle-bounds pass. The plane gives a ray's
// depth on the triangle the same way whichever backend sampled it (fragment depths
// differ in the last bits between rasterizers).
struct TriangleBounds {
    vec4 box;
    float zmin, zmax;
    float slope;   // |dz/dx| + |dz/dy| per pixel; 3.4e38 where the projection is degenerate
    float plane;   // depth at pixel coordinates (0, 0): z = plane + dzdx * x + dzdy * y
    float dzdx, dzdy;
};

// Per-ray state of the peeling.
struct PixelState {
    VKC_ADDRESS(uint64_t) last_front;  // key of the last fragment peeled from the front
    VKC_ADDRESS(uint64_t) last_back;   // ... from the back (dual peeling)
    uint peeled;                        // front count (low 16) | back count (high 16)
    uint flags;
};

// Header::loop_limit. llvmpipe ends a shader invocation's loops once their iterations
// together pass 65,535, without an error (DeviceInfo::loop_iteration_limit); a pass whose
// loops can run that long checks that each ran to its end and sets its bit if not.
VKC_CONST kLoopLimitSplat = 1u;  // tri_bounds: an edge-on triangle's depth did not reach every ray near it
VKC_CONST kLoopLimitDraw = 2u;   // compute sampling: a work item's tiles were not all drawn

// Small results the host reads after each submission.
struct Header {
    uint depth_complexity;  // max fragments on one ray that is peeled (not thin, not deep)
    uint record_count;      // packed records written
    uint collision_rays;
    uint max_row_count;     // paper packing: most records in one row
    uint bounds[6];         // ordered-float min u,v,d then max u,v,d (auto fit)
    // GPU-side input checks (kObjectCheckOnGpu): how many triangles failed, and one of them.
    uint bad_index_count, bad_index_object, bad_index_triangle;
    uint bad_vertex_count, bad_vertex_object, bad_vertex_triangle;
    uint cs_small;          // compute sampling: triangles drawn by one invocation each
    uint cs_big;            // ... triangles drawn in tiles
    uint cs_items;          // ... tile work items (workgroups) for the big ones
    uint loop_limit;        // kLoopLimit*: a pass's loops ended early (llvmpipe's loop limit); the run fails
    uint64_t fragments;     // sum over rays of their fragment counts (reduce-max)
    uint deep_rays;         // rays with more than kMaxRayFragments fragments (collision rays, not peeled)
    uint subnormal_vertices;  // vertices with a subnormal coordinate (bounds pass): GPUs flush them to zero
};

// Everything a broad-phase shader needs, uploaded once per detection.
struct Frame {
    VKC_ADDRESS(uint64_t) objects;      // ObjectGpu[object_count]
    VKC_ADDRESS(uint64_t) projection;   // Projection
    VKC_ADDRESS(uint64_t) header;       // Header (host-visible)
    VKC_ADDRESS(uint64_t) counts;       // uint[N*N]
    VKC_ADDRESS(uint64_t) front_keys;   // uint64[N*N]
    VKC_ADDRESS(uint64_t) back_keys;    // uint64[N*N]
    VKC_ADDRESS(uint64_t) state;        // PixelState[N*N]
    VKC_ADDRESS(uint64_t) bundles;      // vec4[sum of (N>>l)^2]: the ray-bundle mipmap
    VKC_ADDRESS(uint64_t) sparse;       // vec4[triangle_count]: kept box or empty
    VKC_ADDRESS(uint64_t) records;      // CandidateTriangle[] (host-visible)
    VKC_ADDRESS(uint64_t) scratch;      // uint[]: packing scratch
    VKC_ADDRESS(uint64_t) ray_image;    // uint[N*N] collision flags for inspection, or 0
    uint resolution;                    // N, a power of two
    uint levels;                        // log2(N) + 1
    uint object_count;
    uint triangle_count;
    uint dual;                          // 1: peel from the front and the back at once
    uint pack_rows;                     // rows of the packing texture
    uint pack_blocks;                   // workgroups of the scan packing
    float direction_basis[12];          // u, v, d rows and (unused) for auto fit
    float open_epsilon_world;           // open-surface proximity in world units
    float fit_margin;                   // relative margin of the auto fit
    float closed_epsilon_world;         // closed-surface touching gap in world units (0: exact ties only)
    uint level_offset[kMaxLevels];      // first texel of each mip level in `bundles`
    VKC_ADDRESS(uint64_t) compute_sampling;  // CsFrame (compute sampling backend), or 0
    VKC_ADDRESS(uint64_t) method;            // a broad-phase method's own frame (its layout), or 0
    VKC_ADDRESS(uint64_t) ray_fragments;     // uint64[N*N]: fragments per ray (kFragments*), counted by sampling
    // Depth-aware separation (docs/broadphase.md); addresses 0 and depth_aware 0 when off.
    // Depth intervals are vec2 (lo, hi) in normalised depth; lo > hi is empty.
    VKC_ADDRESS(uint64_t) tri_bounds;        // TriangleBounds[triangle_count]
    VKC_ADDRESS(uint64_t) bundle_depth;      // vec2 per texel of `bundles`: the bundle's depth interval
    VKC_ADDRESS(uint64_t) sparse_depth;      // vec2[triangle_count]: kept depth range, beside `sparse`
    VKC_ADDRESS(uint64_t) ray_depth_image;   // vec2[N*N] each ray's interval for inspection, or 0
    VKC_ADDRESS(uint64_t) edge_depth;        // uvec2[N*N]: depths of edge-on triangles near each ray
    uint depth_aware;                        // 1: depth-aware separation
};

// Pushed per dispatch or draw.
struct Push {
    VKC_ADDRESS(uint64_t) frame;
    uint object;
    uint step;
    uint level;
    uint coverage;  // kCoverage* (sampling passes only)
};

// ---- Compute sampling backend (src/broad/peeling/sampling/compute_sampler.hpp) -----------------------
// Object sampling without the graphics pipeline: edge-function rasterization in compute
// with the rasterizer's coverage rule. Triangles whose pixel box is small are drawn by one
// invocation each; bigger ones are cut into kCsTile x kCsTile pixel tiles, one workgroup
// (one invocation per pixel) per work item of `tiles_per_item` consecutive tiles (more in a
// triangle that would otherwise take more than kCsMaxTriangleItems items). Peeling
// either draws the triangles again per step, or (fragment lists) the count pass stores
// every ray's keys (a gather pass redraws when a ray had more than list_layers) and each
// step picks the next keys per pixel from them.
VKC_CONST kCsMaxGroupsX = 65535;     // indirect dispatch width (the guaranteed minimum of
                                     // maxComputeWorkGroupCount[0] and [1])
VKC_CONST kCsMaxTriangleTiles = 0x400000u;  // (16384 / kCsTile)^2: the tiles of a triangle
                                            // that covers the largest image
VKC_CONST kCsSmallExtent = 16384;    // one-invocation triangles span at most this many
                                     // sub-pixel units per axis (edge functions fit 32 bits)
VKC_CONST kCsTieTopLeft = 0u;        // sample on an edge: covered by left and top edges
VKC_CONST kCsTieBottomLeft = 1u;     // ... by left and bottom edges

// One triangle after setup, 48 bytes. Pixel (i, j)'s sample sits at (i, j) << subpixel
// bits in these coordinates; vertices are ordered so the edge functions are positive inside.
struct CsTriangle {
    int x[3];
    int y[3];
    uint box_lo;        // first pixel of the box: x | y << 16 (box_lo > box_hi: culled)
    uint box_hi;        // last pixel (inclusive)
    uint key_low;       // triangle id | kKeyOpen | kKeyBackFacing
    float z;            // depth at the centre of pixel box_lo
    float dzdx, dzdy;   // depth step per pixel
};

struct CsCounters {
    uint small_count;     // entries of CsFrame.small
    uint big_count;       // entries of CsFrame.big
    uint item_count;      // entries of CsFrame.items
    uint tiles_per_item;  // tiles one workgroup draws (1 unless the item budget is short)
    uint small_groups;    // workgroups of the one-invocation triangles
    uint total_groups;    // small_groups + item_count
    uint pad0, pad1;
    uint64_t tiles;       // tiles of all big triangles
};

struct CsFrame {
    VKC_ADDRESS(uint64_t) triangles;  // CsTriangle[triangle_count]
    VKC_ADDRESS(uint64_t) small;      // uint[triangle_count]: one-invocation triangles
    VKC_ADDRESS(uint64_t) big;        // uint[triangle_count]: tiled triangles
    VKC_ADDRESS(uint64_t) items;      // uvec2[item_capacity]: (triangle, item of it)
    VKC_ADDRESS(uint64_t) counters;   // CsCounters
    VKC_ADDRESS(uint64_t) args;       // VkDispatchIndirectCommand of the draw dispatches
    VKC_ADDRESS(uint64_t) fill;       // uint[N*N]: keys stored so far per ray (gather pass)
    VKC_ADDRESS(uint64_t) fragments;  // uint64[layers * N*N]: key k of ray p at k*N*N + p
    uint item_capacity;               // > triangle_count
    uint subpixel_bits;               // VkPhysicalDeviceLimits::subPixelPrecisionBits
    uint small_box;                   // most pixels in a one-invocation triangle's box
    uint tie_rule;                    // kCsTieTopLeft or kCsTieBottomLeft
    uint fuse_first_step;             // 1: the count pass also does peeling step 0
    uint depth_snapped;               // 1: depth plane through the snapped vertices
    uint list_layers;                 // keys the count pass stores per ray (0: none)
    uint list_capacity;               // layers `fragments` holds: no pass writes or reads past it
};

#ifdef __cplusplus
}  // namespace vkcollide::gpu
#endif
#endif
