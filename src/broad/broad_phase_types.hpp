// What goes into one broad-phase run and what comes out: the meshes as the GPU sees them,
// the settings, the result, and the GPU input check's findings as data.
//
// The API (src/api/validation.cpp) checks every rule these carry before a run; the broad
// phase asserts them (docs/rooms.md, "Validation").
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "broad/cell_stage_stats.hpp"
#include "broad/sampling_types.hpp"
#include "common/broadphase.h"
#include "graph/executor.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide::passes {

using vkcollide::Coverage;
using vkcollide::PackingMethod;
using vkcollide::SamplingBackend;

// A mesh as the GPU sees it. Addresses come from buffers created with
// SHADER_DEVICE_ADDRESS usage; positions are three floats at `vertices + i * stride`.
// 16-bit index data must be readable in whole 4-byte words (pad the buffer by 2 bytes).
struct GpuMesh {
    VkDeviceAddress vertices = 0;
    std::uint32_t vertex_stride = 12;
    std::uint32_t vertex_count = 0;
    VkDeviceAddress indices = 0;
    bool index16 = false;
    std::uint32_t triangle_count = 0;
    Transform3x4 transform = kIdentity3x4;  // row-major 3x4 object->world
    bool open = false;
    // Geometry only the GPU holds (an engine's buffers): each run checks its indices and
    // positions there (host meshes are checked before upload). Methods that form pairs on
    // the GPU also download the world vertices of its triangles that are in a pair.
    bool check_on_gpu = false;
    // Its own triangles may collide with each other: depth-aware separation makes no near
    // pair of two of them when off, methods that form pairs on the GPU form none (the
    // paper's method leaves that to the narrow phase). true is conservative.
    bool self_collision = true;
    // The caller's name for the object: methods that write pairs on the GPU
    // (BroadPhaseSettings::device_pairs) write it as the pair's object.
    std::uint32_t tag = 0;
    // Proximity (BroadPhaseSettings::proximity_distance): per triangle, the vertices and
    // edges it owns (src/proximity/ownership.hpp). Must outlive the run.
    std::span<const std::uint8_t> proximity_owned;
};

// Which pairs of different objects may collide, over a run's objects 0..n-1: bit
// a * n + b (a < b) set when they may. Computed when objects or the filter change, never
// per run (the world's setPairFilter contract); read by methods that form pairs on the GPU.
struct ObjectPairMask {
    std::uint32_t objects = 0;
    std::vector<std::uint32_t> bits;  // (objects^2 + 31) / 32 words

    void reset(std::uint32_t n) {
        objects = n;
        bits.assign((std::uint64_t(n) * n + 31) / 32, 0u);
    }
    void allow(std::uint32_t a, std::uint32_t b) {
        const std::uint64_t bit = std::uint64_t(a) * objects + b;
        bits[bit >> 5] |= 1u << (bit & 31);
    }
    bool allows(std::uint32_t a, std::uint32_t b) const {
        if (a > b) std::swap(a, b);
        const std::uint64_t bit = std::uint64_t(a) * objects + b;
        return (bits[bit >> 5] >> (bit & 31)) & 1u;
    }
    // The mask of the objects `keep` (indices into this mask's objects, ascending).
    void subset(const ObjectPairMask& from, std::span<const std::uint32_t> keep) {
        reset(static_cast<std::uint32_t>(keep.size()));
        for (std::uint32_t a = 0; a < keep.size(); ++a)
            for (std::uint32_t b = a + 1; b < keep.size(); ++b)
                if (from.allows(keep[a], keep[b])) allow(a, b);
    }
};

