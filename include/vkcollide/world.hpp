// vkcollide: the public collision-detection API.
//
// A CollisionWorld holds the objects (mesh instances) of one scene on one Context and
// finds every pair of intersecting triangles between them (and inside an object, if
// its self-collision is on), with a GPU broad phase and an exact CPU narrow phase. Two
// broad phases (DetectSettings::method): the reliable cell stage (default: never
// misses a pair) and the depth peeling of Georgii, Krüger and Westermann (2006).
//
//   auto ctx = vkcollide::Context::adopt(engine_device);         // Context::create(): host meshes only
//   auto world = vkcollide::CollisionWorld::create(**ctx);
//   auto a = (*world)->addMesh(sphere, {.name = "ball"});        // host arrays, uploaded once
//   auto b = (*world)->addGpuMesh(desc, {.name = "cloth", .self_collision = true, .open = true});
//   each frame:
//     (*world)->setTransform(*a, model);                        // rigid motion
//     (*world)->updateVertices(*a, new_positions);              // or deformation (host meshes)
//     auto hits = (*world)->detect();                           // pairs, responses, statistics
//   or, without stalling the frame:
//     (*world)->submit();  ... render ...  auto hits = (*world)->collect();
//   with the engine's semaphores (submit(settings, sync)), into the engine's command buffer
//   (record()), polled (ready(), tryCollect()), or pipelined: submit frame N+1 before
//   collecting frame N (docs/api.md, "Engines: synchronisation and latency").
//
// Meshes are what an engine renders: indexed triangle lists, no preprocessing and no
// hierarchy. Vertices of GPU meshes may change every frame (skinning, simulation): the
// world reads them when a detection is submitted.
//
// Thread safety: a CollisionWorld is used from one thread at a time (not always the same
// one). A call made while another call of the same world runs on another thread, or from
// inside one of its callbacks (the pair filter, the engine's executor), is refused with
// InvalidArgument naming both calls, and changes nothing. Destroying a world while one of
// its calls runs stops the process with a message (a destructor cannot return an error).
//
// What the world cannot guard: the engine's own writes. vkcollide reads engine buffers
// (addGpuMesh, setGpuMeshBuffers) through device addresses, which neither it nor the
// validation layer can see. Writing or freeing such a buffer while a detection that reads
// it is in flight (from submit() or record() until collect() returns, or until its signal
// semaphores are signalled: see submit()) gives pairs of torn geometry or reads freed
// memory. Order the engine's writes with the semaphores of submit() or after collect().
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vkcollide/contacts.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/export.hpp"
#include "vkcollide/gpu_mesh.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

// Stable handle of an object in a CollisionWorld (never reused after removeObject).
using ObjectId = std::uint32_t;

struct ObjectOptions {
    std::string name;             // used in error messages; default "object <id>"
    bool self_collision = false;  // test the object's own triangles against each other
    bool open = false;            // an open surface (cloth, terrain): depth proximity, not facing
    Transform3x4 transform = kIdentity3x4;  // object -> world, row-major (vkcollide/types.hpp)
    // GPU meshes only: a typical edge length in object units, for the automatic
    // resolution (host meshes are measured). 0: unknown.
    float typical_edge_length = 0;
};

// GpuMeshDesc (an engine's vertex and index buffers): vkcollide/gpu_mesh.hpp.
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
// double-precision triangle test on the GPU drops those it proves disjoint; the
// survivors (pairs of triangle ids, plus the world vertices of engine meshes' triangles)
// go to the exact narrow phase. Guarantee: every pair of triangles that intersect —
// touching included (a shared point, an edge on a face, coplanar overlap, degenerate and
// sliver triangles) — is found, at any resolution and along any direction; resolution
// and direction change the speed only (docs/reliable.md has the proof and its
// assumptions: positions, transform entries and world coordinates below 2^62 in
// magnitude; an object beyond that is treated as a bad object, see bad_objects).
// Cost: GPU passes over every triangle (its cells), every cell (a sweep) and every
// candidate pair (the filter); about 100 bytes per triangle, 20 per footprint (2 to 10 per
// triangle at the automatic resolution) and 12 per candidate of device memory; on the
// host only the surviving pairs (within a few per cent of the intersecting ones for
// different objects; more for self-collision) are read, in place, and tested. One
// submission; nothing is measured first (measured times: docs/results.md).
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
    // says which ran. Gpu is refused where device_pairs would be (peeling, exact Cpu, no
    // shaderFloat64, a pair filter the world applies on the host only); Auto then sorts on
    // the CPU. With engine meshes checked on the GPU (kObjectCheckOnGpu) the CPU sorts.
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
    // With an automatic resolution: whether the grid is chosen per scene from the
    // detections' own GPU times (GridTuning). On, the first detections of a scene try the
    // neighbouring grids (each as exact; some slower) and the world keeps the fastest; the
    // settings note says which grid ran and why. Auto resolves to On on a GPU, to Off on a
    // CPU implementation (lavapipe). A resolution given by the caller is never changed.
    GridTuning grid_tuning = GridTuning::Auto;

    // With the exact decision on the GPU (exact Auto or Gpu, a device with shaderFloat64):
    // the detection also leaves its pairs on the GPU, in buffers the world owns, sorted as
    // DetectResult::pairs, for the engine's next command buffer (DevicePairs below;
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

    PeelingSettings peeling;    // the peeling method only
    ReliableSettings reliable;  // the reliable method only
    ContactSettings contacts;   // either method
    // Reliable: also every vertex-triangle and edge-edge pair within a distance, with its
    // distance, closest points and normal, in DetectResult::proximity (vkcollide/
    // proximity.hpp, docs/proximity.md). Off (distance 0) by default. Host meshes only (their
    // indices say which primitives neighbour each other); needs shaderFloat64.
    ProximitySettings proximity;
    LimitSettings limits;  // either method
};
inline constexpr std::uint32_t kMaxDevicePairCapacity = 1u << 27;
// PairSort::Auto sorts on the GPU from this many pairs in the world's last detection: below
// it the host's sort costs less than the GPU's passes (docs/results.md, "Sorted on the GPU").
inline constexpr std::size_t kGpuPairSortFrom = 4096;

