// CollisionWorld's state, shared by the files of src/api/: the registry (world.cpp), the
// automatic settings (settings.cpp), one detection (detect.cpp). Input rules are checked in
// validation.cpp; the GPU work of a detection is passes::Detection.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "passes/detection.hpp"
#include "vk/resources.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

struct CollisionWorld::Impl {
    struct Object {
        bool alive = false;
        std::string name;
        ObjectOptions options;
        bool host = false;
        vk::Buffer vertices, indices;  // host meshes: uploaded copies
        // Host meshes: the indices again, for measuring after updateVertices (reading the
        // upload buffer back would cross the bus: it may be write-combined device memory).
        std::vector<std::uint32_t> host_indices;
        passes::GpuMesh gpu;           // addresses, counts, flags (transform set per run)
        // Object-space box (host meshes) and typical edge length (object units; measured for
        // host meshes, given for GPU meshes), for the automatic settings.
        std::array<float, 6> box{};
        float edge_length = 0;
    };

    Context* context = nullptr;
    std::unique_ptr<ThreadPool> pool;
    NarrowWorkspace narrow_workspace;  // reused by every detection's narrow phase
    std::function<bool(ObjectId, ObjectId)> pair_filter;
    std::vector<Object> objects;
    // Declared after the objects: destroyed first, it waits for a detection in flight
    // before their buffers are freed.
    std::unique_ptr<passes::Detection> detection;

    // A detection met a lost device (WorldState::DeviceLost): every later one fails at once.
    bool device_lost = false;

    // The detection in flight.
    std::vector<ObjectId> run_ids;  // index in the detection's meshes -> ObjectId
    DetectSettings run_settings;
    std::string run_note;
    std::chrono::steady_clock::time_point run_start;

    vk::Device& device() { return context->device(); }
    bool pending() const { return detection->pending(); }

    // "object 3 ('cloth')": how every error names an object, in one place.
    static std::string who(ObjectId id, const std::string& name);
    static Error named(ObjectId id, const std::string& name, const Error& e) {
        return Error(e.code(), who(id, name) + ": " + e.message(), e.vkResult());
    }
    Error named(ObjectId id, const Error& e) const { return named(id, objects.at(id).name, e); }
    Result<Object*> find(ObjectId id, const char* what);
    Result<void> notPending(const char* what) const;
    // Fails with Timeout while the GPU work of a timed-out detection runs (WorldState::Busy):
    // for calls that change or free what that work reads.
    Result<void> notBusy(const char* what) const;
    // Notes a lost device in `e` (WorldState::DeviceLost) and returns it.
    Error noted(Error e);
    ObjectId newId(const ObjectOptions& options, Object& out) const;
    void objectsChanged() { detection->forgetDepth(); }

    // The live objects as the broad phase reads them (transforms applied), and their ids.
    void liveMeshes(std::vector<passes::GpuMesh>& out_meshes, std::vector<ObjectId>& out_ids) const;

    // settings.cpp: every automatic field filled in from the host's knowledge of the scene
    // (validation::checkSettings checks the result).
    DetectSettings resolve(const DetectSettings& in, std::string* note) const;
    static void measureHost(Object& o, std::span<const Float3> positions, std::span<const std::uint32_t> indices);

    // detect.cpp
    Result<void> start(const DetectSettings& settings, bool measure);
    Result<DetectResult> collect();
    Error describeFailure(const Error& e) const;
    Result<DetectResult> finish(passes::DetectionResult detected);
};

}  // namespace vkcollide
