// vkcollide: what a detection is asked to do (CollisionWorld::detect() and its kin,
// vkcollide/world.hpp): the method, its resolution and direction, and each method's settings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "vkcollide/contacts.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

// PackingMethod, Coverage, BadObjectPolicy, SamplingBackend: vkcollide/types.hpp.

// Every field left empty is chosen from the scene (DetectStats::settings_note says how).
//
// The method (DetectSettings::method), and what it reads:
//
// Reliable (the default). A grid of N x N cells across the image plane of `direction`
// (the grid's square fitted to the scene, or `region`; cells on its border reach to
// infinity). Every triangle is listed in each cell its projection may touch, with an
// interval that holds its depth over that cell, both grown by bounds on float rounding;
// pairs of triangles whose intervals overlap in a cell are candidates; a conservative
// double-precision triangle test on the GPU drops those it proves disjoint; the exact
// decision takes the rest: on the GPU where the device has shaderFloat64
// (ReliableSettings::exact), so that only intersecting pairs are read back, else in the
// CPU narrow phase, which reads the survivors (pairs of triangle ids, plus the world
// vertices of engine meshes' triangles). Guarantee: every pair of triangles that intersect —
// touching included (a shared point, an edge on a face, coplanar overlap, degenerate and
// sliver triangles) — is found, at any resolution and along any direction; resolution
// and direction change the speed only (docs/reliable.md has the proof and its
// assumptions: positions, transform entries and world coordinates below 2^62 in
// magnitude; an object beyond that is treated as a bad object, see bad_objects).
// Cost: GPU passes over every triangle (its cells), every cell (a sweep) and every
// candidate pair (the filter); about 100 bytes per triangle, 20 per footprint (2 to 10 per
// triangle at the automatic resolution) and 12 per candidate of device memory. On the
// host: with the exact decision on the GPU, the intersecting pairs (sorted on the GPU and
// read at 8 bytes each where there are many: ReliableSettings::pair_sort) are named and
// given their responses; with it on the CPU, the surviving pairs (within a few per cent of
// the intersecting ones for different objects; more for self-collision) are read, in
// place, and tested. One submission; nothing is measured first (measured times:
// docs/results.md).
// It reads the top-level fields (resolution: cells per side), `reliable`, `contacts`,
// `proximity` and `limits`; it ignores `peeling` (it shapes the sampling of rays, which
// it does not do), except that it runs peeling.axes = 3 as 1 (one grid finds everything;
// the note says so).
//
// Peeling (the paper). Depth peeling along N x N parallel rays, the triangles near rays
// that cross two surfaces read back and paired on the host. Misses what no ray centre
// sees (sub-pixel, sliver and edge-on triangles, touching contacts: docs/stability.md
// measures each case and the settings that mitigate it). It reads the top-level fields
// (resolution: rays per side), `peeling`, `contacts` and `limits`; `reliable` and
// `proximity` belong to the reliable method (what they ask for is refused by name here).

// Read only by the peeling method (DetectMethod::Peeling).
struct PeelingSettings {
    // Most layers to peel; rays deeper than this count as collision rays (conservative).
    // 0: as many as the scene's depth complexity (measured), no more.
    std::uint32_t layer_cap = 0;
    bool dual = false;  // peel from the front and the back at once (half the passes)
    PackingMethod packing = PackingMethod::Scan;
    SamplingBackend backend = SamplingBackend::Auto;
    // Open surfaces: two hits closer than this along a ray (world units) may collide.
    // Automatic: half the typical edge length of the open objects.
    std::optional<float> open_epsilon;
    // detect() only: measure the depth complexity before peeling (one extra host wait,
    // exactly the layers needed). Off, and always in submit(): peel as many layers as the
    // last detection measured (rays that need more become collision rays and the
    // statistics say so); the first detection of a world measures.
    bool measure_layers = true;

