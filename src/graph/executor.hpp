// Render graph, device side: allocates transient resources (kept between executions, so a
// per-frame graph does not reallocate), records the compiled plan into one command buffer
// with its barriers, submits it and reports each pass's GPU time from timestamps.
//
// Reuse: the plan's commands go onto a command tape first (graph/pass_context.hpp); when
// the tape equals the one the executor's own command buffer was recorded from and no
// buffer, image or pipeline of the device was destroyed since (vk::Device::
// resource_generation), that command buffer is submitted again without recording (the
// timestamp queries are reset on the host, so it writes fresh ones). Otherwise the tape is
// replayed into the command buffer, and kept. Never reused: work recorded into an engine's
// command buffer, and a submission whose callbacks used PassContext::cmd directly.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "graph/command_tape.hpp"
#include "graph/graph.hpp"
#include "graph/pass_context.hpp"
#include "vk/event.hpp"
#include "vk/resources.hpp"

namespace vkcollide::graph {

struct PassTiming {
    std::string name;
    double gpu_ms = 0;
    StageTag stage = 0;  // as the pass declared it
};

// Host wall time (steady clock, ms) around submissions: where a detection's host time goes
// beyond the GPU passes. The executor fills compile..launch_wake for each submission it
// makes; upload and declare belong to the code that builds the graph (the broad phase).
// Sums over several submissions add up (operator+=).
struct HostTimes {
    double upload_ms = 0;       // the builder's per-run inputs written (buffers sized, uploads)
    double declare_ms = 0;      // the builder's graph declared (passes, resources, callbacks)
    double compile_ms = 0;      // Graph::compile, or the check that the last plan still applies
    // Wait for the previous submission, transients, timestamp queries, the command tape
    // built and compared, and the command buffer recorded from it (unless reused).
    double record_ms = 0;
    double submit_ms = 0;       // command buffer ended and handed to the queue
    double wait_ms = 0;         // collect(): waiting for the GPU (less milestone_ms)
    double milestone_ms = 0;    // collect(): in the milestone's callback (Executor::setMilestone)
    double gpu_span_ms = 0;     // ExecutionReport::total_gpu_ms: first pass's start to last pass's end
    // From the queue submission's return to collect()'s waking up, less gpu_span_ms (at
    // least 0): the queue's launch latency, the GPU's gaps before the first and after the last timestamp,
    // and the wake-up of the waiting thread, when collect() follows submit() at once; with
    // host work in between, that work too (and it is no longer all latency).
    double launch_wake_ms = 0;
    std::uint32_t submissions = 0;
    std::uint32_t reused = 0;  // of the submissions: command buffers submitted again, not recorded
    HostTimes& operator+=(const HostTimes& o) noexcept;
};

struct ExecutionReport {
    std::vector<PassTiming> passes;  // in execution order
    std::vector<std::string> culled;
    double total_gpu_ms = 0;         // first pass start to last pass end
    HostTimes host;                  // this submission's host side (upload and declare: 0)
};

// Where one submission's work goes and what it waits for and signals (the API's submit()
// and record()): the engine's semaphores in the queue submission, or the
// engine's command buffer instead of a submission of our own. A detection may take several
// queue submissions: the engine's waits go into the first one made (waits_submitted says
// whether that happened), its signals into the one its caller marks as the last.
struct SubmitTarget {
    SubmitSync sync;
    const EngineCommandBuffer* engine = nullptr;  // record into it (its timeline tells completion)
    bool waits_submitted = false;    // sync.wait is in a submission that succeeded
    bool signals_submitted = false;  // sync.signal is (or the engine's command buffer holds the work)
};

// How long the executor waits for the GPU unless told otherwise.
inline constexpr std::uint64_t kDefaultTimeoutNs = 60ull * 1000 * 1000 * 1000;

// The one timeout rule of a detection, for every submission and rerun of every stage: a
// wait may take what is left before the deadline (0 once it passed), or timeout_ns where
// there is no deadline.
std::uint64_t waitNs(std::uint64_t timeout_ns, const std::optional<std::chrono::steady_clock::time_point>& deadline);
// `e` as the detection's error: a Timeout under a deadline names the whole timeout (a
// wait's own message would name only what was left of it).
Error timeoutOfDetection(std::uint64_t timeout_ns, bool has_deadline, Error e);

// Every wait takes a timeout (ns). A wait that runs out returns ErrorCode::Timeout and
// leaves the work in flight: nothing of it is reused until a later wait (settle(), the
// next submit(), the destructor) has seen it finish.
class Executor {
public:
    explicit Executor(vk::Device& device) : device_(&device) {}
    // Waits for work in flight (however long: its resources may not be freed before).
    ~Executor();
    Executor(const Executor&) = delete;
    Executor& operator=(const Executor&) = delete;

