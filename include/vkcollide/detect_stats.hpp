// vkcollide: what a detection measured and counted (DetectResult::stats): the paper's
// Table 1 columns, each method's counts, GPU pass times and where the host's time goes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "vkcollide/contacts.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

struct PassTime {
    std::string name;
    double gpu_ms = 0;
};

// The reliable method's cell stage, counted on the GPU (docs/reliable.md).
struct CellStats {
    std::uint64_t entries = 0;  // footprints: (triangle, cell) pairs
    std::uint64_t max_cell = 0;  // most triangles in one cell
    std::uint64_t deep_cells = 0;  // cells swept by the deep path (more than 256 entries)
    std::uint64_t candidate_cells = 0;  // cells where the sweep found a candidate
    // Pairs with overlapping depth and boxes in a cell, as the sweep wrote them: a pair may
    // repeat across the cells both footprints share, except in the cells where the sweep
    // checks repeats (docs/reliable.md "Piles": on a CPU implementation cells of 64 entries
    // or more, on a GPU cells of more than 1,024): there it does not write a pair where the
    // cell to the left or below shows an earlier cell keeps it, and counts those in `repeats`.
    std::uint64_t candidates = 0;
    std::uint64_t duplicates = 0;  // of the candidates, dropped: not the pair's first common cell
    std::uint64_t filtered = 0;  // of those, dropped: proved disjoint by the GPU filter
    std::uint64_t survivors = 0;  // pairs read back (8 bytes each)
    std::uint64_t gpu_triangles = 0;  // engine meshes' triangles read back with their vertices (52 bytes each)
    std::uint32_t runs = 1;  // submissions (more after a buffer grew)
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
    std::uint32_t layers = 0;  // layers peeled
    std::uint32_t peel_passes = 0;  // peeling passes (half the layers with dual)
    // Submissions the peeling passes took: more than one per axis where one submission would
    // run long on this device (about 200 ms each; after a timeout the GPU finishes at most
    // the one in flight). 1 per axis on a GPU.
    std::uint32_t peel_submissions = 0;
    // Rays with more than 1,024 surfaces along them (gpu::kMaxRayFragments): collision rays
    // at once, without peeling (their triangles go to the exact narrow phase), and left out
    // of depth_complexity. Bounds the peeling passes of pathological scenes.
    std::uint32_t deep_rays = 0;
    bool dual = false;
    bool layers_short = false;  // some rays had more layers than were peeled (no cap asked), or deep rays
    std::uint32_t axes = 1;  // sampling directions run (the counts of DetectStats are summed over
        // them, depth complexity and layers are their maximum)
    Coverage coverage = Coverage::Centre;  // that ran: Centre, Dilate or Conservative (never Best)
    SamplingBackend backend = SamplingBackend::Raster;  // object sampling that ran (never Auto); toString names it
    std::string backend_reason;  // why (Auto's rule, or "asked for"; reliable: none sampled)
    // GPU, per stage after the sampling (DetectStats::sampling_ms).
    double merging_ms = 0, separation_ms = 0, packing_ms = 0;
};

// Filled by the reliable method: its GPU times by stage (the front: DetectStats::sampling_ms)
// and where its pairs went. Its cell stage's counters are DetectStats::cells.
struct ReliableStats {
    double footprints_ms = 0, pairing_ms = 0, filtering_ms = 0;  // GPU, per stage
    double sorting_ms = 0;  // device_pairs: the GPU's sort of the pairs
    bool pairs_sorted_on_gpu = false;  // DetectSettings::reliable.pair_sort: the GPU ordered the host result's pairs
    bool responses_on_gpu = false;  // DetectSettings::reliable.responses: the GPU computed the host result's responses
    // PairSort::Auto below kGpuPairSortFrom: one GPU pass sorted the few pairs and computed
    // their responses (pairs_sorted_on_gpu and responses_on_gpu are then true as well);
    // false where they did not fit it (more than 4,096 survivors) and the host sorted them.
    bool pairs_sorted_in_one_pass = false;
    // With both (and reliable.pair_naming Auto, kNameDuringGpuFrom pairs or more in the
    // world's last detection): the host named the result's pairs while the GPU computed the
    // responses (a milestone in the submission: docs/exact_gpu.md), not after it finished.
    bool pairs_named_during_gpu = false;
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
    double upload_ms = 0;  // the broad phase's per-run inputs: waiting for earlier
        // work, buffers sized, objects, frame and the method's inputs written
    double declare_ms = 0;  // the render graph declared (its passes and resources)
    double compile_ms = 0;  // the render graph compiled (order, barriers), or its last plan reused
    double record_ms = 0;  // transient resources, timestamp queries, the command buffer recorded
    double submit_ms = 0;  // the command buffer ended and handed to the queue
    double wait_ms = 0;  // waiting for the GPU to finish (fences)
    // From each queue submission's return to the host's waking up after it, less its GPU
    // span: queue launch latency, GPU time outside the timestamps, wake-up latency. With
    // submit() and collect() apart it also counts the host's work in between.
    double launch_wake_ms = 0;
    // Of collect_ms: detect()'s result memory made ready before the wait (pages faulted in,
    // elements made), for GPU-sorted pairs about the last result's size (from 16 KB;
    // docs/api.md); 0 for detectInto(), which writes into the caller's memory. Where it
    // exceeds the GPU span it is also in launch_wake_ms (the host wakes after it).
    double prepare_ms = 0;
    // Of collect_ms: the host's work while the GPU still ran, past a milestone of the
    // submission: the pairs named during the responses' passes, every piece's time, whether
    // the naming was used (reliable.pairs_named_during_gpu; narrow_timings.validate_ms is
    // then that naming's time, outside narrow_ms) or refused (limits.max_pairs) or dropped;
    // not in wait_ms.
    double milestone_ms = 0;
    // Of DetectStats::submissions, those whose command buffer was submitted again instead
    // of recorded: the commands equalled the last recording's and nothing they use was
    // destroyed since.
    std::uint32_t reused_submissions = 0;
    // The threads the narrow phase could use: the executor's, or 1 where it ran on the calling
    // thread (fewer than 2,048 pairs the GPU decided: no tests to share out).
    unsigned narrow_threads = 0;
};

