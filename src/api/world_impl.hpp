// CollisionWorld's state, shared by the files of src/api/: the registry (world.cpp), the
// automatic settings (settings.cpp), one detection (detect.cpp). Input rules are checked in
// validation.cpp; the GPU work of a detection is passes::Detection.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "passes/contacts/contact_stage.hpp"
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
        // Host meshes: positions and indices again, for the narrow phase's TriangleSource
        // (reliable method) and for measuring after updateVertices (reading the upload
        // buffer back would cross the bus: it may be write-combined device memory).
        std::vector<Float3> host_positions;
        std::vector<std::uint32_t> host_indices;
        passes::GpuMesh gpu;           // addresses, counts, flags (transform set per run)
        // Object-space box (host meshes) and typical edge length (object units; measured for
        // host meshes, given for GPU meshes), for the automatic settings.
        std::array<float, 6> box{};
        float edge_length = 0;
        // Host meshes, measured when their geometry changes: sum over triangles of
        // area * n n^T (xx, yy, zz, xy, xz, yz; object space) for the direction, and the
        // largest |coordinate| (the reliable method's limit).
        std::array<double, 6> area_moment{};
        float max_abs = 0;
        // Index of the object in `source` (kNoSource: not in it).
        std::uint32_t source_index = 0xFFFFFFFFu;
    };
    static constexpr std::uint32_t kNoSource = 0xFFFFFFFFu;

    Context* context = nullptr;
    std::unique_ptr<ThreadPool> pool;
    NarrowWorkspace narrow_workspace;  // reused by every detection's narrow phase
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
    // Declared after the objects: destroyed first, it waits for a detection in flight
    // before their buffers are freed.
    std::unique_ptr<passes::Detection> detection;
    // Object-level contacts (DetectSettings::contacts), created at the first detection
    // that asks for them.
    std::unique_ptr<passes::ContactStage> contact_stage;

    // A detection met a lost device (WorldState::DeviceLost): every later one fails at once.
    bool device_lost = false;

    // The detection in flight (vectors kept between detections).
    std::vector<passes::GpuMesh> run_meshes;
    std::vector<ObjectId> run_ids;  // index in the detection's meshes -> ObjectId
    std::vector<ObjectId> finish_ids;  // the broad phase's objects (bad ones left out) -> ObjectId
    NarrowOptions narrow_options;
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
    void objectsChanged() {
        detection->forgetDepth();
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
    // (validation::checkSettings checks the result).
    DetectSettings resolve(const DetectSettings& in, std::string* note) const;
    static void measureHost(Object& o, std::span<const Float3> positions, std::span<const std::uint32_t> indices);

    // detect.cpp
    static passes::MethodFactory methodFactory(DetectMethod method);
    Result<void> start(const DetectSettings& settings, bool measure);
    Result<DetectResult> collect();
    Error describeFailure(const Error& e) const;
    Result<DetectResult> finish(passes::DetectionResult detected);
    // contacts.cpp: DetectResult::contacts and their statistics, after the narrow phase
    // (`out.pairs` mapped to ObjectIds); `ids`: the detection's objects.
    Result<void> addContacts(const passes::DetectionResult& detected, std::span<const ObjectId> ids, DetectResult& io_out);
};

}  // namespace vkcollide