    // Compiles (or reuses the last plan: planKey()), records and submits the graph; returns
    // without waiting for it (but waits up to timeout_ns for the previous submission first).
    // `target` (optional): the engine's waits (unless already submitted) and, when
    // `signal`, its signals go into this submission, or the work is recorded into the
    // engine's command buffer; the target's flags are updated on success.
    [[nodiscard]] Result<void> submit(const Graph& graph, std::uint64_t timeout_ns = kDefaultTimeoutNs,
                                      SubmitTarget* target = nullptr, bool signal = true);
    // Waits for the last submission and reads its timestamps. With polling set
    // (setWaitPolling), the wait sleeps until shortly before the work's expected end, then
    // polls the fence.
    [[nodiscard]] Result<ExecutionReport> collect(std::uint64_t timeout_ns = kDefaultTimeoutNs);
    // submit() then collect().
    [[nodiscard]] Result<ExecutionReport> run(const Graph& graph, std::uint64_t timeout_ns = kDefaultTimeoutNs);
    // Waits up to timeout_ns for any work in flight, also work a collect() gave up on.
    [[nodiscard]] Result<void> settle(std::uint64_t timeout_ns);
    // How collect() waits: 0 (the default) sleeps in the driver's wait, which wakes the
    // thread 0.05-0.2 ms after the GPU finishes (NVIDIA's driver on an H200: docs/results.md);
    // otherwise it sleeps until kPollLeadNs before the work's expected end (the submission
    // time plus the last collected GPU span), polls the fence for up to poll_ns from there,
    // and sleeps for the rest of the timeout if the work is still running. Polling keeps
    // the waiting core busy for at most about poll_ns + kPollLeadNs per collect().
    void setWaitPolling(std::uint64_t poll_ns) noexcept { poll_ns_ = poll_ns; }
    static constexpr std::uint64_t kPollLeadNs = 150'000;
    // Called on the waiting thread while collect() polls: when polling starts (the work is
    // expected to end within kPollLeadNs) and every kPollHookNs after. The world wakes the
    // narrow phase's workers with it, so that they are awake, not asleep in the kernel, when
    // the results arrive. Empty: nothing is called. Must not throw.
    void setPollHook(std::function<void()> hook) { poll_hook_ = std::move(hook); }
    static constexpr std::uint64_t kPollHookNs = 50'000;
    // A milestone's polling naps this long in the fence's wait once the window has passed.
    static constexpr std::uint64_t kMilestoneNapNs = 50'000;
    // Points inside the next submission that the host hears of before the submission ends:
    // the submission sets `events` in this order, each through PassContext::signalHost.
    // collect() polls the first (asleep in the fence's wait until shortly before the GPU
    // time at which the last submission's first such pass began, by its timestamps, with
    // poll_hook calls while it polls), calls `reached(0)` on the waiting thread once it is
    // set, then polls the next, and so on, then waits for the rest of the submission: host
    // work on what the earlier commands left in host-visible memory runs while the GPU does
    // the later ones. Where an event was not set by the end (no such pass ran), neither it
    // nor the ones after it are reached. For the next submit() only, which unsets the
    // events once the previous submission has ended.
    struct Milestone {
        std::span<const vk::Event> events;
        std::function<void(std::size_t)> reached;  // with each event's index; must not throw
    };
    void setMilestone(Milestone milestone) { next_milestone_ = std::move(milestone); }
    // Whether submitted work is still running (polls; never waits).
    bool busy() const;
    // Done once the last submission has finished, NotYet while it runs; never waits.
    // Errors: DeviceLost, or the status query's.
    [[nodiscard]] Result<vk::Completion> poll() { return submission_.valid() ? submission_.poll() : vk::Completion::Done; }
    // Bytes of device memory of the cached transient buffers and images.
    std::uint64_t memoryBytes() const noexcept;
    // How many times submit() compiled a graph; a graph whose planKey() equals the last
    // compiled one's reuses its plan (for tests).
    std::uint64_t compilations() const noexcept { return compilations_; }
    // How many times submit() submitted its command buffer again instead of recording it
    // (for tests; HostTimes::reused says it per submission).
    std::uint64_t reuses() const noexcept { return reuses_; }

private:
    Result<void> prepareResources(const Graph& graph, const GraphPlan& plan, PassContext& ctx);
    // The plan of `graph`: the last one when its planKey() is unchanged, else compiled.
    Result<void> planFor(const Graph& graph);
    // collect()'s wait for the last submission (setWaitPolling).
    Result<void> waitForCollect(std::uint64_t timeout_ns);
    // collect()'s wait for one of the milestone's events (`first`: the first of them): whether
    // it is set (false: the submission ended without it, or timeout_ns passed first).
    Result<bool> waitForMilestone(const vk::Event& event, bool first, std::uint64_t timeout_ns);
    // The plan's commands, the executor's own (barriers, timestamps, rendering, labels) and
    // the passes', onto tape_; outer_label: inside one "vkcollide: detect" label.
    void tapePlan(const Graph& graph, const GraphPlan& plan, PassContext& ctx, bool outer_label);
    void tapeBarriers(const std::vector<Barrier>& barriers, const PassContext& ctx);
    // PassContext::cmd's conversion: the command buffer, recording, with tape_ replayed
    // into it up to now.
    VkCommandBuffer directCommands();
    friend class PassContext::DirectCommandBuffer;

