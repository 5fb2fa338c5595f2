// CollisionWorld's state, shared by the files of src/api/: the registry (world.cpp), engine
// meshes (engine_mesh.cpp), the automatic settings (settings.cpp), one detection
// (detect.cpp), detections in flight and the engine's synchronisation (engine_sync.cpp).
// Input rules are checked in validation.cpp; the GPU work of a detection is
// passes::Detection.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contacts/contact_stage.hpp"
#include "core/use_guard.hpp"
#include "detect/detection.hpp"
#include "vk/resources.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

struct CollisionWorld::Impl {
    // The device, kept alive by the world (declared first: destroyed last, after every
    // buffer and detection below), so that a world outlives its Context safely: the
    // Context holds nothing else a world uses.
    vk::DeviceRef device_ref;
    struct Object {
        bool alive = false;
        std::string name;
        ObjectOptions options;
        bool host = false;
        vk::Buffer vertices, indices;  // host meshes: uploaded copies
        // Host meshes: positions and indices again, for the narrow phase's TriangleSource
        // (reliable method) and for measuring the shape (reading the upload buffer back
        // would cross the bus: it may be write-combined device memory).
        std::vector<Float3> host_positions;
        // updateVertices writes here, then swaps: a refused update leaves host_positions
        // as they were.
        std::vector<Float3> spare_positions;
        // Pipelining host meshes: further copies of the vertices (upload buffer and host
        // positions). updateVertices writes one of them, and makes it current by swapping,
        // when a detection in flight reads the current ones; at most kMaxInFlight, made on
        // first need (a world that never updates in flight has none), reused once no
        // detection in flight reads them (freeCopy).
        struct VertexCopy {
            vk::Buffer upload;
            std::vector<Float3> positions;
        };
        std::vector<VertexCopy> copies;
        std::vector<std::uint32_t> host_indices;
        passes::GpuMesh gpu;           // addresses, counts, flags (transform set per run)
        GpuMeshDesc engine_desc;       // engine meshes: as given (setGpuMeshBuffers keeps its topology)
        // Object-space box (host meshes) and largest |coordinate| (the reliable method's
        // limit), measured when the geometry changes.
        std::array<float, 6> box{};
        float max_abs = 0;
        // Closed host meshes (mesh_checks): edges of one triangle (from addMesh), and six
        // times the object-space volume (both measured by addMesh; updateVertices leaves them).
        std::uint64_t boundary_edges = 0;
        double volume6 = 0;
        // For the automatic settings: the typical edge length (object units; given for GPU
        // meshes) and, host meshes, the sum over triangles of area * n n^T (xx, yy, zz, xy,
        // xz, yz; object space). A cache for host meshes: after their geometry changes
        // (shape_stale) they are measured by the next resolve() that needs them
        // (measureShapes), not by addMesh; hence mutable. updateVertices measures them on
        // the way (in its own parallel loop) while the last resolve() needed them.
        mutable float edge_length = 0;
        mutable std::array<double, 6> area_moment{};
        mutable bool shape_stale = false;
        // Proximity: the vertices and edges each triangle owns (host meshes, computed by the
        // first detection that asks; the indices never change).
        std::vector<std::uint8_t> proximity_owned;
        // Index of the object in `source` (kNoSource: not in it).
        std::uint32_t source_index = 0xFFFFFFFFu;
    };
    static constexpr std::uint32_t kNoSource = 0xFFFFFFFFu;

    // One detection, from start() to finish(): its GPU part and what the narrow phase
    // needs of the objects as they were at start() (ids, transforms, flags), so that the
    // objects may move (setTransform) and engine meshes change buffers (setGpuMeshBuffers)
    // while it is in flight. Two of them: a second detection may be submitted before the
    // first is collected (pipelining, docs/api.md).
    struct Run {
        std::unique_ptr<passes::Detection> detection;  // slot 1: created on first use
        bool in_flight = false;
        std::vector<passes::GpuMesh> meshes;
        std::vector<ObjectId> ids;  // index in the detection's meshes -> ObjectId
        // Host meshes' positions as they were at start() (parallel to ids; empty for GPU
        // meshes), which its narrow phase reads: updateVertices writes another copy while
        // the run is in flight (meshes[i].vertices is the upload buffer it reads).
        std::vector<std::span<const Float3>> positions;
        DetectSettings settings;
        std::string note;
        std::chrono::steady_clock::time_point start;
        // When every wait of its GPU work ends (DetectSettings::limits.timeout_ms): start + the
        // timeout for detect(); submit() and record() restart it at collect().
        std::chrono::steady_clock::time_point deadline;
        double start_ms = 0, wait_ms = 0;  // host: start() (settings, record, submit); collect's wait and readback
        double settings_ms = 0;            // host: start()'s settings, validation and mask (DetectStats::host.settings_ms)
    };

