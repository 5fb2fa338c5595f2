// CollisionWorld's state: its parts, each with one job, and what ties them together.
//   registry (object_registry.*)   the objects, their ids, the narrow phase's source and the
//                                  pair filter's mask; world.cpp and engine_mesh.cpp change it
//   auto_settings (auto_settings.*) every automatic field of the settings, from the scene
//   detections (in_flight.*)        the two detection slots, which is collected next
// One detection is detect.cpp (and contacts.cpp after its narrow phase), the calls that start
// and collect detections engine_sync.cpp. Input rules are checked in validation.cpp; the GPU
// work of a detection is passes::Detection.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "api/auto_settings.hpp"
#include "api/in_flight.hpp"
#include "api/object_registry.hpp"
#include "core/use_guard.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

struct CollisionWorld::Impl {
    using Object = ObjectRegistry::Object;
    using Run = DetectionsInFlight::Run;
    static constexpr std::uint32_t kNoSource = ObjectRegistry::kNoSource;

    // The device, kept alive by the world (declared first: destroyed last, after every
    // buffer and detection below), so that a world outlives its Context safely: the
    // Context holds nothing else a world uses.
    vk::DeviceRef device_ref;
    UseGuard guard{"CollisionWorld"};
    std::unique_ptr<ThreadPool> own_pool;  // unless WorldOptions::executor
    Executor* executor = nullptr;          // the narrow phase's: own_pool or the engine's
    NarrowWorkspace narrow_workspace;  // reused by every detection's narrow phase
    std::size_t last_narrow_pairs = 0;  // the last pair-path narrow phase's input: whom to wake while the next one waits
    bool last_narrow_decided = false;   // ... and whether the GPU had decided its pairs (no tests: fewer threads)
    bool last_narrow_one_pass = false;  // ... or sorted them in one pass (the host copies them on its calling thread)
    // detect()'s result memory for GPU-sorted pairs and responses, made ready while the GPU
    // works (prepareResultMemory) and handed to the result; the last result's pair and
    // response counts.
    std::vector<TrianglePair> ready_pairs;
    std::vector<TriangleResponse> ready_responses;
    std::size_t last_result_pairs = 0, last_responses = 0;
    ObjectRegistry registry;
    AutoSettings auto_settings;
    // Declared after the objects: destroyed first, the detections wait for their work in
    // flight before the objects' buffers are freed.
    DetectionsInFlight detections;

    // A detection met a lost device (WorldState::DeviceLost): every later one fails at once.
    bool device_lost = false;

    // finish()'s scratch (vectors kept between detections).
    std::vector<ObjectId> finish_ids;  // the broad phase's objects (bad ones left out) -> ObjectId
    NarrowOptions narrow_options;

    vk::Device& device() const { return *device_ref; }
    // Notes a lost device in `e` (WorldState::DeviceLost) and returns it.
    Error noted(Error e);
    void objectsChanged() {
        detections.forgetDepth();
        registry.changed();
    }
    // The settings a detection of the scene as it is now runs with (AutoSettings::resolve).
    DetectSettings resolve(const DetectSettings& in, std::string* note, std::optional<AutoSettings::GridChoice>* grid = nullptr) const {
        return auto_settings.resolve(in, registry, device(), *executor, note, grid);
    }

    // world.cpp: addMesh and updateVertices after their guards (they may throw
    // std::bad_alloc, which the public calls turn into OutOfMemory).
    Result<ObjectId> addHostMesh(const HostMesh& mesh, const ObjectOptions& options);
    Result<void> updateHostVertices(ObjectId id, std::span<const Float3> positions);

    // engine_mesh.cpp: an engine mesh as the broad phase reads it, every rule checked
    // (errors name the object).
    Result<passes::GpuMesh> describeEngineMesh(ObjectId id, const std::string& name, const GpuMeshDesc& desc, bool open) const;

    // detect.cpp
    // Starts a detection in `run` (target: the engine's semaphores or command buffer).
    Result<void> start(Run& run, const DetectSettings& settings, bool measure, graph::SubmitTarget* target);
    Result<void> prepareProximity(Run& run);
    // Whether the reliable method's host pairs are sorted on the GPU with `s` after a
    // detection that found `last_pairs` pairs (PairSort::Auto), the pair filter aside.
    bool sortsOnGpu(const DetectSettings& s, std::size_t last_pairs) const;
    // The broad phase's settings that choose a method's passes and stages (`sort_on_gpu`:
    // sortsOnGpu's answer, the pair filter considered); the rest are start()'s.
    passes::BroadPhaseSettings methodSettings(const DetectSettings& s, bool sort_on_gpu) const;
    // restart_clock: the timeout counts from now (submit() and record(): the caller chose
    // when to collect); detect() counts from its start.
    // `reuse`: the caller's result (detectInto, collectInto), whose pairs', responses' and
    // pair contacts' memory finish() reuses; null: fresh vectors.
    Result<DetectResult> collect(Run& run, bool restart_clock, DetectResult* reuse = nullptr);
    // Before collect()'s wait for a run whose pairs the GPU sorts and whose result memory the
    // caller does not lend (detect(), collect()): vectors as large as the last result's pairs
    // and responses, their new pages faulted in while the GPU works, not after it.
    void prepareResultMemory();
    // The broad phase's on_sorted_pairs for `run`: its sorted pairs named into the result's
    // memory (Run::early_into) while the GPU computes the responses.
    bool nameEarly(Run& run, std::span<const CandidatePair> sorted, std::size_t begin, std::size_t end);
    // CollisionWorld::detect/collect and their *Into forms (reuse_memory: the caller's result).
    Result<DetectResult> detectCall(const DetectSettings& settings, DetectResult* reuse_memory);
    Result<DetectResult> collectCall(DetectResult* reuse_memory);
    Error describeFailure(const Run& run, const Error& e) const;
    Result<DetectResult> finish(Run& run, passes::DetectionResult detected, DetectResult* reuse);

    // engine_sync.cpp: the one detect()/submit()/record() path.
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