struct PassTime {
    std::string name;
    double gpu_ms = 0;
};

// The reliable method's cell stage, counted on the GPU (docs/reliable.md).
struct CellStats {
    std::uint64_t entries = 0;          // footprints: (triangle, cell) pairs
    std::uint64_t max_cell = 0;         // most triangles in one cell
    std::uint64_t deep_cells = 0;       // cells swept by the deep path (more than 256 entries)
    std::uint64_t candidate_cells = 0;  // cells where the sweep found a candidate
    // Pairs with overlapping depth and boxes in a cell, as the sweep wrote them: a pair may
    // repeat across the cells both footprints share, except in the cells where the sweep
    // checks repeats (docs/reliable.md "Piles": on a CPU implementation cells of 64 entries
    // or more, on a GPU cells of more than 1,024): there it does not write a pair where the
    // cell to the left or below shows an earlier cell keeps it, and counts those in `repeats`.
    std::uint64_t candidates = 0;
    std::uint64_t duplicates = 0;       // of the candidates, dropped: not the pair's first common cell
    std::uint64_t filtered = 0;         // of those, dropped: proved disjoint by the GPU filter
    std::uint64_t survivors = 0;        // pairs read back (8 bytes each)
    std::uint64_t gpu_triangles = 0;    // engine meshes' triangles read back with their vertices (52 bytes each)
    std::uint32_t runs = 1;             // submissions (more after a buffer grew)
    // The device has shaderFloat64 and the filter ran (before the exact pass it is skipped
    // while it rejects under a tenth of the candidates: docs/exact_gpu.md, "Two passes").
    bool filter_ran = false;
    bool exact_ran = false;  // the pair pass decided exactly (DetectSettings::reliable.exact)
    std::uint64_t exact_tests = 0;  // candidates the GPU's exact test decided (after the filter)
    std::uint64_t exact_neighbours = 0;  // of those, left out as neighbours (a bit-identical vertex)
    // Overlapping pairs the sweep did not write because they repeat a pair of an earlier
    // cell (where it checks, above). candidates + repeats is what
    // limits.max_candidate_pairs bounds.
    std::uint64_t repeats = 0;
    // Submissions the last run's sweep and pair pass took (0: the reliable method did not
    // run): more than one each only where one would run longer than about 200 ms on this
    // device (docs/stability.md, "Time").
    std::uint32_t sweep_chunks = 0;
    std::uint32_t pair_chunks = 0;
    // Cells of more than 1,024 footprints, sorted in global memory (docs/reliable.md, "Huge
    // cells"): their sweep skips coincident copies and pairs each footprint with those that
    // meet it in depth, so a pile costs about its pairs, not its footprints squared.
    std::uint64_t huge_cells = 0;
    // The sweep's comparisons, which 64 x limits.max_candidate_pairs bounds: k (k - 1) / 2
    // in a cell of k <= 1,024 footprints; in a huge cell its sort (k L (L + 1) / 4, L =
    // ceil(log2 k)), k per object in it and the pairs its sweep visits.
    std::uint64_t comparisons = 0;
    // With exact_ran: the exact decision ran as a pass of its own over the candidates the
    // filter left (the last detection had many), else inside the pair pass
    // (docs/exact_gpu.md, "Two passes"). The pairs are the same either way.
    bool exact_queued = false;
};

// A host mesh declared closed (ObjectOptions::open false) that is not a closed surface
// facing outwards. Closed objects are told apart by inside and outside: an inside-out one
// gets contact volume 0 (DetectSettings::contacts.objects) and, under the peeling method,
// collision rays wherever a ray crosses it; a holed one has no inside. The pairs of the
// reliable method do not depend on it. Checked on the host when the mesh is added (holes: its
// topology; inside out: the sign of its volume, one pass over its triangles on the world's
// executor, then counted under each detection's transform); updateVertices does not
// re-check, and engine meshes are not checked.
struct MeshWarning {
    ObjectId object = 0;
    bool inside_out = false;  // its enclosed volume is negative (mirroring transforms counted)
    std::uint64_t boundary_edges = 0;  // edges of one triangle only (holes); inside_out is then false
    std::string message;  // names the object, the problem and the fix
};