struct BroadPhaseSettings {
    std::uint32_t resolution = 256;                 // power of two in [kMinResolution, kMaxResolution]
    std::array<float, 3> direction{0, 0, 1};        // projection direction (any length > 0)
    std::uint32_t layer_cap = 0;                    // 0: peel every layer
    bool dual = false;                              // front and back peeling at once
    PackingMethod packing = PackingMethod::Scan;
    float open_epsilon = 0;                         // world units; open-surface depth proximity
    float closed_epsilon = 0;                       // world units; closed surfaces this close touch
    Coverage coverage = Coverage::Centre;           // never Best (the API resolves it)
    float fit_margin = gpu::kFitMargin;             // relative margin of the automatic fit
    bool keep_ray_image = false;                    // read back the collision-ray image
    // Sample this world box instead of fitting the scene: min x,y,z then max x,y,z.
    std::optional<std::array<float, 6>> region;
    // Object sampling on the graphics pipeline or in compute (same rays and records);
    // Auto picks per device and scene (chooseSamplingBackend in peeling/sampling/backend_choice.hpp).
    SamplingBackend backend = SamplingBackend::Auto;
    ComputeSamplingTuning compute;
    // Longest wait for one submission (ns); beyond it the run fails with ErrorCode::Timeout
    // and its GPU work is left to finish on its own (BroadPhase::busy()).
    std::uint64_t timeout_ns = graph::kDefaultTimeoutNs;
    // When set, one clock for the whole run instead: every wait (an earlier timed-out run's
    // work, each submission, a method's reruns) ends by then, and no new submission starts
    // after it; timeout_ns is then the length it stands for, named in the error. A
    // detection sets it so that all of its GPU work shares DetectSettings::limits.timeout_ms.
    std::optional<std::chrono::steady_clock::time_point> deadline;
    // How collect() waits for the GPU (graph::Executor::setWaitPolling): 0 sleeps only.
    std::uint64_t poll_ns = 0;
    // Called while collect() polls (graph::Executor::setPollHook); empty: nothing.
    std::function<void()> poll_hook;
    // Depth-aware separation (docs/broadphase.md): collision rays carry the depth interval
    // of their near pairs, bundles are (x, y, depth) boxes, a triangle is kept only where
    // its own box meets them in all three, and records carry the kept depth range. Off:
    // the paper's separation (screen boxes only).
    bool depth_aware = false;
    // Methods that form pairs on the GPU: which object pairs may collide (null: all). Must
    // outlive the run (until collect); its object count is the run's.
    const ObjectPairMask* pair_mask = nullptr;
    // Methods that form pairs on the GPU: their budget (CellStageSettings::max_candidate_pairs;
    // DetectSettings::limits.max_candidate_pairs in a detection). Past it the run fails with
    // LimitExceeded.
    std::uint64_t max_candidate_pairs = std::numeric_limits<std::uint64_t>::max();
    // Methods that form pairs on the GPU: decide them exactly there where the device can
    // (CellStageSettings::exact); BroadPhaseResult::cells.exact_ran says whether it did.
    bool exact_on_gpu = false;
    ExactPass exact_pass = ExactPass::Auto;  // CellStageSettings::exact_pass
    // Methods that decide pairs exactly on the GPU: also sort them there into device
    // buffers (DevicePairsView; objects named by GpuMesh::tag). Capacity in pairs, 0: automatic.
    bool device_pairs = false;
    std::uint32_t device_pair_capacity = 0;
    // With device_pairs: false leaves the pairs on the GPU only (no survivors read back:
    // BroadPhaseResult::pairs empty, device_header set).
    bool host_pairs = true;
    // With device_pairs: every colliding triangle's response there too (DevicePairsView::responses).
    bool device_responses = false;
    // Methods that decide pairs exactly on the GPU, without device_pairs: sort the pairs there
    // and read them back in order (BroadPhaseResult::sorted_pairs). Not with meshes checked
    // on the GPU.
    bool sort_on_gpu = false;
    // sort_on_gpu: the pairs expected (the last detection's): what the host's copy holds
    // first. More sort and copy once more.
    std::uint32_t sorted_pairs_expected = 0;
    // Where sort_on_gpu ran: the responses computed there too (BroadPhaseResult::sorted_responses).
    bool responses_on_gpu = false;
    // Methods that decide pairs exactly on the GPU, without sort_on_gpu or device_pairs: one
    // pass sorts the few survivors and computes their responses (cells/small_sort.hpp) beside
    // the host's path; where they fit, BroadPhaseResult::sorted_pairs, sorted_responses and
    // sorted_in_one_pass are set. Not with meshes checked on the GPU.
    bool small_sort = false;
    // With responses_on_gpu: called inside collect(), on its thread, as soon as the GPU has
    // copied a piece of the sorted pairs (global triangle ids, as BroadPhaseResult::sorted_pairs)
    // to host memory, while it still copies the rest and computes the responses: with all of
    // them (the span, whose later pieces may not be there yet) and the piece [begin, end) that
    // is, pieces in order from 0 (begin 0: a new sort's first). Returns whether it took the
    // piece; a refused piece ends the calls for that sort. BroadPhaseResult::sorted_pairs_seen
    // says whether it took every piece of the final sort. Only a complete sort's pairs; the
    // span is valid until the next run. Empty: not called.
    std::function<bool(std::span<const CandidatePair> all, std::size_t begin, std::size_t end)> on_sorted_pairs;
    // With on_sorted_pairs: the copy's pieces hold at least this many pairs (of the copy's
    // capacity; at most DevicePairStage::kMaxEarlyChunks pieces). 0: automatic
    // (DevicePairStage::kMinEarlyChunkPairs); tests set it small.
    std::uint32_t early_piece_pairs = 0;
    // Methods that form pairs on the GPU with the exact decision there: also every
    // vertex-triangle and edge-edge pair within this distance (world units; 0: off), each
    // mesh with its GpuMesh::proximity_owned. Capacity in records, 0: automatic.
    double proximity_distance = 0;
    std::uint32_t proximity_capacity = 0;
    // Methods that decide candidates in a pair pass: at most this many per submission (0:
    // automatic, CellStageSettings::pair_chunk); tests set it small.
    std::uint32_t pair_chunk = 0;
    // The reliable method's sweep: comparisons per chunk, each its own submission (0:
    // automatic, CellStageSettings::sweep_work); tests set it small.
    std::uint32_t sweep_work = 0;
    // The reliable method: which cells drop a pair's repeats in the sweep (0: automatic, by
    // device type; 1: every cell of kCellsSweepDedupe entries or more; 2: only the deep
    // cells swept in chunks, CellStageSettings::RepeatChecks); tests pick each.
    std::uint32_t repeat_checks = 0;
    // The peeling method: at most this many peeling steps per submission (0: automatic,
    // PeelingMethod's kPeelChunkTargetMs of GPU time); tests set it small.
    std::uint32_t peel_chunk = 0;
};

