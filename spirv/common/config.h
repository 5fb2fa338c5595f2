// Every tunable of vkcollide in one place, shared by the shaders (GLSL) and the host (C++),
// each with why it has its value. Buffer layouts and bit assignments are not tunables:
// they live in broadphase.h. Changing a value here changes speed or the automatic
// settings, never the contract (a value that would break one says so).
#ifndef VKCOLLIDE_CONFIG_H
#define VKCOLLIDE_CONFIG_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace vkcollide::gpu {
using uint = std::uint32_t;
#define VKC_CONST inline constexpr uint
#define VKC_CONST_FLOAT inline constexpr float
#else
#define VKC_CONST const uint
#define VKC_CONST_FLOAT const float
#endif

// ---- GPU work shape --------------------------------------------------------------------
// Workgroup size of every per-pixel and per-triangle compute shader (a multiple of every
// subgroup size in use; the workgroup reduce/scan helpers assume a power of two).
VKC_CONST kGroupSize = 256;
// Row width of the paper's packing texture (count / shift / move). pack_rowcount reduces a
// row with the workgroup helpers, so it must equal kGroupSize.
VKC_CONST kPackRowWidth = 256;

// ---- Image-space sampling --------------------------------------------------------------
// A triangle is thin when its projected inradius is below this many pixels: half a pixel
// diagonal, below which it may cover no pixel centre (sub-pixel, sliver, zero-area,
// edge-on); coverage Dilate/Conservative treats exactly these (docs/stability.md).
VKC_CONST_FLOAT kThinInradiusPx = 0.70710678f;
// The fitted projection maps the scene's depth range to [kDepthNear, kDepthNear +
// kDepthSpan]: a margin from 0 and 1, which the rasterizer clips.
VKC_CONST_FLOAT kDepthNear = 0.05f;
VKC_CONST_FLOAT kDepthSpan = 0.9f;
// Deepest ray that is peeled: a ray with more fragments (surfaces along it) is a collision
// ray at once, as if a layer cap had stopped it, and no run records more peeling steps
// than this. Peeling costs one pass over every triangle per layer, so this bounds the
// sampling time of pathological scenes (thousands of stacked surfaces, one triangle
// repeated: docs/stability.md); the rays it marks only add candidates for the exact
// narrow phase. At most 0x7FFF (the peeling passes' 15-bit closed count; broadphase.h).
VKC_CONST kMaxRayFragments = 1024;
// The sampling range (docs/stability.md, "Limits"). Every world-space coordinate must lie
// within +-kMaxWorldCoordinate and the sampled image must be at least kMinSamplingExtent
// wide (world units): then the projection's rows (1 / extent), every product of a row and
// a coordinate and every pixel are normal floats, which GPUs do not flush to zero (at
// 1e38 the rows are subnormal and flushed: every vertex fell on one pixel, 0 pairs). A
// host mesh beyond the range is refused, an engine mesh fails the GPU check (left out),
// a scene narrower than the minimum fails with LimitExceeded. Not a tunable: wider
// bounds reach subnormals.
VKC_CONST_FLOAT kMaxWorldCoordinate = 1e30f;
VKC_CONST_FLOAT kMinSamplingExtent = 1e-30f;

