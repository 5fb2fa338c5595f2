// Detections from start to result: detect(), submit() with the engine's semaphores,
// record() into the engine's command buffer, polling (ready, tryCollect); the two slots they
// run in are in_flight.* (pipelining; docs/api.md, "Engines: synchronisation and latency").
#include <new>
#include <stdexcept>

#include "api/world_impl.hpp"
#include "core/host_memory.hpp"
#include "vk/debug_names.hpp"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

// No exception crosses the API: host memory running out anywhere in a detection (the
// records read back, the union of three axes, the narrow phase's arrays, the result)
// becomes OutOfMemory, and the detection is forgotten (its GPU work is waited for like a
// timed-out one's).
template <typename F>
auto hostGuarded(passes::Detection& detection, bool& io_in_flight, F&& f) -> decltype(f()) {
    return hostMemoryGuarded("the detection", std::forward<F>(f), [&] {
        detection.abandon();
        io_in_flight = false;
    });
}

// Refused before anything is submitted: Vulkan would reject these, and a batch of only
// the waits and signals could not be made from them either.
Result<void> checkSync(const SubmitSync& sync) {
    for (auto [list, what] : {std::pair{sync.wait, "wait"}, std::pair{sync.signal, "signal"}})
        for (std::size_t i = 0; i < list.size(); ++i) {
            if (list[i].semaphore == VK_NULL_HANDLE)
                return Error(ErrorCode::InvalidArgument, "submit: SubmitSync::" + std::string(what) + "[" + std::to_string(i) +
                                                             "] has a null semaphore");
            if (list[i].stages == 0)
                return Error(ErrorCode::InvalidArgument, "submit: SubmitSync::" + std::string(what) + "[" + std::to_string(i) +
                                                             "] has stage mask 0 (ALL_COMMANDS: all of the detection's work)");
        }
    return {};
}

}  // namespace

Result<void> CollisionWorld::Impl::begin(const DetectSettings& settings, bool measure, graph::SubmitTarget* target) {
    if (device_lost)
        return Error(ErrorCode::DeviceLost, "the device was lost in an earlier detection: destroy the world and create a new Context");
    detections.last_device_pairs.reset();
    auto run = detections.freeRun(device());
    if (!run) return run.error();
    auto started = hostGuarded(*(*run)->detection, (*run)->in_flight, [&] { return start(**run, settings, measure, target); });
    if (started)
        if (auto view = (*run)->detection->devicePairs()) detections.last_device_pairs = detections.devicePairsOf(*view, **run);
    return started;
}

Result<DetectResult> CollisionWorld::detect(const DetectSettings& settings) { return impl_->detectCall(settings, nullptr); }

Result<DetectResult> CollisionWorld::Impl::detectCall(const DetectSettings& settings, DetectResult* reuse_memory) {
    auto scope = guard.enter("CollisionWorld::detect");
    if (!scope) return scope.error();
    if (detections.pending()) return Error(ErrorCode::InvalidArgument, "detect while a detection is in flight: collect() it first");
    // The reliable method measures nothing before its one submission: it is left in flight
    // here and collect() waits for it, so that what the host prepares for the result
    // (prepareResultMemory) runs while the GPU works.
    const bool measure = settings.method == DetectMethod::Peeling && settings.peeling.measure_layers;
    if (auto ok = begin(settings, measure, nullptr); !ok) return ok.error();
    Run& run = detections.runs[detections.oldest];
    return hostGuarded(*run.detection, run.in_flight, [&] { return collect(run, false, reuse_memory); });
}

Result<void> CollisionWorld::detectInto(DetectResult& io_result, const DetectSettings& settings) {
    auto r = impl_->detectCall(settings, &io_result);
    if (!r) return r.error();
    io_result = std::move(*r);
    return {};
}

Result<void> CollisionWorld::collectInto(DetectResult& io_result) {
    auto r = impl_->collectCall(&io_result);
    if (!r) return r.error();
    io_result = std::move(*r);
    return {};
}

Result<void> CollisionWorld::submit(const DetectSettings& settings, const SubmitSync& sync) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::submit");
    if (!scope) return scope.error();
    if (auto ok = checkSync(sync); !ok) return ok.error();
    graph::SubmitTarget target{sync};
    auto started = w.begin(settings, false, &target);
    if (!started && !target.signals_submitted && !(sync.wait.empty() && sync.signal.empty())) {
        // Keep the promise made to the engine's queues: its waits consumed and its
        // signals made, after whatever of this detection was submitted.
        if (!w.detections.sync_only.valid())
            if (auto s = vk::Submission::create(w.device(), "sync-only submission")) w.detections.sync_only = std::move(*s);
        if (w.detections.sync_only.valid()) {
            SubmitSync rest = sync;
            if (target.waits_submitted) rest.wait = {};
            (void)w.detections.sync_only.submitSyncOnly(rest);  // a failure here is the device's, reported by the next call
        }
    }
    return started;
}

Result<void> CollisionWorld::record(const EngineCommandBuffer& target, const DetectSettings& settings) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::record");
    if (!scope) return scope.error();
    graph::SubmitTarget into{{}, &target};
    // One label around all of it: several executors may record into the engine's buffer.
    const bool label = target.command_buffer != VK_NULL_HANDLE;
    if (label) vk::beginLabel(w.device(), target.command_buffer, "detect");
    auto recorded = w.begin(settings, false, &into);
    if (label) vk::endLabel(w.device(), target.command_buffer);
    return recorded;
}

Result<DetectResult> CollisionWorld::collect() { return impl_->collectCall(nullptr); }

Result<DetectResult> CollisionWorld::Impl::collectCall(DetectResult* reuse_memory) {
    auto scope = guard.enter("CollisionWorld::collect");
    if (!scope) return scope.error();
    if (!detections.pending()) return Error(ErrorCode::InvalidArgument, "collect without a detection in flight: submit() first");
    Run& run = detections.runs[detections.oldest];
    detections.oldest = 1 - detections.oldest;  // the other slot, in flight or not, is the oldest now
    return hostGuarded(*run.detection, run.in_flight, [&] { return collect(run, true, reuse_memory); });
}

Result<bool> CollisionWorld::ready() {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::ready");
    if (!scope) return scope.error();
    if (!w.detections.pending()) return Error(ErrorCode::InvalidArgument, "ready without a detection in flight: submit() first");
    auto done = w.detections.runs[w.detections.oldest].detection->ready();
    if (!done) return w.noted(done.error());
    return *done;
}

Result<std::optional<DetectResult>> CollisionWorld::tryCollect() {
    auto done = ready();
    if (!done) return done.error();
    if (!*done) return std::optional<DetectResult>();
    auto r = collect();
    if (!r) return r.error();
    return std::optional<DetectResult>(std::move(*r));
}

Result<DevicePairs> CollisionWorld::devicePairs() const {
    if (!impl_->detections.last_device_pairs)
        return Error(
            ErrorCode::InvalidArgument,
            "devicePairs: the detection started last did not ask for them (DetectSettings::reliable.device_pairs), or none started");
    return *impl_->detections.last_device_pairs;
}

bool CollisionWorld::pending() const noexcept { return impl_->detections.pending(); }
std::uint32_t CollisionWorld::inFlight() const noexcept { return impl_->detections.inFlight(); }

WorldState CollisionWorld::state() const {
    if (impl_->device_lost) return WorldState::DeviceLost;
    return impl_->detections.busy() ? WorldState::Busy : WorldState::Ready;
}

}  // namespace vkcollide
