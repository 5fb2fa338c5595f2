// vkcollide: the CPU narrow phase (Georgii, Krüger, Westermann 2006, section 7).
//
// The GPU broad phase finds the triangles (or triangle pairs) that may collide. The narrow
// phase
//   1. pairs them up: sweep and prune over the kept screen-space boxes (overlap in x, y
//      and the depth extent z; swept along x within the cells of a y/depth grid), or takes
//      candidate pairs the GPU formed,
//   2. drops pairs that the options forbid and pairs of neighbouring triangles,
//   3. runs an exact triangle-triangle test on the rest,
//   4. returns the colliding pairs and one response vector per colliding triangle.
//
// Three entries, one result (NarrowResult), each deterministic for every thread count and
// input order:
//   runNarrowPhase(CandidateTriangle)        80-byte records carrying world vertices (the
//                                            GPU's records today; the paper's path);
//   runNarrowPhase(CandidateRecord, source)  32-byte records (ids, kept box, depth extent);
//                                            vertices come from a TriangleSource;
//   runPairNarrowPhase(CandidatePair, source) candidate pairs of global triangle ids, e.g.
//                                            from a GPU pair stage; no boxes, no sweep.
// Everything parallel runs on an Executor (vkcollide/thread_pool.hpp): vkcollide's
// ThreadPool or an engine's job system. docs/narrow_phase.md has the measurements.
//
// Exactness: the triangle test decides with exact orientation predicates, never with a
// tolerance. Touching (a shared point, an edge lying on a face, ...) counts as
// intersecting, degenerate (zero-area) and coplanar triangles get the exact answer.
//
// Thread safety: the entries are reentrant; they share no state between calls. An
// Executor runs one call's work at a time; calls that share a ThreadPool are serialised.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "vkcollide/export.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

// Runs the narrow phase's parallel loops; declared in vkcollide/thread_pool.hpp.
class Executor;

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

// A candidate triangle without vertices (32 bytes): what the record path needs besides the
// geometry a TriangleSource holds. The GLSL side declares the same fields in the same
// order in a std430 buffer.
struct CandidateRecord {
    std::uint32_t object;    // object id in the TriangleSource
    std::uint32_t triangle;  // triangle within its object
    float box[4];            // screen-space x0, y0, x1, y1: the box the GPU kept
    float zmin, zmax;        // screen-space depth extent of the triangle
};
static_assert(std::is_standard_layout_v<CandidateRecord>);
static_assert(offsetof(CandidateRecord, box) == 8 && offsetof(CandidateRecord, zmin) == 24);
static_assert(sizeof(CandidateRecord) == 32 && alignof(CandidateRecord) == 4);

// A candidate pair of triangles named by global triangle ids (8 bytes). A TriangleSource
// numbers its triangles object after object: triangle t of object o has the global id
// source.triangleBase(o) + t. The order of a and b does not matter; a pair may repeat and
// pairs may come in any order.
struct CandidatePair {
    std::uint32_t a, b;
};
static_assert(sizeof(CandidatePair) == 8);

// One triangle of a GPU-only mesh, downloaded by the GPU for the narrow phase (52 bytes,
// std430: `uint id; uint vertex_index[3]; float v[9];`): its global id, its vertex
// indices within its object (for the neighbour rule) and its world-space vertices.
struct GpuTriangle {
    std::uint32_t id;
    std::uint32_t vertex_index[3];
    Float3 v[3];
};
static_assert(std::is_standard_layout_v<GpuTriangle>);
static_assert(offsetof(GpuTriangle, v) == 16 && sizeof(GpuTriangle) == 52 && alignof(GpuTriangle) == 4);

// Where the narrow phase reads the triangles of the lean record path and the pair path.
// Objects are numbered 0, 1, ... in the order they are added; their triangles get global
// ids object after object (triangleBase).
//   Host meshes: the host holds object-space positions and indices; a triangle's world
//     vertices are M * p evaluated in double and rounded once to float (an exact identity
//     copies p bit for bit): the same rule as tests/support/exact_reference.hpp's
//     worldPositions, so results match the exact reference bit for bit.
//   GPU-only meshes: only the triangle count is known here; the vertices and indices of
//     the triangles a call needs come from the GpuTriangle table (setGpuTriangles).
// Lifetime: the source borrows the positions, indices and table; they must stay valid
// and unchanged while a narrow-phase call reads the source (one call or many).
// Checks: adding checks counts and the transform; index ranges, finite vertices and table
// entries are checked for the triangles a call reads (errors name object and triangle).
// Thread safety: const member functions may run concurrently; changes must not overlap
// a call that reads the source.
class VKCOLLIDE_API TriangleSource {
public:
    static constexpr Transform3x4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