// Where a run writes its sorted pairs on the GPU (BroadPhaseSettings::device_pairs):
// vkcollide::DevicePairs without the slot.
struct DevicePairsView {
    VkBuffer pairs = VK_NULL_HANDLE, header = VK_NULL_HANDLE;
    VkDeviceAddress pairs_address = 0, header_address = 0;
    std::uint32_t capacity = 0;
    VkBuffer responses = VK_NULL_HANDLE;  // device_responses: TriangleResponse[response_capacity]
    VkDeviceAddress responses_address = 0;
    std::uint32_t response_capacity = 0;
};

// A mesh as the shaders read it (gpu::ObjectGpu), its triangles numbered from
// `triangle_base`; vertex_base (the bounds pass's batching) is the broad phase's to set.
gpu::ObjectGpu objectGpu(const GpuMesh& mesh, std::uint32_t triangle_base);

// How long the run's next wait may take (ns): what is left before the deadline (0 once it
// passed: a wait then only polls), or timeout_ns without one.
std::uint64_t waitNs(const BroadPhaseSettings& s);
// `e` as the run's error: a Timeout under a deadline names the whole timeout (a wait's own
// message names only what was left of it).
Error timeoutOfRun(const BroadPhaseSettings& s, Error e);

// A problem the GPU input check found in one object (kObjectCheckOnGpu meshes), as data:
// the API names the object and formats the message (describe()).
struct ObjectFault {
    enum class Kind : std::uint8_t {
        IndexOutOfRange,    // an index >= the vertex count
        NonFinitePosition,  // a vertex position that is NaN or infinite, or beyond +-kMaxWorldCoordinate in world space
        OutOfRange,         // a position, transform entry or world coordinate not below 2^62
                            // (found by the reliable method's cell stage, docs/reliable.md)
    };
    std::uint32_t object = 0;              // index in the run's meshes
    Kind kind = Kind::IndexOutOfRange;
    std::uint32_t triangle = 0;            // one bad triangle of the object
    std::uint32_t triangles_affected = 0;  // how many of the run's triangles have this problem
    std::uint32_t vertex_count = 0;        // the object's vertex count
};
// "triangle 2 has an index >= the vertex count 50 (3 triangles affected)": the problem,
// without naming the object.
std::string describe(const ObjectFault& fault);