// ---- Depth-aware separation (docs/broadphase.md) ---------------------------------------
// Each triangle's depth range is padded by this fraction of the sum of the magnitudes of
// the terms of its depth (a dot product of four terms): a bound on the float rounding of
// the computed vertex depths (about 4 units in the last place; 16 are taken), so two
// triangles that share a point always get overlapping ranges. Windows (below) get this
// much more, absolute, against the rounding of the planes evaluated at the rays.
VKC_CONST_FLOAT kDepthRoundingPad = 1.0f / 1048576.0f;
VKC_CONST_FLOAT kFragmentDepthPad = 1.0f / 1048576.0f;
// A fragment's window: the depths its triangle's plane takes within kNearReachPx pixels
// of the ray (in x and in y), and its depth range within kNearRangePx pixels. Two
// consecutive fragments whose windows overlap are a near pair. First order, a ray lies
// within half a pixel of any point, so two surfaces that cross between rays still have
// overlapping windows on the rays around the crossing; one pixel leaves room for the
// surfaces' curvature, and the range (the vertices, where the neighbouring triangles
// start) for sharper bends. Larger: more triangles kept; smaller: pairs lost between rays
// (measured at reduced scale, docs/broadphase.md: reach 0.5 lost pairs the paper finds in
// an earlier form of the rule; range 4 instead of 2 kept up to 7 % more triangles and
// found no more pairs).
VKC_CONST_FLOAT kNearReachPx = 1.0f;
VKC_CONST_FLOAT kNearRangePx = 2.0f;
// Two triangles of one object whose normals are within 30 degrees (cos above this) look
// like the two sides of a silhouette on a grazing ray (steep, adjacent in depth); their
// slopes count as at most kSelfSlopeCap times a 45-degree surface's, or every silhouette
// of a self-colliding object would be a near pair (uncapped, 2.4x the downloads of two
// deep-overlapping blobs; capped for every pair of one object, a twisted bar lost 2 of 219
// pairs). Crossings at steeper angles keep their slopes.
VKC_CONST_FLOAT kSilhouetteCos = 0.8660254f;
VKC_CONST_FLOAT kSelfSlopeCap = 4.0f;
// A thin triangle (kThinInradiusPx) steeper than this many times a 45-degree surface (or
// degenerate in the image) is edge-on: its surface may be invisible to every ray (a box's
// side seen along it), so its depth range is left at every ray within kNearReachPx of it.
// Lower values also take the thin steep triangles of smooth silhouettes without finding
// more pairs (4: 1.6x the downloads of two deep-overlapping blobs, in an earlier form).
VKC_CONST_FLOAT kEdgeOnSlope = 1024.0f;
// Separation tests each bundle under a triangle's box this many mip levels finer than the
// paper's (which reads the four corner bundles of the coarsest level whose texels are as
// large as the box): up to (2^k + 1)^2 texels (a ring more for the near rays' grown
// boxes), each a (x, y, depth) box of its own. 2 kept about 7 % fewer triangles and
// found fewer pairs.
VKC_CONST kSeparationRefine = 1;

// ---- Compute sampling backend ----------------------------------------------------------
// Big triangles are drawn in kCsTile x kCsTile pixel tiles, one workgroup of kCsGroupSize
// (= kCsTile^2) invocations, one per pixel.
VKC_CONST kCsGroupSize = 64;
VKC_CONST kCsTile = 8;
// A big triangle takes at most this many work items; beyond, each item draws more tiles.
// One invocation of the bin pass writes all of a triangle's items, and llvmpipe ends a
// shader invocation's loops past 65,535 iterations without an error (DeviceInfo::
// loop_iteration_limit): a triangle over a 4096^2 image has 262,144 tiles. With 4,096 it
// draws 64 tiles per item (4,096 workgroups), at 16384^2 1,024; a test at 1024^2 (16,384
// tiles, 4 per item) runs the path on lavapipe in CI.
VKC_CONST kCsMaxTriangleItems = 4096;

#ifdef __cplusplus
// ---- Host only -------------------------------------------------------------------------
// Automatic resolution (CollisionWorld::resolveSettings): about this many pixels along a
// typical triangle edge across the scene's extent, a power of two within the bounds; the
// fallback when nothing can be measured (GPU meshes without typical_edge_length).
inline constexpr double kPixelsPerEdge = 4.0;
inline constexpr std::uint32_t kMinAutoResolution = 64, kMaxAutoResolution = 2048;
inline constexpr std::uint32_t kFallbackResolution = 512;
// Automatic resolution of the reliable method (cells per side, any integer): about this
// many cells per typical triangle edge across the scene's extent. H200,
// vkcollide_bench_cells: f = 2 was fastest on deep overlap (2.56M), the deforming pair and
// the self-intersecting scenes, f = 1 on the pile of 60 meshes (0.77 against 0.9 ms);
// counts by f in docs/reliable.md. Within the bounds, and at most kMaxCellsPerTriangle
// cells per triangle (a scene whose extent dwarfs its triangles -- an object far away --
// would otherwise pay N^2 cells of counts and scan for nothing). The fallback when no
// edge length is known (GPU meshes without typical_edge_length, first detection).
inline constexpr double kCellsPerEdge = 2.0;
inline constexpr std::uint32_t kMinAutoCells = 8, kMaxAutoCells = 4096;
inline constexpr double kMaxCellsPerTriangle = 16.0;
inline constexpr std::uint32_t kFallbackCells = 256;
// ... and cells no smaller than this many float ulps of the scene's largest coordinate:
// footprints are padded by about 6-10 ulps of the coordinates (docs/reliable.md), so finer
// cells far from the origin only multiply footprints and candidates (1e-3 features at 1e4:
// 128 cells needed 12 GiB of candidates, 3 cells a few MiB).
inline constexpr double kMinCellUlps = 16.0;
// The pair filter's answers are kept as a bit mask (n^2 bits: 2 MiB at 4096 objects,
// computed when objects or the filter change) up to this many live objects; beyond, the
// filter is called during each detection as the narrow phase needs it.
inline constexpr std::uint32_t kMaxFilterMaskObjects = 4096;
// Automatic open epsilon: this fraction of the open objects' typical edge length.
inline constexpr double kOpenEpsilonPerEdge = 0.5;
// Resolutions the broad phase accepts (powers of two); the mip chain of ray bundles needs
// log2(kMaxResolution) + 1 <= kMaxLevels levels.
inline constexpr std::uint32_t kMinResolution = 4, kMaxResolution = 16384;
// Relative margin of the automatic fit on each side of the image, so triangles on the
// scene's silhouette do not sit on the image border.
inline constexpr float kFitMargin = 1.0f / 64.0f;
// Multi-axis union (DetectSettings::peeling.axes = 3): kept boxes mapped back to world space are
// padded by this fraction of the image width against rounding.
inline constexpr double kKeptBoxPad = 1e-4;

