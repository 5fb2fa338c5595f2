// The GPU broad phase on the render graph: a common front (clear, GPU input checks, bounds,
// fit), a method's stages (PeelingMethod, the paper's passes 1-4: sampling, ray merging,
// primitive separation, packing; or ReliableMethod, the cell stage), then the header
// readback. docs/rooms.md maps
// each stage to its file and each buffer to its row.
//
// run() makes two submissions with a host wait between them: the first measures (depth
// complexity), the method reads it, the second does the rest (one submission for a method
// that measures nothing). submit() records everything
// in one submission from a predicted depth. Both go through one recording path (record()).
//
// Preconditions (the API checks them; src/api/validation.cpp): settings as documented in
// BroadPhaseSettings, at least one mesh, every mesh non-empty with 4-byte aligned addresses,
// a stride of at least 12, a finite transform, fewer than 2^30 triangles in all. The broad
// phase asserts them.
//
// Not thread-safe; one run in flight per instance.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "broad/buffer_table.hpp"
#include "broad/common_stages.hpp"
#include "broad/follow_up.hpp"
#include "broad/method.hpp"
#include "graph/executor.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

// Device memory the broad phase (core and PeelingMethod rows) needs for a resolution and
// triangle count, without the collision-ray image (bytes, all buffers); with depth-aware
// separation's buffers when `depth_aware`.
VkDeviceSize broadPhaseMemory(std::uint32_t resolution, std::uint32_t triangles, std::uint32_t objects, bool depth_aware = true);