struct DetectStats {
    // Both methods.
    // The paper's Table 1. Peeling as in the paper. Reliable, the closest meaning:
    //   collision rays        -> cells where the sweep found a candidate pair
    //   triangles downloaded  -> distinct triangles named by the pairs read back (their ids
    //                            crossed the bus; engine meshes' vertices too)
    //   pot. coll. triangles, tri-tri tests, pos. tests -> the narrow phase's, as for peeling
    //                            (tests: exact tests, GPU and CPU; positive: pairs found)
    std::size_t triangles = 0;  // "# tri's"
    std::size_t collision_rays = 0;  // "# coll. rays"
    std::size_t triangles_downloaded = 0;  // "# tri's downl."
    std::size_t potentially_colliding_triangles = 0;  // "# pot. coll. tri's"
    std::size_t triangle_tests = 0;  // "# tri-tri tests"
    std::size_t positive_tests = 0;  // "# pos. tests"
    std::size_t gpu_exact_tests = 0;  // of the tests, decided on the GPU (reliable, DetectSettings::reliable.exact)
    std::size_t cpu_exact_tests = 0;  // of the tests, decided on the CPU
    NarrowStats narrow;  // every narrow-phase counter
    NarrowTimings narrow_timings;  // the narrow phase's stages (host wall clock)
    // What ran.
    DetectMethod method = DetectMethod::Reliable;
    std::uint32_t objects = 0;
    std::uint32_t resolution = 0;  // rays (peeling) or cells (reliable) per side
    std::array<float, 3> direction{};
    std::string settings_note;  // how automatic settings were chosen
    std::vector<MeshWarning> mesh_warnings;  // closed objects that are inside out or holed, by id
    // Times.
    std::vector<PassTime> gpu_passes;  // GPU timestamps of every pass, in order
    // GPU: the front (clear, GPU input checks, bounds, fit) and, peeling, the object
    // sampling: all of the reliable method's GPU time before its footprints. The other
    // stages: peeling.merging_ms .. packing_ms, reliable.footprints_ms .. sorting_ms.
    double sampling_ms = 0;
    double readback_ms = 0;  // host: reading the header and the records or pairs
    double narrow_ms = 0;  // host: the CPU narrow phase
    double total_ms = 0;  // host wall time from submit to result
    double gpu_span_ms = 0;  // the GPU's own span: first pass's start to last pass's end
        // (timestamps; barriers and gaps between passes included)
    std::uint32_t submissions = 0;  // queue submissions the broad phase made
    // Memory: device memory held by the world, in Context::deviceMemoryInUse()'s unit (the
    // memory requirements' sizes): uploaded meshes, the broad phases' buffers, images and
    // cached transients, both slots when two detections were in flight. With one world on a
    // Context this is deviceMemoryInUse(). Engine-owned buffers are not counted.
    std::uint64_t gpu_memory_bytes = 0;

    PeelingStats peeling;  // the peeling method's
    ReliableStats reliable;  // the reliable method's times and where its pairs went
    CellStats cells;  // the reliable method's cell stage, counted on the GPU
    ContactStats contacts;  // DetectSettings::contacts
    ProximityStats proximity;  // DetectSettings::proximity
    HostStats host;  // where the host's time goes beyond the narrow phase
};

}  // namespace vkcollide