// Sampling backend Auto (broad/peeling/sampling/backend_choice.hpp has the rule): compute below
// this many covered pixels per triangle on a GPU with raster hardware (quad-based
// rasterizers waste most of their work on tiny triangles: an inference, not measured) and
// on a CPU implementation (lavapipe on 2 cores: compute 3-4x faster at 7 px per triangle,
// raster about 2x faster from 24 px up).
inline constexpr double kTinyTriangleFragments = 1.0;
inline constexpr double kCpuComputeFragments = 8.0;
// Compute backend, defaults of ComputeSamplingTuning (H200 measurements in docs/results.md):
// most pixels in the box of a triangle drawn by one invocation (256 is 0.07 ms faster than
// 64 on 24-50 px triangles, 0.6 ms slower on 91 px ones at 4096^2);
inline constexpr std::uint32_t kCsSmallBox = 256;
// per-ray fragment lists while they need at most this many bytes, storing at least this
// many layers per ray in the count pass;
inline constexpr std::uint64_t kCsListBudgetBytes = std::uint64_t{1} << 30;
inline constexpr std::uint32_t kCsListLayers = 8;
// work items beyond one per triangle, so a scene of few big triangles keeps one tile per item.
inline constexpr std::uint32_t kCsExtraItems = 65536;
#endif

#ifdef __cplusplus
}  // namespace vkcollide::gpu