    UseGuard guard{"CollisionWorld"};
    std::unique_ptr<ThreadPool> own_pool;  // unless WorldOptions::executor
    Executor* executor = nullptr;          // the narrow phase's: own_pool or the engine's
    NarrowWorkspace narrow_workspace;  // reused by every detection's narrow phase
    std::size_t last_narrow_pairs = 0;  // the last pair-path narrow phase's input: whom to wake while the next one waits
    std::function<bool(ObjectId, ObjectId)> pair_filter;
    std::vector<Object> objects;
    // The narrow phase's view of the live objects for the pair path (reliable method):
    // host meshes borrow host_positions and host_indices, GPU meshes are read from the
    // detection's downloaded triangles. Rebuilt (O(objects), no copies) when objects are
    // added or removed; transforms are set in place.
    TriangleSource source;
    std::vector<ObjectId> source_ids;
    bool source_dirty = true;
    // The pair filter's answers over the live objects in id order (setPairFilter's
    // contract): recomputed at the next detection after the filter or the objects change.
    passes::ObjectPairMask pair_mask;
    bool pair_mask_dirty = true;
    // The scene box the last detection measured on the GPU (engine meshes included), for
    // the automatic settings of scenes with GPU meshes.
    std::optional<std::array<float, 6>> measured_box;
    // Whether the last resolve() needed the shapes of all host meshes (automatic direction
    // or resolution) or of open ones (automatic open epsilon): updateVertices then measures
    // them with its copy (the same shape, bit for bit, as a later measureShapes).
    mutable bool shapes_wanted_all = true, shapes_wanted_open = true;
    // Whether the last resolve() needed this object's shape (measureShapes and
    // updateVertices ask the same question).
    bool wantsShape(const Object& o) const { return shapes_wanted_all || (shapes_wanted_open && o.options.open); }
    // A batch of only the engine's waits and signals, for a submit() that failed after it
    // was given them (engine_sync.cpp); created on first use.
    vk::Submission sync_only;
    // Declared after the objects: destroyed first, they wait for a detection in flight
    // before their buffers are freed. runs[oldest] is collected next.
    std::array<Run, 2> runs;
    std::uint32_t oldest = 0;
    // The device pairs of the detection started last (CollisionWorld::devicePairs()); reset
    // by every start, set when it asked for them.
    std::optional<DevicePairs> last_device_pairs;
    DevicePairs devicePairsOf(const passes::DevicePairsView& v, const Run& run) const {
        return {v.pairs, v.pairs_address, v.header, v.header_address, v.capacity, static_cast<std::uint32_t>(&run - runs.data())};
    }
    // Object-level contacts (DetectSettings::contacts.objects), created at the first detection
    // that asks for them; used by collect(), one at a time.
    std::unique_ptr<passes::ContactStage> contact_stage;

    // A detection met a lost device (WorldState::DeviceLost): every later one fails at once.
    bool device_lost = false;

    // finish()'s scratch (vectors kept between detections).
    std::vector<ObjectId> finish_ids;  // the broad phase's objects (bad ones left out) -> ObjectId
    NarrowOptions narrow_options;

    vk::Device& device() const { return *device_ref; }
    std::uint32_t inFlight() const { return std::uint32_t(runs[0].in_flight) + std::uint32_t(runs[1].in_flight); }
    bool pending() const { return inFlight() > 0; }
    bool busy() const {
        for (const Run& r : runs)
            if (r.detection && r.detection->busy()) return true;
        return false;
    }
    // GPU work runs that is no longer in flight: a detection that timed out or was abandoned.
    bool settling() const {
        for (const Run& r : runs)
            if (!r.in_flight && r.detection && r.detection->busy()) return true;
        return false;
    }

