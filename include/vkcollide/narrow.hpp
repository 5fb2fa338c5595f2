// vkcollide: the CPU narrow phase (Georgii, Krüger, Westermann 2006, section 7).
//
// The GPU broad phase downloads the triangles that may collide, each with the
// screen-space box of the rays that hit it. The narrow phase
//   1. sweeps and prunes those boxes (overlap in x, y and the depth extent z; swept along
//      x within the cells of a y/depth grid),
//   2. drops pairs that the options forbid and pairs of neighbouring triangles,
//   3. runs an exact triangle-triangle test on the rest,
//   4. returns the colliding pairs and one response vector per colliding triangle.
// Validation, sweep and prune and the exact tests run on the ThreadPool; the rest is
// linear in the pairs found (docs/narrow_phase.md has the measurements).
//
// Exactness: the triangle test decides with exact orientation predicates, never with a
// tolerance. Touching (a shared point, an edge lying on a face, ...) counts as
// intersecting, degenerate (zero-area) and coplanar triangles get the exact answer.
//
// Thread safety: runNarrowPhase is reentrant; it shares no state between calls. A
// ThreadPool runs one call's work at a time; calls that share a pool are serialised.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide {

// Worker threads for the narrow phase; declared in vkcollide/thread_pool.hpp.
class ThreadPool;

// One potentially colliding triangle, as the GPU broad phase writes it. The GLSL side
// declares the same fields in the same order in a std430 buffer, with `v` written as
// `float v[9]` (a `vec3[3]` would get a 16-byte stride in std430).
struct CandidateTriangle {
    std::uint32_t object;           // index of the object (mesh instance) in the scene
    std::uint32_t triangle;         // index of the triangle within its object
    std::uint32_t vertex_index[3];  // the triangle's vertex indices within its object
    float box[4];                   // screen-space x0, y0, x1, y1, normalised to [0,1]: the box the GPU kept
    float zmin, zmax;               // screen-space depth extent of the triangle
    Float3 v[3];                    // world-space vertices
};
static_assert(std::is_standard_layout_v<CandidateTriangle> && std::is_trivially_copyable_v<Float3>);
static_assert(sizeof(Float3) == 12);
static_assert(offsetof(CandidateTriangle, object) == 0);
static_assert(offsetof(CandidateTriangle, triangle) == 4);
static_assert(offsetof(CandidateTriangle, vertex_index) == 8);
static_assert(offsetof(CandidateTriangle, box) == 20);
static_assert(offsetof(CandidateTriangle, zmin) == 36);
static_assert(offsetof(CandidateTriangle, zmax) == 40);
static_assert(offsetof(CandidateTriangle, v) == 44);
static_assert(sizeof(CandidateTriangle) == 80 && alignof(CandidateTriangle) == 4);

// Two intersecting triangles, ordered so that (object_a, triangle_a) < (object_b, triangle_b).
struct TrianglePair {
    std::uint32_t object_a = 0, triangle_a = 0;
    std::uint32_t object_b = 0, triangle_b = 0;

    friend bool operator==(const TrianglePair&, const TrianglePair&) = default;
    friend auto operator<=>(const TrianglePair&, const TrianglePair&) = default;
};

// The response of one colliding triangle i (section 7: "taking into account its own
// normal and the normal of the colliding partner"):
//
//     direction = normalize( sum over partners j of (n_j - n_i) )
//
// where n are unit geometric normals, n = normalize((v1 - v0) x (v2 - v0)), so they
// point outwards for counter-clockwise closed meshes. For two surfaces that press into
// each other (n_j close to -n_i) each term is about 2 n_j: the direction points out of
// the partner's surface, the way to push triangle i to separate it. Terms of partners
// whose normal equals n_i contribute nothing; if the sum is exactly zero the direction
// is the zero vector. A zero-area triangle has n = 0. Summed in double in the order of
// the sorted pairs, so it is identical for every thread count and input order.
struct TriangleResponse {
    std::uint32_t object = 0, triangle = 0;
    Float3 direction;                // unit vector, or zero (see above); world space
    std::uint32_t partner_count = 0; // number of pairs this triangle is in
};

// Counters matching the columns of the paper's Table 1.
struct NarrowStats {
    std::size_t candidates = 0;                       // "# tri's downl.": triangles in
    std::size_t potentially_colliding_triangles = 0;  // "# pot. coll. tri's": in >= 1 pair whose boxes overlap in x, y and z
    std::size_t sap_pairs = 0;                        // pairs whose boxes overlap in x, y and z
    std::size_t filtered_pairs = 0;                   // of those, dropped by NarrowOptions (object filter, self-collision off)
    std::size_t neighbour_pairs = 0;                  // of those, dropped as neighbours (same object, shared vertex)
    std::size_t triangle_tests = 0;                   // "# tri-tri tests": exact tests run (= sap - filtered - neighbour)
    std::size_t positive_tests = 0;                   // "# pos. tests": tests that found an intersection (= pairs.size() + pairs_left_out)
};