    // Beyond the paper (docs/stability.md measures each on the failure cases):
    // Sampling directions: 1 (the paper), or 3: also the two directions perpendicular to
    // `direction`; each triangle's candidates from the three are united (their kept
    // regions mapped back to world boxes) and tested once. About 3x the GPU time.
    // The reliable method runs 3 as 1 (resolveSettings says so).
    std::uint32_t axes = 1;
    Coverage coverage = Coverage::Centre;
    // Depth-epsilon policy for closed surfaces (world units): leaving one closed surface
    // and entering the next across a gap of at most this along a ray counts as touching
    // (a collision ray). 0: only exact depth ties, ordered front before back, do.
    float closed_epsilon = 0;
    // Depth-aware separation (docs/broadphase.md): rays also record where two consecutive
    // hits may collide (triangles of different objects, or of one self-colliding object and
    // not neighbours, whose surfaces come within a pixel of each other in depth), and a
    // triangle is downloaded only where its own (x, y, depth) box meets those of the rays
    // around it; records then carry the kept depth range. Off: the paper's separation,
    // which keeps every triangle under a collision ray whatever its depth. The collision
    // rays are the same either way. On by default: on the bench set it never found fewer
    // pairs than the paper's separation and downloads 2-30x fewer triangles where meshes
    // overlap deeply (about as many on coarse piles). Costs 48 bytes per triangle and 19
    // per ray of GPU memory, and a little GPU time per peeling step.
    bool depth_aware = true;
    // Also return where the collision rays were (DetectResult::collision_rays), as
    // world-space segments, for pictures and debugging. Costs a 4-byte-per-ray readback and
    // a host pass over the ray image. The reliable method samples no rays: refused there.
    bool collision_rays = false;
};

// Read only by the reliable method (DetectMethod::Reliable, the default); the peeling
// method refuses by name what it cannot do (exact Gpu, pair_sort Gpu, device_pairs).
struct ReliableSettings {
    // Where the exact triangle-triangle test decides the pairs the GPU's filter keeps
    // (docs/exact_gpu.md). Gpu (Auto where the device has shaderFloat64): the pair pass
    // decides every candidate exactly in double-precision expansion arithmetic and applies
    // the neighbour rule, so only intersecting pairs are read back and the CPU computes
    // their responses alone. Cpu: the filter's survivors are read back and the CPU narrow
    // phase tests them (the reference path, and the only one without shaderFloat64). The
    // pairs are the same either way; DetectStats::gpu_exact_tests and ::cpu_exact_tests say
    // which ran. Peeling decides on the CPU: Gpu is refused there.
    ExactDecision exact = ExactDecision::Auto;
    // With the exact decision on the GPU: whether it runs inside the pair pass or as a pass
    // of its own over the candidates the filter leaves (ExactPass); CellStats::exact_queued
    // says which ran.
    ExactPass exact_pass = ExactPass::Auto;
    // Exact decision on the GPU, no device_pairs: where the host result's pairs are put in
    // order (PairSort; docs/exact_gpu.md). Gpu: sorted on the GPU and read back in order, so
    // the CPU only computes the responses; Cpu: the narrow phase sorts them (the reference
    // path). Same pairs and responses either way; DetectStats::reliable.pairs_sorted_on_gpu
    // says which ran. Auto below kGpuPairSortFrom: one GPU pass sorts them and computes their
    // responses (pairs_sorted_in_one_pass) where the survivors fit it, with responses Auto.
    // Gpu is refused where device_pairs would be (peeling, exact Cpu, no shaderFloat64, a
    // pair filter the world applies on the host only); Auto then sorts on the CPU. With
    // engine meshes checked on the GPU (kObjectCheckOnGpu) the CPU sorts.
    PairSort pair_sort = PairSort::Auto;
    // Where the host result's responses are computed when its pairs are sorted on the GPU
    // (ResponseSource; docs/exact_gpu.md, "Responses on the GPU"). Gpu: the GPU computes them
    // (and sorts the pairs, as pair_sort Gpu) and both are read back ready, so the host only
    // checks and copies; Cpu: the narrow phase computes them (the reference path). The same
    // responses to the bit either way; DetectStats::reliable.responses_on_gpu says which
    // ran. Gpu is refused where pair_sort Gpu would be, with pair_sort Cpu and with
    // device_pairs (whose host result is built on the host); Auto then computes them on the
    // CPU, as it does for a result cut at limits.max_pairs.
    ResponseSource responses = ResponseSource::Auto;
    // With the responses on the GPU: when the host names the sorted pairs into the result
    // (PairNaming). Auto: while the GPU computes the responses, once the world's last
    // detection had kNameDuringGpuFrom pairs; the host learns that each piece of the pairs
    // is in its memory from a VkEvent the GPU sets, which Vulkan does not name as a host
    // synchronisation (docs/exact_gpu.md says what was checked, and where). AfterFence: only
    // after the submission's fence, as for every other readback: the naming (stack-mating's
    // 1.7M pairs: about 0.8 ms on an H100's host) no longer overlaps the GPU, but the GPU
    // span is shorter (no event, no early copy): detect() measured within noise of Auto on
    // the stacks, 0.07 ms more on cad-mating (H100, run 43). The same result either way;
    // DetectStats::reliable.pairs_named_during_gpu says which ran.
    PairNaming pair_naming = PairNaming::Auto;
    // With an automatic resolution: whether the grid is chosen per scene from the
    // detections' own GPU times (GridTuning). On, the first detections of a scene try the
    // neighbouring grids (each as exact; some slower) and the world keeps the fastest; the
    // settings note says which grid ran and why. Auto resolves to On on a GPU, to Off on a
    // CPU implementation (lavapipe). A resolution given by the caller is never changed.
    GridTuning grid_tuning = GridTuning::Auto;