    // "object 3 ('cloth')": how every error names an object, in one place.
    static std::string who(ObjectId id, const std::string& name);
    static Error named(ObjectId id, const std::string& name, const Error& e) {
        return Error(e.code(), who(id, name) + ": " + e.message(), e.vkResult());
    }
    Error named(ObjectId id, const Error& e) const { return named(id, objects.at(id).name, e); }
    Result<Object*> find(ObjectId id, const char* what);
    // Whether a detection in flight reads object `id`'s vertices at `upload` (its upload
    // buffer's address) or `positions` (its host copy).
    bool readInFlight(ObjectId id, VkDeviceAddress upload, const Float3* positions) const;
    // A copy of `o`'s vertices that no detection in flight reads, made when there is none.
    Result<Object::VertexCopy*> freeCopy(ObjectId id, Object& o);
    // world.cpp: addMesh and updateVertices after their guards (they may throw
    // std::bad_alloc, which the public calls turn into OutOfMemory).
    Result<ObjectId> addHostMesh(const HostMesh& mesh, const ObjectOptions& options);
    Result<void> updateHostVertices(ObjectId id, std::span<const Float3> positions);
    Result<void> notPending(const char* what) const;
    // Fails with Timeout while the GPU work of a timed-out detection runs (WorldState::Busy;
    // settling()): for calls that change or free what that work reads.
    Result<void> notBusy(const char* what) const;
    // Notes a lost device in `e` (WorldState::DeviceLost) and returns it.
    Error noted(Error e);
    ObjectId newId(const ObjectOptions& options, Object& out) const;
    void objectsChanged() {
        for (Run& r : runs)
            if (r.detection) r.detection->forgetDepth();
        source_dirty = pair_mask_dirty = true;
    }
    // The source for the detection's objects (`ids`, in run order); rebuilt when needed.
    Result<void> syncSource(std::span<const ObjectId> ids);
    // The filter's mask over the live objects `ids` (id order), or null: no filter, or more
    // than kMaxFilterMaskObjects objects; the filter's exception as an error.
    Result<const passes::ObjectPairMask*> pairMask(std::span<const ObjectId> ids);
    // The pair filter's answer, or InvalidArgument naming the pair if it threw.
    Result<bool> callPairFilter(ObjectId a, ObjectId b) const;

    // The live objects as the broad phase reads them (transforms applied), and their ids.
    void liveMeshes(std::vector<passes::GpuMesh>& out_meshes, std::vector<ObjectId>& out_ids) const;

    // settings.cpp: every automatic field filled in from the host's knowledge of the scene
    // (validation::checkSettings checks the result); stale shapes are measured first when
    // an automatic field needs them (measureShapes).
    DetectSettings resolve(const DetectSettings& in, std::string* note) const;
    // A new host mesh's box and largest |coordinate|; its shape is left to measureShapes.
    static void measureHost(Object& o, std::span<const Float3> positions);
    // Measures the shape of every live host mesh whose geometry changed since it was last
    // measured, on the executor, if `in` leaves a setting automatic that uses shapes.
    void measureShapes(const DetectSettings& in) const;

    // engine_mesh.cpp: an engine mesh as the broad phase reads it, every rule checked
    // (errors name the object).
    Result<passes::GpuMesh> describeEngineMesh(ObjectId id, const std::string& name, const GpuMeshDesc& desc, bool open) const;

    // detect.cpp
    static passes::MethodFactory methodFactory(DetectMethod method);
    // Starts a detection in `run` (target: the engine's semaphores or command buffer).
    Result<void> start(Run& run, const DetectSettings& settings, bool measure, graph::SubmitTarget* target);
    Result<void> prepareProximity(Run& run);
    // restart_clock: the timeout counts from now (submit() and record(): the caller chose
    // when to collect); detect() counts from its start.
    // `reuse`: the caller's result (detectInto, collectInto), whose pairs', responses' and
    // pair contacts' memory finish() reuses; null: fresh vectors.
    Result<DetectResult> collect(Run& run, bool restart_clock, DetectResult* reuse = nullptr);
    // CollisionWorld::detect/collect and their *Into forms (reuse_memory: the caller's result).
    Result<DetectResult> detectCall(const DetectSettings& settings, DetectResult* reuse_memory);
    Result<DetectResult> collectCall(DetectResult* reuse_memory);
    Error describeFailure(const Run& run, const Error& e) const;
    Result<DetectResult> finish(Run& run, passes::DetectionResult detected, DetectResult* reuse);

    // engine_sync.cpp: the slot a new detection starts in (created when needed), and the
    // one detect()/submit()/record() path.
    Result<Run*> freeRun();
    Result<void> begin(const DetectSettings& settings, bool measure, graph::SubmitTarget* target);
    // contacts.cpp, after the narrow phase (`out.pairs` mapped to ObjectIds; `ids`: the
    // detection's objects): the pairs' contact geometry from the run's host meshes, and
    // DetectResult::contacts with their statistics.
    Result<void> addPairContacts(const Run& run, const passes::DetectionResult& detected, std::span<const ObjectId> ids,
                                 DetectResult& out);
    Result<void> addContacts(const Run& run, const passes::DetectionResult& detected, std::span<const ObjectId> ids,
                             DetectResult& io_out);
};

}  // namespace vkcollide