// Wall-clock time of each stage of one runNarrowPhase call, in milliseconds (host
// steady clock). For benchmarks and the statistics; never affects the result.
struct NarrowTimings {
    double validate_ms = 0;  // input checks, duplicate detection
    double sweep_ms = 0;     // sweep and prune, self-collision switch and neighbour rule
    double filter_ms = 0;    // NarrowOptions::may_collide
    double test_ms = 0;      // exact triangle-triangle tests
    double sort_ms = 0;      // colliding pairs into canonical order
    double response_ms = 0;  // response vectors
    double total_ms = 0;     // the whole call
};

struct NarrowOptions {
    // Whether objects a and b (a < b) may collide at all. Empty: every pair may.
    // Called on the thread that calls runNarrowPhase, never concurrently, once per
    // distinct object pair that has candidates whose boxes overlap, in ascending (a, b)
    // order; it must not call back into the pool.
    std::function<bool(std::uint32_t object_a, std::uint32_t object_b)> may_collide;
    // Per-object self-collision switch, indexed by object; objects past the end use
    // default_self_collision. Triangles of one object are only tested when it is on.
    std::vector<bool> self_collision;
    bool default_self_collision = true;
    // Most pairs the result holds. Beyond it the pairs found are counted
    // (NarrowResult::pairs_left_out), not kept: the result holds the first max_pairs in the
    // order the tests run (the same for every thread count and run), sorted, with their
    // responses. Bounds the memory of the hits and the result.
    std::size_t max_pairs = std::numeric_limits<std::size_t>::max();
    // Most pairs of candidates whose boxes overlap (NarrowStats::sap_pairs): past it the call
    // stops and returns ErrorCode::LimitExceeded. Bounds the time of inputs whose boxes pile
    // up in one place (k copies of one triangle make k^2/2 pairs to sweep, mostly
    // neighbours): the sweep costs a few nanoseconds per pair.
    std::size_t max_box_pairs = std::numeric_limits<std::size_t>::max();

    bool selfCollides(std::uint32_t object) const {
        return object < self_collision.size() ? static_cast<bool>(self_collision[object]) : default_self_collision;
    }
};

struct NarrowResult {
    std::vector<TrianglePair> pairs;           // sorted ascending, no duplicates
    std::vector<TriangleResponse> responses;   // one per triangle in pairs, sorted by (object, triangle)
    std::size_t pairs_left_out = 0;            // intersecting pairs found beyond NarrowOptions::max_pairs
    NarrowStats stats;
    NarrowTimings timings;  // not part of the result proper: differs from run to run
};

// Scratch memory that runNarrowPhase keeps between calls. Passing the same workspace
// every frame reuses its arrays instead of allocating them anew, which for large arrays
// also means new pages from the system: 20-30 % of the narrow phase's time on the demo's
// candidates (docs/narrow_phase.md). Holds no results; its size follows the largest call.
// Thread safety: one runNarrowPhase call at a time per workspace.
class NarrowWorkspace {
public:
    NarrowWorkspace();
    ~NarrowWorkspace();
    NarrowWorkspace(NarrowWorkspace&&) noexcept;
    NarrowWorkspace& operator=(NarrowWorkspace&&) noexcept;

    struct Impl;   // src/narrow/narrow_phase.cpp
    Impl& impl();  // for runNarrowPhase (a moved-from workspace gets a new Impl)

private:
    std::unique_ptr<Impl> impl_;
};

// Runs the narrow phase on the candidates that the GPU broad phase kept.
//
// Preconditions (checked; a broken one returns ErrorCode::InvalidArgument naming the
// candidate's object and triangle): every vertex, box coordinate and depth is finite;
// box[0] <= box[2], box[1] <= box[3], zmin <= zmax; no (object, triangle) appears twice.
// Boxes and depths are only compared with each other, so any consistent screen space
// works; intervals are closed (touching boxes overlap). Vertices are in world units.
//
// Two candidates of the same object are neighbours, never a collision, when they share
// a vertex index or a bit-identical vertex position. The result is bit-identical for
// every thread count of `pool` and every order of `in_candidates`.
//
// Host memory running out returns ErrorCode::OutOfMemory (no exception escapes).
//
// Thread safety: reentrant; `in_candidates` must not change during the call. The first
// form uses a workspace of its own; the second reuses `io_workspace` (same results).
Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    ThreadPool& pool);
Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    ThreadPool& pool, NarrowWorkspace& io_workspace);

}  // namespace vkcollide