// Filled by the peeling method. The reliable method samples no rays (backend_reason says
// so): it peels nothing, and dual and coverage echo its settings.
struct PeelingStats {
    std::uint32_t depth_complexity = 0;  // measured by this detection, over the rays that are peeled
    std::uint32_t layers = 0;            // layers peeled
    std::uint32_t peel_passes = 0;       // peeling passes (half the layers with dual)
    // Submissions the peeling passes took: more than one per axis where one submission would
    // run long on this device (about 200 ms each; after a timeout the GPU finishes at most
    // the one in flight). 1 per axis on a GPU.
    std::uint32_t peel_submissions = 0;
    // Rays with more than 1,024 surfaces along them (gpu::kMaxRayFragments): collision rays
    // at once, without peeling (their triangles go to the exact narrow phase), and left out
    // of depth_complexity. Bounds the peeling passes of pathological scenes.
    std::uint32_t deep_rays = 0;
    bool dual = false;
    bool layers_short = false;           // some rays had more layers than were peeled (no cap asked), or deep rays
    std::uint32_t axes = 1;              // sampling directions run (the counts of DetectStats are summed over
                                         // them, depth complexity and layers are their maximum)
    Coverage coverage = Coverage::Centre;  // that ran: Centre, Dilate or Conservative (never Best)
    SamplingBackend backend = SamplingBackend::Raster;  // object sampling that ran (never Auto); toString names it
    std::string backend_reason;          // why (Auto's rule, or "asked for"; reliable: none sampled)
    // GPU, per stage after the sampling (DetectStats::sampling_ms).
    double merging_ms = 0, separation_ms = 0, packing_ms = 0;
};

// Filled by the reliable method: its GPU times by stage (the front: DetectStats::sampling_ms)
// and where its pairs went. Its cell stage's counters are DetectStats::cells.
struct ReliableStats {
    double footprints_ms = 0, pairing_ms = 0, filtering_ms = 0;  // GPU, per stage
    double sorting_ms = 0;             // device_pairs: the GPU's sort of the pairs
    bool pairs_sorted_on_gpu = false;  // DetectSettings::reliable.pair_sort: the GPU ordered the host result's pairs
    bool responses_on_gpu = false;     // DetectSettings::reliable.responses: the GPU computed the host result's responses
    // device_pairs with host_pairs off: the header's `needed` (the distinct intersecting pairs,
    // as DetectResult::pairs would have held) and `count` (those the buffer holds).
    std::uint32_t device_pairs_found = 0, device_pairs_written = 0;
    // device_responses: the header's `responses` (every colliding triangle's, in the buffer).
    std::uint32_t device_responses_written = 0;
};

// DetectSettings::contacts. With objects on: the stage's host wall time (both submissions,
// the waits and the reading) and GPU time, its rays (width x height), the most hits on one
// ray (layers), the candidate object pairs (closed, allowed, boxes overlapping), rays inside
// more than 16 objects at once (those extra objects ignored there) and its submissions.
struct ContactStats {
    double host_ms = 0, gpu_ms = 0;
    std::uint32_t rays_x = 0, rays_y = 0, layers = 0;
    std::uint32_t candidate_pairs = 0, nested_rays = 0, runs = 0;
    double geometry_ms = 0;  // with geometry on: its host wall time
};

// Host wall time of a detection's parts: start (settings, recording, queue submission) and
// the broad phase's collection (waiting for the GPU, reading the results back); the narrow
// phase is DetectStats::narrow_ms.
struct HostStats {
    double start_ms = 0, collect_ms = 0;
    // Where the host time of start and collection goes beyond the GPU passes (ms, host wall
    // clock; summed over the detection's queue submissions and sampling directions):
    double settings_ms = 0;  // the live objects, automatic settings (shapes measured
                             // when stale), validation, the pair filter's mask
    double upload_ms = 0;    // the broad phase's per-run inputs: waiting for earlier
                             // work, buffers sized, objects, frame and the method's inputs written
    double declare_ms = 0;   // the render graph declared (its passes and resources)
    double compile_ms = 0;   // the render graph compiled (order, barriers), or its last plan reused
    double record_ms = 0;    // transient resources, timestamp queries, the command buffer recorded
    double submit_ms = 0;    // the command buffer ended and handed to the queue
    double wait_ms = 0;      // waiting for the GPU to finish (fences)
    // From each queue submission's return to the host's waking up after it, less its GPU
    // span: queue launch latency, GPU time outside the timestamps, wake-up latency. With
    // submit() and collect() apart it also counts the host's work in between.
    double launch_wake_ms = 0;
    // Of collect_ms: detect()'s result memory made ready before the wait (pages faulted in,
    // elements made), for GPU-sorted pairs about the last result's size; 0 for detectInto(),
    // which writes into the caller's memory. Where it exceeds the GPU span it is also in
    // launch_wake_ms (the host wakes after it).
    double prepare_ms = 0;
    // Of DetectStats::submissions, those whose command buffer was submitted again instead
    // of recorded: the commands equalled the last recording's and nothing they use was
    // destroyed since.
    std::uint32_t reused_submissions = 0;
    unsigned narrow_threads = 0;  // the executor's threads the narrow phase could use
};

