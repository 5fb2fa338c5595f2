// One detection's GPU part, without the world: the broad phase along one or three
// directions, started (measured, or from the depth the last detection measured) and
// collected; engine meshes that fail the GPU input check are left out and the run repeated
// (BadObjectPolicy::Exclude), or the detection fails (Fail). With three directions the
// candidates are united in world space (axis_union.hpp). A method that returns pairs
// (ReliableMethod) runs along one direction; its pairs are the candidates.
//
// Objects are named by their index in the span given to start(); the caller (the API) maps
// indices to its objects and words the errors (failure() holds the findings as data).
//
// Not thread-safe; one detection in flight per instance.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "broad/broad_phase.hpp"

namespace vkcollide::passes {

struct DetectionSettings {
    BroadPhaseSettings broad;  // `direction` is the first direction
    std::uint32_t axes = 1;    // 1, or 3: also the first direction's image axes u and v (record methods only)
    BadObjectPolicy bad_objects = BadObjectPolicy::Exclude;
    // The broad-phase method every direction runs (a change recreates the broad phases). No
    // default: the caller names it (the API: DetectionsInFlight::methodFactory); start()
    // refuses a null one.
    MethodFactory method = nullptr;
};

struct DetectionResult {
    std::vector<BroadPhaseResult> axes;           // one per direction, in order
    std::array<std::array<float, 3>, 3> directions{};
    // Broad-phase object index (CandidateTriangle::object) -> index in start()'s meshes.
    std::vector<std::uint32_t> objects;
    // Objects left out (ObjectFault::object: index in start()'s meshes), with what was wrong.
    std::vector<ObjectFault> excluded;
    std::vector<CandidateTriangle> united;        // with several directions
    // What the narrow phase tests: the united records, or the one direction's.
    std::span<const CandidateTriangle> candidates() const { return axes.size() > 1 ? std::span<const CandidateTriangle>(united) : axes[0].records; }
    // A method that returns pairs ran: axes[0].pairs (and gpu_triangles) are the candidates.
    bool hasPairs() const { return axes.size() == 1 && axes[0].has_pairs; }
};

class Detection {
public:
    // Creates the first direction's broad phase (its pipelines) now, with `method` (no
    // default, as for DetectionSettings::method).
    static Result<std::unique_ptr<Detection>> create(vk::Device& device, MethodFactory method);
    ~Detection();
    Detection(const Detection&) = delete;
    Detection& operator=(const Detection&) = delete;

    // Starts a detection of `meshes` (copied). `measure`: each direction measures its depth
    // complexity first (two submissions, waited for); otherwise it peels as many layers as
    // its last measurement (one submission, left in flight), measuring only where none is
    // known yet. Preconditions as BroadPhase's; settings.axes is 1 or 3.
    // `target` (optional, not with `measure`): the engine's waits go into the detection's
    // first queue submission, its signals into its last (the last direction's); or, with
    // target->engine, the one submission is recorded into the engine's command buffer
    // (refused by name where the detection needs more than one: three directions, or a
    // method that must measure first). The target's flags say what was submitted, also
    // after an error.
    [[nodiscard]] Result<void> start(std::span<const GpuMesh> meshes, const DetectionSettings& settings, bool measure,
                                     graph::SubmitTarget* target = nullptr);
    // Waits for every direction, leaving out bad engine meshes and running again as needed.
    [[nodiscard]] Result<DetectionResult> collect();
    // Moves the deadline of the detection in flight (BroadPhaseSettings::deadline): its
    // collect(), reruns and runs without bad objects all end by then. After collect(), that
    // of its follow-up stages.
    void setDeadline(std::chrono::steady_clock::time_point deadline);
    bool pending() const noexcept { return pending_; }
    // Whether collect() would find the GPU work done (it may still run GPU work again: a
    // buffer that overflowed, an engine mesh to leave out). Never waits. Not pending: true.
    // Errors: DeviceLost, or the status query's.
    [[nodiscard]] Result<bool> ready();
    // GPU work of a detection that failed with Timeout is still running (polls; never
    // waits). Buffers it reads must not change or be freed until it ends; the next start()
    // waits for it (with its own timeout) and fails with Timeout while it runs.
    bool busy() const;
    // Forgets the detection in flight without reading it (after host memory ran out): the
    // broad phases' GPU work is settled like a timed-out one (busy()). Allocates nothing.
    void abandon() noexcept;
    // The scene changed: the next detection measures instead of predicting its depth.
    void forgetDepth() noexcept { depth_known_.fill(false); }
    // Takes the depth `other` last measured (a second detection in flight predicts from the
    // first's measurement instead of measuring again).
    void shareDepth(const Detection& other) noexcept {
        last_depth_ = other.last_depth_;
        depth_known_ = other.depth_known_;
    }
    // Bytes of the broad phases' GPU buffers.
    std::uint64_t memoryBytes() const noexcept;
    // The first direction's device pairs (BroadPhaseSettings::device_pairs) of the detection
    // started last; nullopt without.
    std::optional<DevicePairsView> devicePairs() const { return broads_[0] ? broads_[0]->devicePairs() : std::nullopt; }