    vk::Device* device_;
    // The last plan compiled and its graph's planKey(); scratch_key_: this submission's.
    GraphPlan plan_;
    std::vector<std::uint64_t> plan_key_, scratch_key_;
    bool plan_valid_ = false;
    std::uint64_t compilations_ = 0;
    // tapeBarriers()'s scratch, kept between submissions.
    std::vector<VkImageMemoryBarrier2> image_barriers_;
    std::vector<VkBufferMemoryBarrier2> buffer_barriers_;
    std::vector<VkRenderingAttachmentInfo> colors_;
    // This submission's commands, and those the own command buffer holds (held_valid_:
    // submission_.canResubmit() with them, recorded at resource generation held_generation_).
    CommandTape tape_, held_;
    bool held_valid_ = false;
    std::uint64_t held_generation_ = 0;
    std::uint64_t reuses_ = 0;
    // The recording of this submission once begun (the engine's command buffer from the
    // start, our own once a callback goes direct or the tape is replayed), how much of
    // tape_ it holds, whether a callback recorded directly, and a begin() that failed
    // under a direct callback (submit() returns it).
    VkCommandBuffer recording_ = VK_NULL_HANDLE;
    std::size_t replayed_ = 0;
    bool went_direct_ = false;
    std::optional<Error> direct_error_;
    // Mutable for busy(): polling the fence changes nothing the executor promises.
    mutable vk::Submission submission_;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    std::uint32_t query_capacity_ = 0;
    std::uint64_t poll_ns_ = 0;
    std::function<void()> poll_hook_;
    std::uint64_t last_gpu_span_ns_ = 0;
    Milestone next_milestone_, pending_milestone_;
    static constexpr std::uint32_t kNoPass = ~0u;
    std::uint32_t pending_signal_pass_ = kNoPass;  // the first pass of pending_names_ that sets an event
    std::uint64_t last_milestone_ns_ = 0;  // the GPU time to that pass's start, last submission (its timestamps)  // the last collected submission's, for the expected end
    // Transients cached by name; recreated when the description changes.
    struct CachedBuffer {
        VkDeviceSize size = 0;
        VkBufferUsageFlags usage = 0;
        vk::Buffer buffer;
    };
    struct CachedImage {
        ImageInfo info;
        VkImageUsageFlags usage = 0;
        vk::Image image;
    };
    std::map<std::string, CachedBuffer> buffers_;
    std::map<std::string, CachedImage> images_;
    std::vector<std::string> pending_names_;
    std::vector<StageTag> pending_stages_;
    std::vector<std::string> pending_culled_;
    HostTimes pending_host_;                                  // the submission in flight's, so far
    std::chrono::steady_clock::time_point pending_submitted_at_;  // when its queue submission returned
};

}  // namespace vkcollide::graph