struct DetectStats {
    // Both methods.
    // The paper's Table 1. Peeling as in the paper. Reliable, the closest meaning:
    //   collision rays        -> cells where the sweep found a candidate pair
    //   triangles downloaded  -> distinct triangles named by the pairs read back (their ids
    //                            crossed the bus; engine meshes' vertices too)
    //   pot. coll. triangles, tri-tri tests, pos. tests -> the narrow phase's, as for peeling
    //                            (tests: exact tests, GPU and CPU; positive: pairs found)
    std::size_t triangles = 0;                        // "# tri's"
    std::size_t collision_rays = 0;                   // "# coll. rays"
    std::size_t triangles_downloaded = 0;             // "# tri's downl."
    std::size_t potentially_colliding_triangles = 0;  // "# pot. coll. tri's"
    std::size_t triangle_tests = 0;                   // "# tri-tri tests"
    std::size_t positive_tests = 0;                   // "# pos. tests"
    std::size_t gpu_exact_tests = 0;  // of the tests, decided on the GPU (reliable, DetectSettings::reliable.exact)
    std::size_t cpu_exact_tests = 0;  // of the tests, decided on the CPU
    NarrowStats narrow;                               // every narrow-phase counter
    NarrowTimings narrow_timings;                     // the narrow phase's stages (host wall clock)
    // What ran.
    DetectMethod method = DetectMethod::Reliable;
    std::uint32_t objects = 0;
    std::uint32_t resolution = 0;        // rays (peeling) or cells (reliable) per side
    std::array<float, 3> direction{};
    std::string settings_note;           // how automatic settings were chosen
    std::vector<MeshWarning> mesh_warnings;  // closed objects that are inside out or holed, by id
    // Times.
    std::vector<PassTime> gpu_passes;    // GPU timestamps of every pass, in order
    // GPU: the front (clear, GPU input checks, bounds, fit) and, peeling, the object
    // sampling: all of the reliable method's GPU time before its footprints. The other
    // stages: peeling.merging_ms .. packing_ms, reliable.footprints_ms .. sorting_ms.
    double sampling_ms = 0;
    double readback_ms = 0;              // host: reading the header and the records or pairs
    double narrow_ms = 0;                // host: the CPU narrow phase
    double total_ms = 0;                 // host wall time from submit to result
    double gpu_span_ms = 0;              // the GPU's own span: first pass's start to last pass's end
                                         // (timestamps; barriers and gaps between passes included)
    std::uint32_t submissions = 0;       // queue submissions the broad phase made
    // Memory: device memory held by the world, in Context::deviceMemoryInUse()'s unit (the
    // memory requirements' sizes): uploaded meshes, the broad phases' buffers, images and
    // cached transients, both slots when two detections were in flight. With one world on a
    // Context this is deviceMemoryInUse(). Engine-owned buffers are not counted.
    std::uint64_t gpu_memory_bytes = 0;

    PeelingStats peeling;      // the peeling method's
    ReliableStats reliable;    // the reliable method's times and where its pairs went
    CellStats cells;           // the reliable method's cell stage, counted on the GPU
    ContactStats contacts;     // DetectSettings::contacts
    ProximityStats proximity;  // DetectSettings::proximity
    HostStats host;            // where the host's time goes beyond the narrow phase
};

// A colliding pair; objects are ObjectIds, triangles index the object's triangle list.
// Sorted, (object_a, triangle_a) < (object_b, triangle_b).
// An object a detection left out (BadObjectPolicy::Exclude), and why.
struct ExcludedObject {
    ObjectId object = 0;
    Error error{ErrorCode::InvalidMesh, {}};  // names the object, a bad triangle and the problem
};