class BroadPhase {
public:
    // `method` makes the method that runs (PeelingMethod::create, ReliableMethod::create):
    // no default, so that every caller names the one it runs.
    static Result<std::unique_ptr<BroadPhase>> create(vk::Device& device, MethodFactory method);
    // Waits for GPU work still in flight (also work a timed-out run left behind) before
    // any buffer is freed.
    ~BroadPhase();
    BroadPhase(const BroadPhase&) = delete;
    BroadPhase& operator=(const BroadPhase&) = delete;
    // Two submissions with a host wait between them: the first measures the depth
    // complexity, the second peels exactly that many layers (or the cap).
    // `target` (optional): the engine's waits go into the first submission, its signals
    // into the last (graph::SubmitTarget); not into an engine's command buffer (run() waits
    // on the host between its submissions: refused with InvalidArgument).
    [[nodiscard]] Result<BroadPhaseResult> run(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings,
                                               graph::SubmitTarget* target = nullptr, bool signal = true);
    // One submission that peels `layers` layers (at most the cap) whatever the depth
    // complexity turns out to be: rays with more layers become collision rays
    // (conservative). collect() waits and reads the result; it reports the depth
    // complexity measured in the same submission.
    // `target` (optional): the engine's semaphores (signals only when `signal`) or its
    // command buffer (graph::SubmitTarget).
    [[nodiscard]] Result<void> submit(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings, std::uint32_t layers,
                                      graph::SubmitTarget* target = nullptr, bool signal = true);
    [[nodiscard]] Result<BroadPhaseResult> collect();
    bool pending() const noexcept { return pending_; }
    // After a run or collect() failed with ErrorCode::Timeout its GPU work goes on: busy()
    // polls it, settle() waits for it. The next run() or submit() settles first (with its
    // own timeout) and fails with Timeout while that work still runs.
    bool busy() const { return executor_.busy(); }
    // Done when the submission in flight has finished (collect() will not wait); never waits.
    [[nodiscard]] Result<vk::Completion> poll() { return executor_.poll(); }
    // Forgets the run in flight without waiting for it (after host memory ran out while
    // collecting it): its GPU work is settled like a timed-out one.
    void abandon() noexcept { pending_ = false; }
    // Moves the run's deadline (BroadPhaseSettings::deadline): the waits of collect() and
    // of the method's reruns end by then.
    void setDeadline(std::chrono::steady_clock::time_point deadline) { run_.settings.deadline = deadline; }
    [[nodiscard]] Result<void> settle(std::uint64_t timeout_ns) { return executor_.settle(timeout_ns); }
    MethodTraits traits() const noexcept { return method_->traits(); }
    // After an InvalidMesh error from the GPU input check: what it found, per object (run
    // indices); at most one per kind of problem, so other objects may be bad too.
    const std::vector<ObjectFault>& faults() const noexcept { return faults_; }
    // Bytes of the GPU buffers the broad phase holds (its own, not the meshes').
    // Every buffer is a row of its table (the methods', their stages' and the follow-ups').
    std::uint64_t memoryBytes() const noexcept { return table_.bytes() + executor_.memoryBytes(); }
    // The method's device pairs (BroadPhaseSettings::device_pairs) of the run started last.
    std::optional<DevicePairsView> devicePairs() const { return method_->devicePairs(); }
    // Makes now every pipeline the method may record with `settings` (its forms and the
    // stages it would create on first use; BroadPhaseMethod::preparePipelines).
    [[nodiscard]] Result<void> preparePipelines(const BroadPhaseSettings& settings) { return method_->preparePipelines(settings); }
    // The follow-up stage `factory` makes (broad/follow_up.hpp), created on first use with
    // its rows in this broad phase's table and kept while the broad phase lives.
    [[nodiscard]] Result<FollowUpStage*> followUp(FollowUpFactory factory);
    // Runs `stage` after the last run was collected: its submissions on this executor,
    // each within what is left of that run's deadline (timeout_ns without one), until it
    // answers Done. A Timeout leaves its work in flight (busy()), like a run's.
    [[nodiscard]] Result<void> runFollowUp(FollowUpStage& stage);
    // The projection the last run sampled with, as the GPU holds it (the fit's output, or
    // the caller's region as uploaded). For tests: BroadPhaseResult::projection is the host's.
    gpu::Projection gpuProjection() const;

private:
    explicit BroadPhase(vk::Device& device) : device_(&device), executor_(device) {}
    // Sizes the buffers, lets the method prepare, uploads objects, frame and projection
    // (timed as run_.host.upload_ms).
    Result<void> prepare(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings);
    Result<void> prepareRun(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings);
    RunView view() const;
    // The one recording path (timed into run_.host.declare_ms): front and the method's
    // measuring passes, its main passes, then the header readback; or the method's Again
    // passes alone.
    // or a follow-up stage's next submission.
    enum class Recording { Measure, Main, Whole, Again, FollowUp };
    void record(graph::Graph& g, Recording what, FollowUpStage* follow_up = nullptr);
    // One more submission after a collect() (Recording::Again or FollowUp), run and waited
    // for within what is left of the run's deadline; nothing starts after it ends.
    // `what` names it in the error.
    Result<graph::ExecutionReport> runMore(Recording what, FollowUpStage* follow_up, const char* what_runs);
    gpu::Header readHeader() const;
    Result<void> checkInputs(const gpu::Header& header);
    Result<void> checkExtent(const gpu::Header& header) const;
    static void addTimings(BroadPhaseResult& io_result, const graph::ExecutionReport& report);

    vk::Device* device_;
    BufferTable table_;
    CoreBuffers core_{};
    std::unique_ptr<CommonStages> common_;
    std::unique_ptr<BroadPhaseMethod> method_;
    // Follow-up stages by the factory that made them (their rows are in table_).
    std::vector<std::pair<FollowUpFactory, std::unique_ptr<FollowUpStage>>> follow_ups_;
    bool pending_ = false;
    std::vector<ObjectFault> faults_;
    // The run being recorded or in flight (RunView refers to it).
    struct Prepared {
        gpu::Frame frame{};
        BroadPhaseSettings settings;
        std::vector<GpuMesh> meshes;
        std::vector<gpu::ObjectGpu> objects;  // as uploaded
        bool any_gpu_check = false;
        BroadPhaseResult first;  // timings of a separate measuring submission
        graph::HostTimes host;   // its upload and declaration times (the executor's come with its reports)
    } run_;
    // Declared last, destroyed first: it waits for work in flight (a wait that timed out
    // leaves it in flight) before the buffers and the method's buffers are freed.
    graph::Executor executor_;
};

}  // namespace vkcollide::passes
