// vkcollide: the public collision-detection API.
//
// A CollisionWorld holds the objects (mesh instances) of one scene on one Context and
// finds every pair of intersecting triangles between them (and inside an object, if
// its self-collision is on), with a GPU broad phase and an exact decision. Two broad
// phases (DetectSettings::method): the reliable cell stage (default: never misses a pair)
// and the depth peeling of Georgii, Krüger and Westermann (2006). With the reliable
// method on a device with shaderFloat64 (the default), the GPU decides every pair
// exactly and sorts them and computes their responses (the host then names and copies
// them): from kGpuPairSortFrom pairs in passes over the triangles, below that in one
// workgroup's sort and a pass over the responders where the survivors fit it (else the
// host sorts them). Without
// shaderFloat64, with peeling, or where the settings ask for it, the CPU narrow phase
// decides (the reference path). DetectStats says which ran (gpu_exact_tests,
// cpu_exact_tests, reliable.pairs_sorted_on_gpu, reliable.pairs_sorted_in_one_pass).
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
#include "vkcollide/detect_result.hpp"
#include "vkcollide/detect_settings.hpp"
#include "vkcollide/detect_stats.hpp"
#include "vkcollide/export.hpp"
#include "vkcollide/gpu_mesh.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

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
// DetectSettings (what a detection is asked to do): vkcollide/detect_settings.hpp.
// DetectStats (what it measured and counted): vkcollide/detect_stats.hpp.
// DetectResult and DevicePairs (what it returns, on the host and on the GPU):
// vkcollide/detect_result.hpp.

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
    // "Results on the GPU" in vkcollide/detect_result.hpp); after its collect() they are DetectResult::device (the
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