// ---- Results on the GPU (DetectSettings::reliable.device_pairs; docs/api.md) ------------
//
// Layout. `pairs`: TrianglePair records (four uint32: object_a, triangle_a, object_b,
// triangle_b; 16 bytes, tightly packed) at offset 0, `capacity` of them; the first
// `count` are the detection's pairs in DetectResult::pairs' order (object ids as the API
// returns them, triangles within the object). `header`: one DevicePairsHeader at offset 0.
// Both are storage buffers with device addresses in device-local memory (usage STORAGE,
// SHADER_DEVICE_ADDRESS, TRANSFER_SRC, TRANSFER_DST; EXCLUSIVE on the Context's queue
// family), written by compute shaders; the engine reads them, never writes them.
//
// Synchronisation: the writes are complete and visible at the world's signal. submit():
// wait for sync.signal with the stage mask of your reads (e.g. COMPUTE_SHADER); record():
// after the recorded commands in your command buffer, a memory (or buffer memory) barrier
// from COMPUTE_SHADER / SHADER_WRITE to your stage and access; detect() and collect(): the
// work is finished (on another queue, order after the world's work as for submit()).
// Before collect() returns, check the header: kDevicePairsIncomplete means this GPU run must
// be repeated or finished (a reliable-method buffer overflowed, DetectStats::cells.runs > 1;
// an engine mesh failed the GPU input check; or the sweep or the pair pass goes on in later
// submissions, cells.sweep_chunks or pair_chunks > 1) and count is 0; collect() does it,
// after which the buffers hold the final pairs (as DetectResult::pairs) for reads ordered
// after collect().
//
// Lifetime: each of the world's two detection slots (kMaxInFlight) has its own buffers
// (DevicePairs::slot). A detection's pairs stay there until the GPU work of the next
// detection in the same slot: the next detect()/submit()/record() when none is in flight
// when it starts (slot 0), else the other slot (pipelining: frame N + 1 writes slot 1 while
// frame N's pairs stay in slot 0). Your GPU reads must be ordered before that detection's
// GPU work: on the Context's queue, submitted before its submit() (each detection begins
// with a full memory barrier); on another queue, by a semaphore in its SubmitSync::wait.
// The buffers may be re-created (larger) for a later detection: take DevicePairs afresh
// for every detection (devicePairs() or DetectResult::device). Replaced buffers stay
// alive until the start of the second detection after in that slot, so reads ordered as
// above never meet a freed buffer. All of them are freed with the world.
struct DevicePairsHeader {
    std::uint32_t count = 0;     // pairs written: min(needed, capacity)
    std::uint32_t needed = 0;    // distinct intersecting pairs the detection found
    std::uint32_t flags = 0;     // kDevicePairs* below
    std::uint32_t capacity = 0;  // pairs the buffer holds
    // With device_responses: the responses written (one per triangle in any of the `needed`
    // pairs, even where the pairs overflowed) and the buffer's capacity (the detection's
    // triangles: it never overflows); 0 and 0 without.
    std::uint32_t responses = 0;
    std::uint32_t response_capacity = 0;
    std::uint32_t reserved[2] = {};
};
inline constexpr std::uint32_t kDevicePairsOverflow = 1;    // needed > capacity: the first `capacity` pairs written
inline constexpr std::uint32_t kDevicePairsIncomplete = 2;  // repeated by collect(): count 0 until then
struct DevicePairs {
    VkBuffer pairs = VK_NULL_HANDLE;   // TrianglePair[capacity] at offset 0
    VkDeviceAddress pairs_address = 0;
    VkBuffer header = VK_NULL_HANDLE;  // DevicePairsHeader at offset 0
    VkDeviceAddress header_address = 0;
    std::uint32_t capacity = 0;        // pairs (the header says it too)
    std::uint32_t slot = 0;            // the detection slot (0 or 1) whose buffers these are
    // With DetectSettings::reliable.device_responses: TriangleResponse[response_capacity] at
    // offset 0 (24 bytes each, tightly packed: object, triangle, direction x y z as floats,
    // partner_count), the first header.responses of them DetectResult::responses' records in
    // its order; same usage, memory, synchronisation and lifetime as `pairs`. Else null.
    VkBuffer responses = VK_NULL_HANDLE;
    VkDeviceAddress responses_address = 0;
    std::uint32_t response_capacity = 0;
};

// The collision rays of a peeling detection (DetectSettings::peeling.collision_rays): each ray from
// where the sampled box begins along its direction to where it ends, in world space.
struct CollisionRays {
    std::vector<std::array<Float3, 2>> segments;  // every direction's rays, the first direction's first
    std::array<std::uint32_t, 3> per_axis{};      // how many of `segments` each direction gave
    float pixel_size = 0;                         // world width of one ray's pixel (first direction)
};

struct DetectResult {
    std::vector<TrianglePair> pairs;
    // With DetectSettings::reliable.device_pairs: where the same pairs are on the GPU (above).
    std::optional<DevicePairs> device;
    std::vector<TriangleResponse> responses;  // one per colliding triangle, world space
    std::vector<ExcludedObject> excluded;     // engine meshes that failed the GPU check this time
    // With DetectSettings::contacts.objects: one per pair of closed objects whose volumes overlap
    // or whose triangles intersect (filtered pairs and excluded objects have none), sorted
    // by (object_a, object_b). Empty otherwise.
    std::vector<ObjectContact> contacts;
    // With DetectSettings::contacts.geometry: one per `pairs` entry, same index; and per pair
    // of objects with intersecting triangles, their sums, sorted by (object_a, object_b).
    std::vector<PairContact> pair_contacts;
    std::vector<ObjectPairContact> pair_contact_totals;
    // With DetectSettings::proximity: every vertex-triangle and edge-edge pair within the
    // distance, each once, sorted (ProximityPair). Empty otherwise.
    std::vector<ProximityPair> proximity;
    // With DetectSettings::proximity: the same pairs on the GPU (vkcollide/proximity.hpp).
    std::optional<DeviceProximity> device_proximity;
    // With DetectSettings::peeling.collision_rays: where the collision rays were.
    std::optional<CollisionRays> collision_rays;
    DetectStats stats;
    // DetectSettings::limits.max_pairs was reached: the intersecting pairs found beyond it (not in
    // `pairs`, not in `responses`), and an error (LimitExceeded) that says so. Empty and 0
    // when the result is complete.
    std::uint64_t pairs_left_out = 0;
    std::optional<Error> incomplete;
};