    // With the exact decision on the GPU (exact Auto or Gpu, a device with shaderFloat64):
    // the detection also leaves its pairs on the GPU, in buffers the world owns, sorted as
    // DetectResult::pairs, for the engine's next command buffer (DevicePairs in vkcollide/detect_result.hpp;
    // docs/api.md, "Results on the GPU"). Refused by name with the peeling method, with
    // exact Cpu, without shaderFloat64 (UnsupportedFeature), and with a pair filter the
    // world applies on the host only (more than kMaxFilterMaskObjects live objects). The
    // host result is unchanged. Costs GPU passes over the survivors and the triangles
    // (DetectStats::reliable.sorting_ms) and 16 bytes per pair of capacity plus 12 per
    // triangle and 4 per survivor of capacity of device memory.
    bool device_pairs = false;
    // Pairs the device buffer holds. 0: automatic, the reliable method's survivor capacity
    // (it grows with the scene and holds every pair of a complete run: no overflow). A
    // smaller one: the first `device_pair_capacity` pairs in order are written and the
    // header says kDevicePairsOverflow with the count needed (never a silent drop); at most
    // kMaxDevicePairCapacity.
    std::uint32_t device_pair_capacity = 0;
    // With device_pairs: false leaves the pairs on the GPU only, for an engine that reads
    // them there. Nothing is read back and no host narrow phase runs: DetectResult::pairs
    // and ::responses stay empty, DetectStats::reliable.device_pairs_found says how many
    // pairs the buffers hold, and the survivors stay in device-local memory. Refused without
    // device_pairs and with contacts.objects (they are built from the host's pairs).
    bool host_pairs = true;
    // With device_pairs: every colliding triangle's response on the GPU too, in a buffer the
    // world owns (DevicePairs::responses): TriangleResponse records in DetectResult::responses'
    // order, equal to them to the bit (docs/exact_gpu.md, "Responses on the GPU"). Refused
    // by name without device_pairs. Costs GPU passes over the triangles and their partners
    // (DetectStats::reliable.sorting_ms) and 64 bytes per triangle plus 4 per survivor of
    // capacity of device memory. With host_pairs off DetectResult::responses stays empty.
    bool device_responses = false;
};