    // Adds a host mesh (`indices` holds 3 per triangle, each below positions.size()) and
    // returns its object id. Errors: InvalidMesh for an index count that is not a
    // multiple of 3; InvalidArgument for a non-finite transform or when the source would
    // exceed 2^32 - 1 triangles.
    Result<std::uint32_t> addHostMesh(std::span<const Float3> positions, std::span<const std::uint32_t> indices,
                                      const Transform3x4& object_to_world = kIdentity);
    // Adds a GPU-only mesh of `triangle_count` triangles and returns its object id.
    // Errors: InvalidArgument when the source would exceed 2^32 - 1 triangles.
    Result<std::uint32_t> addGpuMesh(std::uint32_t triangle_count);
    // A host mesh's new transform or geometry (same triangle count); errors as when adding,
    // and InvalidArgument for an unknown object, a GPU-only one or a different count.
    Result<void> setTransform(std::uint32_t object, const Transform3x4& object_to_world);
    Result<void> setHostGeometry(std::uint32_t object, std::span<const Float3> positions,
                                 std::span<const std::uint32_t> indices);
    // The GPU-only triangles of this frame, in any order, each id at most once (checked
    // when a call reads the table). Only triangles of GPU-only meshes are looked up here.
    void setGpuTriangles(std::span<const GpuTriangle> table) noexcept { gpu_triangles_ = table; }
    void clear() noexcept;

    std::uint32_t objectCount() const noexcept { return static_cast<std::uint32_t>(objects_.size()); }
    std::uint32_t triangleCount(std::uint32_t object) const noexcept { return base_[object + 1] - base_[object]; }
    // Global id of triangle 0 of `object`; triangleBase(objectCount()) is the total count.
    std::uint32_t triangleBase(std::uint32_t object) const noexcept { return base_[object]; }
    std::uint32_t totalTriangles() const noexcept { return base_.back(); }

    // For the narrow phase.
    struct Object {
        std::span<const Float3> positions;       // host meshes
        std::span<const std::uint32_t> indices;  // host meshes
        Transform3x4 transform = kIdentity;
        bool identity = true;  // transform == kIdentity exactly: world = object bit for bit
        bool gpu = false;      // GPU-only: geometry from the table
    };
    std::span<const Object> objects() const noexcept { return objects_; }
    std::span<const GpuTriangle> gpuTriangles() const noexcept { return gpu_triangles_; }

private:
    std::vector<Object> objects_;
    std::vector<std::uint32_t> base_{0};
    std::span<const GpuTriangle> gpu_triangles_;
};

// Two intersecting triangles, ordered so that (object_a, triangle_a) < (object_b, triangle_b).
//
// Default-constructed (`TrianglePair p;`, also `TrianglePair p{};`) the four ids are unset, as
// an int's are: write them, or construct with all four. Why: std::vector's resize() makes
// its elements by value-initialisation, which for a type with zeroed members is a memset on
// one thread. A result of 1.7M pairs (27 MB) took 2.8 ms for it on an H100's host (run 33),
// longer than the GPU's whole detection; with this constructor resize() writes nothing and
// the pairs are written once, in parallel, as they are named.
struct TrianglePair {
    std::uint32_t object_a, triangle_a;
    std::uint32_t object_b, triangle_b;