// What a world can do, in particular after a failed detection (docs/stability.md,
// "After a failure"). Every state can be destroyed.
enum class WorldState : std::uint8_t {
    Ready,       // detections run
    Busy,        // a detection failed with Timeout and its GPU work is still running: calls
                 // that would change what that work reads (updateVertices, removeObject)
                 // fail with Timeout, and the next detection first waits for it (within its
                 // own limits.timeout_ms). Engine buffers given to addGpuMesh stay in use until then.
    DeviceLost,  // a detection met a lost device: every later detection fails with
                 // DeviceLost; destroy the world and create a new Context
};

struct WorldOptions {
    // Threads of the world's own pool for the narrow phase (vkcollide/thread_pool.hpp);
    // 0: all hardware threads. Ignored with `executor`.
    unsigned threads = 0;
    // Optional: the engine's job system (a CallbackExecutor around its parallel-for, or its
    // own Executor). The narrow phase, updateVertices' copy and the shape measurement of
    // the automatic settings run their loops there, and the world starts no thread.
    // Borrowed: it must outlive the world. Called from the thread that calls
    // updateVertices(), resolveSettings(), detect(), submit(), record(), collect() or
    // tryCollect(), one loop at a time; it must not call into the world.
    Executor* executor = nullptr;
};

// What CollisionWorld::preparePipelines() did.
struct PreparedPipelines {
    // Pipelines the Context compiled during the call: 0 where every one was made before (one
    // that another thread's world compiled meanwhile counts too).
    std::uint32_t created = 0;
    double ms = 0;  // the call's time on the host
};

class VKCOLLIDE_API CollisionWorld {
public:
    // The world keeps the Context's device alive: it may outlive the Context, and every
    // call works as before after the Context is destroyed (context.hpp, "Lifetime").
    [[nodiscard]] static Result<std::unique_ptr<CollisionWorld>> create(Context& context, const WorldOptions& options = {});
    ~CollisionWorld();
    CollisionWorld(const CollisionWorld&) = delete;
    CollisionWorld& operator=(const CollisionWorld&) = delete;

    // Host arrays, checked (validateMesh) and uploaded. The world keeps no pointer to `mesh`.
    // Errors name the object and the rule; OutOfMemory when device memory for the upload or
    // host memory for the world's copy runs out (nothing added then).
    [[nodiscard]] Result<ObjectId> addMesh(const HostMesh& mesh, const ObjectOptions& options = {});
    // Engine-owned buffers; checked against the declared sizes, formats and usage
    // (GpuMeshDesc). Index values and vertex values live only on the GPU: each detection
    // checks them there; an object with an index out of range or a position not finite is
    // left out of that detection and named in DetectResult::excluded (or fails it:
    // DetectSettings::bad_objects). The buffers must stay alive until the object is removed
    // or re-pointed (setGpuMeshBuffers) and no detection that reads them is in flight.
    [[nodiscard]] Result<ObjectId> addGpuMesh(const GpuMeshDesc& mesh, const ObjectOptions& options = {});
    // Re-points an engine mesh at other buffers (double buffering: the engine writes one
    // pair while a detection reads the other). Same topology: the same vertex count, index
    // count, position format and index type (stride, offsets and buffers may differ); the
    // new description is checked as addGpuMesh checks it. Keeps the id, the options, the
    // measured depth complexity and everything automatic settings learnt: no extra work in
    // the next detection. Allowed while detections are in flight: they read the buffers they
    // were submitted with (keep those alive and unwritten until collected or signalled), the
    // next submit() reads the new ones.
    // Errors: InvalidArgument (no such object, a host mesh, another topology: named),
    // plus addGpuMesh's; on error nothing changes.
    [[nodiscard]] Result<void> setGpuMeshBuffers(ObjectId id, const GpuMeshDesc& mesh);
    [[nodiscard]] Result<void> removeObject(ObjectId id);