// Contacts beyond the triangle pairs (vkcollide/contacts.hpp, docs/contacts.md). Either
// method; the contacts are the same whatever the method.
struct ContactSettings {
    // Object-level contacts: for every pair of closed objects whose volumes overlap, the
    // intersection volume, a contact normal, the penetration depth along it and the
    // centroid, in DetectResult::contacts. Off by default: it is a second GPU stage after
    // the broad phase (two short submissions, waited for in detect() or collect(): the
    // first measures the objects' boxes), which draws the closed objects whose boxes
    // overlap another's along `resolution`^2 rays across the region where those boxes
    // overlap, sorts each ray's hits and walks them. Cost: GPU time about one sampling pass
    // of those objects at that resolution, 72 bytes per triangle and 4 + 8 x (most hits on
    // one ray) bytes per ray of GPU memory (docs/contacts.md measures it).
    bool objects = false;
    // Contact geometry of the intersecting pairs: where each pair meets (a segment, a point
    // or a coplanar overlap, open surfaces included) and a normal, in
    // DetectResult::pair_contacts, and per pair of objects the total length, area and normal
    // in ::pair_contact_totals. Host meshes only (their vertices are on the host; engine
    // meshes are refused by name). Off by default: computed on the host after the narrow
    // phase (DetectStats::contacts.geometry_ms).
    bool geometry = false;
    // Object-level contacts: rays across the longer side of the region where closed
    // objects' boxes overlap, an integer in [kMinContactResolution, kMaxContactResolution]
    // (16 .. 4096). The error of the volume shrinks about linearly with it
    // (docs/contacts.md). Automatic: kDefaultContactResolution (spirv/contacts/contacts.h; 128).
    std::optional<std::uint32_t> resolution;
};

// Bounds on a detection's time, memory and result (docs/stability.md, "Limits"). Both
// methods.
struct LimitSettings {
    // Longest wait for all of the detection's GPU work together, in milliseconds: every
    // submission, the reliable method's reruns after a buffer grew, each direction, the
    // runs without bad engine meshes and the contacts' submissions share it, and nothing
    // new is submitted after it ran out. detect() counts from its call; submit() and
    // record() count their own waits (measuring, an earlier timed-out detection's work)
    // from the call and start the clock again at collect(). Beyond it the detection fails
    // with ErrorCode::Timeout naming this setting; the GPU work already submitted goes on
    // and the world is WorldState::Busy until it ends (CollisionWorld::state()). The
    // world's destructor waits for that work without a limit (docs/stability.md, "Time").
    // Not counted: the pipelines a context's first detections with a method or stage compile
    // before they submit (0.57 s on lavapipe); CollisionWorld::preparePipelines compiles
    // them at load time.
    std::uint32_t timeout_ms = 60000;
    // How the thread that collects a detection waits for its GPU work: it sleeps until
    // shortly (0.15 ms) before the work's expected end (the submission time plus the last
    // detection's GPU time), then polls the GPU's fence for up to wait_poll_us
    // microseconds, then sleeps for the rest of timeout_ms. A sleeping wait alone may wake
    // the thread well after the GPU finishes (docs/results.md measures it); polling wakes
    // it at once, and keeps one core busy for at most about wait_poll_us + 150
    // microseconds per detection. While it polls, the world calls its executor's prepare()
    // (WorldOptions::executor's, or its own pool's: that one keeps as many workers awake as
    // the last detection's narrow phase used, when it had 256 pairs or more, and those
    // cores spin for the same time), so they start on the pairs at once. 0: sleep only.
    std::uint32_t wait_poll_us = 500;
    // Most colliding pairs a detection returns. When the exact phase finds more, the
    // result holds max_pairs of them (the same ones for the same input, not necessarily
    // the smallest) with their responses, and DetectResult::pairs_left_out and
    // ::incomplete say so. The result costs about 40 bytes per pair kept (pairs,
    // responses, the narrow phase's hits); found pairs beyond the budget are counted, not
    // kept.
    std::uint64_t max_pairs = std::uint64_t{1} << 24;
    // The candidate budget: past it the detection stops and fails with LimitExceeded,
    // naming the count it needed and this setting (an error, nothing partial: unlike
    // max_pairs). Bounds time and memory where candidates pile up in one place: k copies of
    // one triangle give k^2/2 pairs. Either way the world stays usable after the error.
    // Peeling: the pairs of candidate triangles whose boxes overlap, which the narrow phase
    // sweeps (DetectStats::narrow.sap_pairs, up to 8 bytes each). Real scenes make about 9
    // per candidate (8.7M for 1M candidates; docs/narrow_phase.md measures the sweep's time).
    // Reliable: the GPU cell stage's work and memory (docs/stability.md, "Limits"): the
    // cells of the triangles' footprint boxes (each footprint costs 20 bytes of GPU memory)
    // and the candidate pairs the cells form (12 bytes each, DetectStats::cells.candidates)
    // at most this many each, the sweep's comparisons (CellStats::comparisons) at most 64
    // times it; no GPU buffer grows beyond it. Two 1.28M-triangle
    // spheres overlapping deeply need 15.6M box cells, 5.2e8 comparisons and 181K
    // candidates at the automatic resolution.
    std::uint64_t max_candidate_pairs = std::uint64_t{1} << 27;
};