// ---- Narrow phase (host) ---------------------------------------------------------------
// Work sizes and thresholds of the CPU narrow phase (src/narrow/). None changes a result:
// every form and split gives the same pairs and responses to the bit.
namespace vkcollide::narrow {
// Validation (narrow_phase.cpp):
// Records per validation task.
inline constexpr std::size_t kValidateGrain = 16384;
// Sweep tiles per task: about kTasksPerThread tasks per thread (active tiles cluster where
// objects meet, so many small tasks balance better), at most this many.
inline constexpr std::size_t kMaxSweepGrain = 256;
inline constexpr std::size_t kTasksPerThread = 32;
// Box pairs a sweep task counts between looks at NarrowOptions::max_box_pairs (one atomic
// add per stride: nothing next to the sweep's nanoseconds per pair).
inline constexpr std::size_t kBoxBudgetStride = std::size_t{1} << 16;
// The narrow phase's CPU grid sweep (GridSweep, sweep_and_prune.cpp):
// Cell size in typical (median) box extents: high and deep, and wide. Cells are swept
// along x, so they can be long in x; the limit in x lets cells of a single object be
// skipped (docs/narrow_phase.md has the measurements).
inline constexpr double kGridCellExtent = 3.0;
inline constexpr double kGridCellExtentX = 8.0;
// At most one cell per box on average, this many slabs per axis.
inline constexpr double kGridMaxSlabs = 65535;
// Average cells per box allowed by the sampled estimate (large boxes are listed often);
// the exact count allowed before the grid is made coarser anyway.
inline constexpr double kGridMaxListingsPerBox = 4.0;
inline constexpr std::size_t kGridHardListingsPerBox = 12;
// Boxes sampled to choose the grid: enough for a stable median, independent of n.
inline constexpr std::size_t kGridSampleSize = 1024;
// Tiles: about one per this many boxes, at most this many, at most this many cells each.
inline constexpr std::size_t kGridBoxesPerTile = 512;
inline constexpr std::size_t kGridMaxTiles = 16384;
inline constexpr std::size_t kGridMaxTileCells = 1u << 16;
// Boxes per task while listing them in tiles: about two tasks per thread (each task has
// a count per tile), at least this many.
inline constexpr std::size_t kGridMinListGrain = 8192;
// Exact tests (exact_stage.cpp):
// Exact tests per task: about four tasks per thread, within [kMinTestGrain, kMaxTestGrain]:
// large enough to amortise the hand-out, small enough to balance (a test costs 0.05 to 1
// microseconds, more when the exact fallback runs) and, for the few hundred tests of a
// light contact, to spread them over the threads at all (a fixed 512 ran 650 tests as two
// tasks). Results do not depend on it: hits are concatenated in test order.
inline constexpr std::size_t kMinTestGrain = 32;
inline constexpr std::size_t kMaxTestGrain = 512;
// Results and responses (exact_stage.cpp, responses.cpp): items per task of the linear
// loops that build the result, and of those over slots.
inline constexpr std::size_t kResultGrain = 2048;
inline constexpr std::size_t kSlotGrain = 8192;
// Responses on the calling thread below this many colliding pairs (respondSerial), when
// the slots number at most kSlotsPerEnd per end plus kSlotsFree. From the single-thread
// cost (15 ns a pair here, against 29 for the parallel form run on one thread) and the
// H200 host's 0.205 ms for 7.2K pairs on 16 threads: serial is estimated at ~0.15 ms there.
inline constexpr std::size_t kSerialResponsesBelow = std::size_t{1} << 13;
// The Grouped form from this many threads on: on one thread it costs about twice the
// Serial form (5.1-7.7 against 2.3-2.4 ms for 596K pairs, touching scene), so two or
// three threads would gain little or nothing (the Sorted form it replaces cost 2-3 times
// the Serial one on two threads).
inline constexpr unsigned kGroupedFromThreads = 4;
inline constexpr std::size_t kSlotsPerEnd = 4;
inline constexpr std::size_t kSlotsFree = 4096;
// The pair path (pair_narrow_phase.cpp, pair_keys.cpp, sorted_pairs.cpp, slots.cpp): pairs
// per task of its loops;
inline constexpr std::size_t kPairUpGrain = 1024;
inline constexpr std::size_t kPairKeyGrain = 2048;
inline constexpr std::size_t kSortedPairGrain = 8192;
// The parallel form numbers slots through one marker per id while ids span at most this
// many per input pair (plus a constant); beyond, through sorting the pairs' ends.
inline constexpr std::size_t kDenseIdsPerPair = 8;
inline constexpr std::size_t kDenseIdsFree = std::size_t{1} << 16;
// The serial form's radix digits: at most this wide, and about as many buckets as ends
// (a digit's buckets are cleared and summed once per call), at least kMinDigitBits.
inline constexpr int kMaxDigitBits = 11;
inline constexpr int kMinDigitBits = 4;
// Digits times buckets for 32-bit ids: at most ceil(32 / w) * 2^w for w in [4, 11], 3 * 2048.
inline constexpr std::size_t kCountCapacity = 3 * 2048;
// A run of keys sharing a lower slot longer than this is sorted by std::sort.
inline constexpr std::size_t kInsertionRun = 16;
// Triangles per block of the sorted pairs' slot numbering.
inline constexpr std::size_t kSlotMarkBlock = std::size_t{1} << 16;
// Slots per gather task: a task walks the objects and the sorted GPU table from its first
// slot on, so it starts with two binary searches. At most kMaxGatherGrain; down to
// kMinGatherGrain so that the thousand-odd slots of a light contact spread over about
// two tasks per thread (each slot is a few cache misses: threads overlap them), and on
// the calling thread alone below 2 * kMinGatherGrain (a loop that wakes a sleeping
// worker costs the caller more than gathering them).
inline constexpr std::size_t kMaxGatherGrain = 1024;
inline constexpr std::size_t kMinGatherGrain = 256;
// The gather is bound by memory latency, not arithmetic: each slot loads three indices
// from its mesh, then three positions they name, both usually cache misses (a pile's
// meshes are megabytes, and between two detections the GPU wait and the engine evict
// them). Slot s prefetches the indices of slot s + kIndicesAhead and, those having
// arrived meanwhile, the positions of slot s + kPositionsAhead, so several slots' misses
// overlap instead of following one another.
inline constexpr std::size_t kIndicesAhead = 8;
inline constexpr std::size_t kPositionsAhead = 4;
}  // namespace vkcollide::narrow
#endif
#endif