    // Moves an object. Allowed while detections are in flight: each uses the transforms of
    // its submit() (on the GPU and in the narrow phase), the next submit() the new one.
    [[nodiscard]] Result<void> setTransform(ObjectId id, const Transform3x4& object_to_world);
    [[nodiscard]] Result<void> setSelfCollision(ObjectId id, bool on);
    // New positions of a host mesh (same count, every one finite, and within the sampling
    // range under the object's transform). One pass over `positions`, split over the
    // world's executor (WorldOptions) in chunks of at least 16,384 vertices: copied into the
    // world's host copy (the narrow phase reads it) and straight into the mesh's upload
    // buffer, checked and boxed on the way. The world keeps no pointer to `positions`.
    // Allowed while detections are in flight (pipelining a host-deformed mesh): they read
    // the vertices they were submitted with, on the GPU and in the narrow phase, and this
    // call writes another copy of the host copy and the upload buffer, which the next
    // submit() reads. Those copies are made on the first such update (up to kMaxInFlight
    // more of each: DetectStats::gpu_memory_bytes counts them) and reused from then on.
    // The typical edge and facing that automatic settings use are measured on at most
    // 4,096 sampled triangles (128 evenly spaced blocks of 32 consecutive ones), on the
    // executor: in this call's own loop while the last detection or resolveSettings()
    // needed them, else at the next one that does (not at all while `direction`,
    // `resolution` and `peeling.open_epsilon` are given).
    // Cost: about the time to write 12 bytes per vertex twice, once over the bus when the
    // upload buffer is device memory; measuring the shapes adds a little to it. docs/api.md,
    // "Costs", and docs/results.md have the measurements and where the time goes.
    // The inside-out check of DetectStats::mesh_warnings is made by addMesh, not here: a
    // deformation rarely turns a mesh inside out, and a pass over its triangles per frame
    // would cost a deforming mesh about as much as this call's own copy.
    // Errors: InvalidArgument (no such object, a GPU mesh, another vertex count),
    // InvalidMesh naming the first NaN or infinite vertex, LimitExceeded (the sampling
    // range), OutOfMemory (a copy for pipelining), Timeout (WorldState::Busy). A refused
    // update changes nothing.
    [[nodiscard]] Result<void> updateVertices(ObjectId id, std::span<const Float3> positions);
    // Which object pairs may collide (called with a < b); empty: every pair may. Called on
    // the thread that calls detect() or submit(). Contract: a pure function of the two ids.
    // It is called for every pair of live objects at the next detection after
    // setPairFilter, addMesh, addGpuMesh or removeObject (not in every detection), and its
    // answers are kept as a bit mask that the GPU reads (the reliable method forms no pair
    // of filtered objects: no GPU work for them) and the narrow phase applies. Call
    // setPairFilter again when its answers change. Fails (InvalidArgument, nothing changed)
    // while a detection is in flight: its narrow phase still uses the filter. Above kMaxFilterMaskObjects
    // (spirv/common/config.h) live objects no mask is kept: the filter is then called in every
    // detection (on the thread that calls detect() or collect()), once per object pair
    // that has candidates. It must not throw: if it does, the world catches the exception,
    // stops calling the filter and fails that detection with InvalidArgument naming the
    // pair and the exception's message (the world stays Ready).
    [[nodiscard]] Result<void> setPairFilter(std::function<bool(ObjectId a, ObjectId b)> may_collide);

    std::size_t objectCount() const noexcept;
    std::size_t triangleCount() const noexcept;

    // The settings detect() would use now, with every automatic field filled in.
    [[nodiscard]] Result<DetectSettings> resolveSettings(const DetectSettings& settings = {}) const;

    // Makes now every pipeline a detection with `settings` may need, so that no later
    // detection on any world of this Context compiles one and its timeout
    // (LimitSettings::timeout_ms) bounds all of its time. Without it a Context's first
    // detection with a method or stage compiles that one's pipelines inside detect() (0.5 s
    // for the reliable method on lavapipe), and so does a later detection whose scene picks
    // another form (the reliable method's exact pass, the peeling method's compute
    // sampling). Covers the method and what the settings turn on or Auto may turn on later:
    // the exact decision on the GPU, device pairs and responses, the pair sort on the GPU,
    // proximity, object contacts. The pipelines live as long as the Context. Call it at load
    // time; it submits nothing, so it may be called with a detection in flight. Errors:
    // detect()'s for bad settings or a bad scene; the driver's (VulkanError), naming the
    // program.
    [[nodiscard]] Result<PreparedPipelines> preparePipelines(const DetectSettings& settings = {});

