// The detections in flight: the world's two slots (a second detection may be submitted
// before the first is collected: pipelining, docs/api.md), which one is collected next,
// and what the calls that change objects ask of them (is a detection in flight, does one
// read these vertices, does GPU work of an abandoned one still run).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "api/auto_settings.hpp"
#include "detect/detection.hpp"
#include "vk/submission.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

struct DetectionsInFlight {
    // One detection, from start() to finish(): its GPU part and what the narrow phase
    // needs of the objects as they were at start() (ids, transforms, flags), so that the
    // objects may move (setTransform) and engine meshes change buffers (setGpuMeshBuffers)
    // while it is in flight.
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
        std::optional<AutoSettings::GridChoice> grid;  // the tuned grid it runs (its time goes back to the tuner)
        std::string note;
        std::chrono::steady_clock::time_point start;
        // When every wait of its GPU work ends (DetectSettings::limits.timeout_ms): start + the
        // timeout for detect(); submit() and record() restart it at collect().
        std::chrono::steady_clock::time_point deadline;
        double start_ms = 0, wait_ms = 0;  // host: start() (settings, record, submit); collect's wait and readback
        double prepare_ms = 0;  // of wait_ms: detect()'s result memory made ready (prepareResultMemory)
        double settings_ms = 0;            // host: start()'s settings, validation and mask (DetectStats::host.settings_ms)
        bool sorts_on_gpu = false;         // the reliable method's host pairs come back sorted by the GPU
        // During collect(): where nameEarly names the pairs (the caller's result for
        // detectInto, else the memory made ready) and how long that took.
        std::vector<TrianglePair>* early_into = nullptr;
        double early_name_ms = 0;
    };

    // A batch of only the engine's waits and signals, for a submit() that failed after it
    // was given them (engine_sync.cpp); created on first use.
    vk::Submission sync_only;
    // runs[oldest] is collected next.
    std::array<Run, 2> runs;
    std::uint32_t oldest = 0;
    // The device pairs of the detection started last (CollisionWorld::devicePairs()); reset
    // by every start, set when it asked for them.
    std::optional<DevicePairs> last_device_pairs;

    static passes::MethodFactory methodFactory(DetectMethod method);
    // The slot a new detection starts in (created when needed).
    Result<Run*> freeRun(vk::Device& device);
    DevicePairs devicePairsOf(const passes::DevicePairsView& v, const Run& run) const {
        return {v.pairs,          v.pairs_address, v.header, v.header_address, v.capacity, static_cast<std::uint32_t>(&run - runs.data()),
                v.responses,      v.responses_address, v.response_capacity};
    }

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
    // Whether a detection in flight reads object `id`'s vertices at `upload` (its upload
    // buffer's address) or `positions` (its host copy).
    bool reads(ObjectId id, VkDeviceAddress upload, const Float3* positions) const;
    // InvalidArgument naming `what` while a detection is in flight: for calls that change
    // what it reads.
    Result<void> notPending(const char* what) const;
    // Fails with Timeout while the GPU work of a timed-out detection runs (WorldState::Busy;
    // settling()): for calls that change or free what that work reads.
    Result<void> notBusy(const char* what) const;
    // The objects changed: no depth complexity measured before holds.
    void forgetDepth() {
        for (Run& r : runs)
            if (r.detection) r.detection->forgetDepth();
    }
};

}  // namespace vkcollide