    // A follow-up stage (broad/follow_up.hpp) on the first direction's broad phase, made by
    // `factory` on first use, and its run after collect() succeeded: on the objects that
    // detection tested (excluded ones left out, run indices as DetectionResult::objects),
    // within what is left of its deadline.
    [[nodiscard]] Result<FollowUpStage*> followUp(FollowUpFactory factory);
    [[nodiscard]] Result<void> runFollowUp(FollowUpStage& stage);

    // After start() or collect() failed with InvalidMesh: the GPU check's findings (objects
    // as indices in start()'s meshes), and whether every object had been left out. Empty
    // for other errors.
    struct Failure {
        std::vector<ObjectFault> faults;
        bool none_left = false;
    };
    const Failure& failure() const noexcept { return failure_; }

private:
    explicit Detection(vk::Device& device) : device_(&device) {}
    void selectRunObjects();
    Result<void> startAxes(bool measure, graph::SubmitTarget* target);
    Result<std::vector<BroadPhaseResult>> gather();
    bool excludable(const Error& e) const;
    Result<void> excludeBad();
    Result<std::vector<BroadPhaseResult>> runExcluding();
    Error failed(Error e);

    vk::Device* device_;
    // One broad phase per direction (the second and third only for three axes).
    std::array<std::unique_ptr<BroadPhase>, 3> broads_;
    std::array<MethodFactory, 3> broad_methods_{};  // the method each was created with
    // The first direction's broad phase of the method used before the current one, kept
    // so that alternating methods does not create pipelines again.
    std::unique_ptr<BroadPhase> spare_;
    MethodFactory spare_method_ = nullptr;
    std::array<std::uint32_t, 3> last_depth_{};
    std::array<bool, 3> depth_known_{};
    // The detection in flight.
    bool pending_ = false;
    DetectionSettings settings_;
    std::uint32_t axes_ = 1;
    std::array<std::array<float, 3>, 3> directions_{};
    std::vector<GpuMesh> meshes_;              // as given
    std::vector<std::uint32_t> run_objects_;   // broad-phase index -> index in meshes_
    std::vector<GpuMesh> run_meshes_;          // meshes_ without the excluded ones
    const ObjectPairMask* run_pair_mask_ = nullptr;  // settings' mask, or subset_mask_ when objects are left out
    ObjectPairMask subset_mask_;
    std::vector<ObjectFault> excluded_;
    std::array<bool, 3> axis_pending_{};                              // submitted, to collect
    std::array<std::optional<BroadPhaseResult>, 3> ready_;            // measured runs, complete
    std::uint32_t failed_axis_ = 0;            // the axis whose error the last call returned
    Failure failure_;
};

}  // namespace vkcollide::passes