struct BroadPhaseResult {
    // The paper's method: the kept triangles.
    std::vector<CandidateTriangle> records;  // in global triangle order
    // Methods that form pairs on the GPU (has_pairs): candidate pairs of global triangle ids
    // (the run's objects in order; unsorted, rarely repeated) and, for every triangle of a
    // check_on_gpu mesh in a pair, its ids and world vertices. Views of the method's
    // host-visible readback memory: valid until the broad phase's next run.
    bool has_pairs = false;
    std::span<const CandidatePair> pairs;
    std::span<const GpuTriangle> gpu_triangles;
    CellStageStats cells;                    // the cell stage's counters (has_pairs)
    // BroadPhaseSettings::sort_on_gpu where it ran: the pairs final, as global triangle ids
    // (the run's objects in order; a < b) in ascending order, which is DetectResult::pairs'
    // (host-visible memory, valid until the next run); `pairs` is then empty.
    bool has_sorted_pairs = false;
    std::span<const CandidatePair> sorted_pairs;
    // BroadPhaseSettings::on_sorted_pairs was called with exactly these sorted_pairs (the
    // final sort's) and used them.
    bool sorted_pairs_seen = false;
    // BroadPhaseSettings::responses_on_gpu where it ran: every pair's triangles' responses, in
    // order (objects as run indices; host-visible memory, valid until the next run).
    bool has_sorted_responses = false;
    std::span<const TriangleResponse> sorted_responses;
    // small_sort did it: the pairs and responses above came from its one pass.
    bool sorted_in_one_pass = false;
    // BroadPhaseSettings::host_pairs off: the device pairs' header as the GPU left it (the
    // pairs are only there).
    struct DeviceHeader {
        std::uint32_t count = 0, needed = 0, flags = 0, capacity = 0;  // vkcollide::DevicePairsHeader
    };
    std::optional<DeviceHeader> device_header;
    // BroadPhaseSettings::device_responses: the responses the device buffer holds.
    std::uint32_t device_responses = 0;
    // Proximity (BroadPhaseSettings::proximity_distance > 0): the pairs in the result's
    // order as the GPU wrote them (a rare one twice, side by side; host-visible memory, valid
    // until the next run), what the pass counted and how many times it ran.
    bool has_proximity = false;
    std::span<const ProximityPair> proximity;
    struct ProximityCounts {
        std::uint32_t triangle_pairs = 0, distances = 0, neighbours = 0, capacity = 0;
    } proximity_counts;
    std::uint32_t proximity_runs = 0;
    DeviceProximity proximity_device;  // its buffers (vkcollide::DeviceProximity)
    std::vector<std::uint8_t> ray_image;     // N*N, row-major, 1 = collision ray (if kept)
    // With depth_aware and keep_ray_image: each ray's depth interval (lo, hi) as its bundle
    // got it, row-major (lo > hi: none; +-3.4e38: every depth).
    std::vector<std::array<float, 2>> ray_depth;
    std::uint32_t depth_complexity = 0;
    std::uint32_t layers = 0;                // layers peeled: min(depth complexity, cap)
    std::uint32_t peel_steps = 0;            // peeling passes recorded (half with dual)
    std::uint32_t peel_submissions = 0;      // the submissions they took (BroadPhaseSettings::peel_chunk)
    std::uint32_t collision_rays = 0;
    // Rays with more than gpu::kMaxRayFragments fragments: collision rays without peeling.
    std::uint32_t deep_rays = 0;
    std::uint32_t triangles = 0;
    // The sampling projection used (world -> [0,1]^2 image, depth): the caller's region, or
    // the fit repeated on the host from the bounds the GPU measured (broad/projection.hpp).
    gpu::Projection projection{};
    std::vector<graph::PassTiming> passes;   // both submissions, in order
    graph::HostTimes host;                   // host time around the submissions, summed over them
    SamplingBackend backend = SamplingBackend::Raster;  // the one that ran (never Auto)
    std::string backend_reason;              // one line: why
    std::uint64_t fragments = 0;             // covered pixels summed over all triangles
    std::uint32_t compute_small = 0, compute_big = 0, compute_items = 0;  // compute backend's triangle lists
    bool compute_fragment_lists = false;     // compute backend peeled from per-ray fragment lists
    // GPU time per stage (broad/stage.hpp; the front's clear, checks and fit count as
    // sampling, as in the paper), and the host's reading of the results.
    double sampling_ms = 0, merging_ms = 0, separation_ms = 0, packing_ms = 0, readback_ms = 0;
    // The cell stage (Stage::Footprints, Pairing, Filtering).
    double footprints_ms = 0, pairing_ms = 0, filtering_ms = 0;
    double sorting_ms = 0;  // device pairs (Stage::Sorting)
    double proximity_ms = 0;  // the proximity pass (Stage::Proximity)
    // The scene's world box as the bounds pass measured it (min x, y, z, max x, y, z):
    // every object, engine meshes included; empty with a caller's region.
    std::optional<std::array<float, 6>> scene_box;
};

}  // namespace vkcollide::passes