struct DetectSettings {
    // Both methods.
    DetectMethod method = DetectMethod::Reliable;
    // Reliable: cells per side, any integer in [1, 16384]. Automatic: about
    // kCellsPerEdge (spirv/common/config.h; 2) cells per typical projected triangle edge across
    // the scene's extent, scaled per scene where reliable.grid_tuning is On, within
    // [kMinAutoCells, kMaxAutoCells] and at most kMaxCellsPerTriangle cells per triangle.
    // Peeling: rays per image side, a power of two in [4, 16384]. Automatic: about four
    // pixels per typical triangle edge across the scene's extent, within [64, 2048].
    // Typical edges: measured for host meshes, ObjectOptions::typical_edge_length for GPU
    // meshes; the extent: host meshes' boxes and, with GPU meshes, the scene box the last
    // detection measured on the GPU (the first detection of a world has only the host's).
    std::optional<std::uint32_t> resolution;
    // Projection direction. Automatic: the world axis along which the most triangle area
    // faces (host meshes' area-weighted normals, measured after their geometry changes; GPU
    // meshes, whose geometry the host never sees, counted as facing like the faces of the
    // last measured scene box), so a flat cloth is seen face-on, not edge-on. Ties: z,
    // then y, then x. The reliable method tilts that axis by 20 degrees where a quarter or
    // more of the host meshes' area faces another world axis exactly (the side faces of
    // axis-aligned boxes: stacks, walls, mating parts, which along the axis are seen
    // edge-on and pile up in deep cells): to (0.21, 0.27, 0.94) for z, (0.94, 0.21, 0.27)
    // for x, (0.27, 0.94, 0.21) for y (docs/reliable.md, "The direction"). Its pairs are the
    // same along any direction; the paper's method keeps the axis.
    std::optional<std::array<float, 3>> direction;
    // Sample only this world box (min x, y, z, max x, y, z); default: fit to the scene.
    // Reliable: the grid's square spans this box's extent; what lies outside falls into
    // the border cells (slower, never missed).
    std::optional<std::array<float, 6>> region;
    BadObjectPolicy bad_objects = BadObjectPolicy::Exclude;

    PeelingSettings peeling;  // the peeling method only
    ReliableSettings reliable;  // the reliable method only
    ContactSettings contacts;  // either method
    // Reliable: also every vertex-triangle and edge-edge pair within a distance, with its
    // distance, closest points and normal, in DetectResult::proximity (vkcollide/
    // proximity.hpp, docs/proximity.md). Off (distance 0) by default. Host meshes only (their
    // indices say which primitives neighbour each other); needs shaderFloat64.
    ProximitySettings proximity;
    LimitSettings limits;  // either method
};
inline constexpr std::uint32_t kMaxDevicePairCapacity = 1u << 27;
// PairSort::Auto sorts on the GPU's device-pairs passes from this many pairs in the world's
// last detection: below it they cost more than the host's sort, and one workgroup sorts the
// pairs and a pass over the responders computes their responses where the survivors fit it
// (docs/exact_gpu.md, "Few pairs: one pass").
inline constexpr std::size_t kGpuPairSortFrom = 4096;
// Where the GPU sorts the pairs and computes their responses, the host names the pairs while
// the GPU computes the responses (ReliableSettings::pair_naming Auto) from this many pairs in
// the world's last detection: below
// it the responses' passes are too short to hide the naming, which then costs more than
// after the wait (pile-shapes' 7,177 pairs: 0.06 ms more on an H100; docs/exact_gpu.md).
inline constexpr std::size_t kNameDuringGpuFrom = 32768;

}  // namespace vkcollide