    TrianglePair() noexcept {}  // NOLINT: user-provided on purpose, see above
    constexpr TrianglePair(std::uint32_t oa, std::uint32_t ta, std::uint32_t ob, std::uint32_t tb) noexcept
        : object_a(oa), triangle_a(ta), object_b(ob), triangle_b(tb) {}

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

// Counters matching the columns of the paper's Table 1, for every entry. "Candidate
// pairs" are, on the record paths, the pairs whose boxes overlap in x, y and z (pairs
// within one object whose self-collision is off are never formed: they cannot collide),
// and on the pair path the distinct input pairs.
struct NarrowStats {
    std::size_t candidates = 0;                       // "# tri's downl.": records in; pair path: distinct triangles in the pairs
    std::size_t potentially_colliding_triangles = 0;  // "# pot. coll. tri's": triangles in >= 1 candidate pair
    std::size_t sap_pairs = 0;                        // candidate pairs
    std::size_t filtered_pairs = 0;                   // of those, dropped by NarrowOptions (may_collide; pair path: self-collision off too)
    std::size_t neighbour_pairs = 0;                  // of those, dropped as neighbours (same object, shared vertex)
    std::size_t triangle_tests = 0;                   // "# tri-tri tests": exact tests run (= sap - filtered - neighbour)
    std::size_t positive_tests = 0;                   // "# pos. tests": tests that found an intersection (= pairs.size() + pairs_left_out)
    std::size_t input_pairs = 0;                      // pair path: pairs received, repeats included (else 0)
};

// Wall-clock time of each stage of one call, in milliseconds (host steady clock). For
// benchmarks and the statistics; never affects the result.
struct NarrowTimings {
    double validate_ms = 0;  // input checks, ordering, duplicates (pair path: sorting, merging repeats;
                             // pairs sorted on the GPU: their check and their copy into the result)
    double gather_ms = 0;    // triangles' vertices and indices from the TriangleSource (lean and pair paths)
    double sweep_ms = 0;     // sweep and prune (pair path: pairing up), self-collision switch, neighbour rule
    double filter_ms = 0;    // NarrowOptions::may_collide
    double test_ms = 0;      // exact triangle-triangle tests
    double sort_ms = 0;      // colliding pairs into canonical order (sorted on the GPU: the GPU's responses copied)
    double response_ms = 0;  // response vectors
    double total_ms = 0;     // the whole call
};

struct NarrowOptions {
    // Whether objects a and b (a < b) may collide at all. Empty: every pair may.
    // Called on the thread that calls the narrow phase, never concurrently, once per
    // distinct object pair that has candidate pairs, in ascending (a, b) order; it must
    // not call back into the executor.
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
    // runPairNarrowPhase only: the input pairs were already decided by an exact test
    // (the reliable method's GPU pair pass): each one that passes the self-collision
    // switch, the neighbour rule and may_collide is taken as intersecting without a test
    // (NarrowStats::triangle_tests stays 0), and only the result and responses are built.
    // Fewer than 2,048 such pairs run on the calling thread: the executor is not called (the
    // work is a few microseconds a hundred pairs, less than waking its threads).
    bool pairs_decided = false;

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

// Scratch memory that the narrow phase keeps between calls. Passing the same workspace
// every frame reuses its arrays instead of allocating them anew, which for large arrays
// also means new pages from the system: a sizeable share of the narrow phase's time
// (docs/narrow_phase.md measures it). Holds no results; its size follows
// the largest call. Any entry may use any workspace.
// Thread safety: one call at a time per workspace.
class VKCOLLIDE_API NarrowWorkspace {
public:
    NarrowWorkspace();
    ~NarrowWorkspace();
    NarrowWorkspace(NarrowWorkspace&&) noexcept;
    NarrowWorkspace& operator=(NarrowWorkspace&&) noexcept;

    struct Impl;   // src/narrow/workspace.hpp
    Impl& impl();  // for the narrow phase (a moved-from workspace gets a new Impl)

private:
    std::unique_ptr<Impl> impl_;
};

// The record path on 80-byte records with world vertices.
//
// Preconditions (checked; a broken one returns ErrorCode::InvalidArgument naming the
// candidate's object and triangle): every vertex, box coordinate and depth is finite;
// box[0] <= box[2], box[1] <= box[3], zmin <= zmax; no (object, triangle) appears twice;
// at most 2^28 - 1 candidates. Boxes and depths are only compared with each other, so any
// consistent screen space works; intervals are closed (touching boxes overlap). Vertices
// are in world units.
//
// Two candidates of the same object are neighbours, never a collision, when they share
// a vertex index or a bit-identical vertex position. The result is bit-identical for
// every executor, thread count and order of `in_candidates`.
//
// Host memory running out returns ErrorCode::OutOfMemory (no exception escapes).
//
// Thread safety: reentrant; `in_candidates` must not change during the call. The forms
// without a workspace use one of their own (same results).
VKCOLLIDE_API Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    Executor& executor);
VKCOLLIDE_API Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    Executor& executor, NarrowWorkspace& io_workspace);

// The record path on 32-byte records; vertices and vertex indices come from `source`
// (objects are the source's ids). Same rules and results as the 80-byte form given the
// same world vertices; besides, InvalidArgument when a record names an object or
// triangle the source does not have, InvalidMesh when a triangle's index is out of
// range or its world vertex is not finite, and InvalidArgument when a GPU-only
// triangle has no entry in the source's table or an id appears twice in the table.
VKCOLLIDE_API Result<NarrowResult> runNarrowPhase(std::span<const CandidateRecord> in_records, const TriangleSource& source,
                                    const NarrowOptions& options, Executor& executor);
VKCOLLIDE_API Result<NarrowResult> runNarrowPhase(std::span<const CandidateRecord> in_records, const TriangleSource& source,
                                    const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace);

// The pair path: the exact test on candidate pairs of global triangle ids (see
// CandidatePair), with the same self-collision switch, object-pair filter, neighbour
// rule and responses as the record paths. Repeated pairs count once; the order of the
// pairs and of a and b within a pair does not matter: the result is bit-identical for
// every input order, executor and thread count. Errors: InvalidArgument naming the first
// pair (input position) whose id is not below source.totalTriangles() or that pairs a
// triangle with itself; the source's errors as for the 32-byte record path.
VKCOLLIDE_API Result<NarrowResult> runPairNarrowPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                        const NarrowOptions& options, Executor& executor);
VKCOLLIDE_API Result<NarrowResult> runPairNarrowPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                        const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace);

}  // namespace vkcollide