    // Records, submits, waits and runs the narrow phase. Errors: InvalidArgument for bad
    // settings, OutOfMemory when the resolution or scene needs more device memory than the
    // device has (nothing is allocated then; the world stays usable), DeviceLost (create a
    // new Context), InvalidMesh for a bad engine mesh under BadObjectPolicy::Fail.
    [[nodiscard]] Result<DetectResult> detect(const DetectSettings& settings = {});
    // detect() into a result the caller keeps from frame to frame: the memory of its pairs,
    // responses and pair contacts is reused, so a loop that passes the same DetectResult every frame asks
    // the system for fresh pages only when they outgrow it (filling fresh pages can cost
    // more than sorting the pairs: docs/results.md). Every field is overwritten
    // with what detect() would return; on failure io_result holds no result (its pairs and
    // responses may be empty) and the error is returned. collectInto() is collect()'s form.
    [[nodiscard]] Result<void> detectInto(DetectResult& io_result, const DetectSettings& settings = {});
    // ---- Detections in flight (docs/api.md, "Engines: synchronisation and latency") ------
    //
    // Records and submits the GPU work and returns; collect() waits for it and runs the
    // narrow phase. Up to kMaxInFlight detections may be in flight: submit frame N+1 before
    // collect() of frame N, and frame N's narrow phase runs on the host while frame N+1's
    // GPU work runs (the second slot's GPU buffers are allocated on its first use, as many
    // again as the first's); collect() returns them in submission order.
    // While a detection is in flight, setTransform, setGpuMeshBuffers and updateVertices
    // work (the detection keeps what it was submitted with); addMesh, addGpuMesh,
    // removeObject, setSelfCollision and setPairFilter fail with InvalidArgument naming
    // the call (the in-flight work reads what they change).
    // Peeling: submit() peels as many layers as the last detection measured (one
    // submission; DetectSettings::peeling.measure_layers is ignored); when none is known (the first
    // detection, or after objects were added or removed) it measures first, with a host
    // wait between two submissions.
    //
    // sync: the engine's semaphores (context.hpp, SubmitSync; binary or timeline, created
    // on the Context's device; the spans are read during the call only). The GPU work waits
    // for sync.wait before it starts (e.g. the engine's deformation of its meshes on another
    // queue) and signals sync.signal when it has finished, so that the engine may write the
    // meshes again, or consume the detection, without a CPU wait. A detection of several
    // queue submissions (peeling with axes 3, or a measuring submission) waits in the first
    // and signals in the last. Timeline waits may be signalled after submit() returns, but
    // not when this submit() measures (above): its host wait would wait for them (up to
    // limits.timeout_ms). Binary waits follow Vulkan's rule (the signal already submitted).
    // If submit() fails, its waits and signals are still submitted (as a batch of only
    // those) so that no engine queue waits forever; except when `sync` itself is invalid
    // (a null semaphore or a 0 stage mask: InvalidArgument, nothing submitted).
    // Caveat: collect() may run GPU work again after the signal, reading the engine's
    // meshes a second time: when a buffer of the reliable method overflowed
    // (DetectStats::cells.runs > 1; buffers grow and keep their size, so this happens in the
    // first frames of a growing scene) or when an engine mesh failed the GPU check and is
    // left out (DetectResult::excluded). Geometry the engine wrote after the signal is then
    // what that rerun sees; an engine that must rule this out writes after collect().
    //
    // Queue-family ownership: vkcollide reads engine buffers on the Context's queue family;
    // an EXCLUSIVE buffer written on a queue of another family must be released there and
    // acquired on the Context's family before the detection (context.hpp, "Sharing").
    [[nodiscard]] Result<void> submit(const DetectSettings& settings = {}, const SubmitSync& sync = {});
    // As submit(), but records the GPU work into the engine's command buffer instead of
    // submitting it (context.hpp, EngineCommandBuffer: the engine submits it to a queue of
    // the Context's family, in a batch that signals target.timeline to target.value; it
    // orders it after its mesh writes with its own barriers or semaphores). Needs a
    // detection of one submission: the reliable method, or peeling with axes 1 once the
    // depth complexity is known; refused by name otherwise (InvalidArgument). Also refused:
    // a null command buffer or timeline, a value the timeline has reached, a device without
    // timelineSemaphore (UnsupportedFeature). collect() and the world's destruction wait
    // for target.value without a time limit: submit the command buffer first.
    [[nodiscard]] Result<void> record(const EngineCommandBuffer& target, const DetectSettings& settings = {});
    // Waits for the oldest detection in flight and runs its narrow phase.
    // Errors: InvalidArgument when none is in flight, and detect()'s.
    [[nodiscard]] Result<DetectResult> collect();
    [[nodiscard]] Result<void> collectInto(DetectResult& io_result);
    // Whether collect() would find the oldest detection's GPU work finished (it may still
    // run GPU work again: see the caveat above). Never waits. Errors: InvalidArgument when
    // none is in flight, DeviceLost.
    [[nodiscard]] Result<bool> ready();
    // collect() if ready(), else std::nullopt at once (nothing changed: still in flight).
    [[nodiscard]] Result<std::optional<DetectResult>> tryCollect();
    // With DetectSettings::reliable.device_pairs: the buffers the detection started last (detect(),
    // submit(), record()) writes its pairs into, known as soon as it started, so that the
    // engine can record its reads before collect() (layout, synchronisation and lifetime:
    // "Results on the GPU" above); after its collect() they are DetectResult::device (the
    // repeated run of a collect() may have grown them). Errors: InvalidArgument when no
    // detection was started or the last one started (or failed to start) without device_pairs.
    [[nodiscard]] Result<DevicePairs> devicePairs() const;
    // A detection is in flight (submitted or recorded, not yet collected).
    bool pending() const noexcept;
    // How many detections are in flight (0, 1 or kMaxInFlight).
    std::uint32_t inFlight() const noexcept;
    static constexpr std::uint32_t kMaxInFlight = 2;
    // Ready, Busy or DeviceLost (polls the GPU's progress; never waits).
    WorldState state() const;

private:
    struct Impl;
    explicit CollisionWorld(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkcollide
