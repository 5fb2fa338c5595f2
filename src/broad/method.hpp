// The seam between the broad phase and a method. Every run records
//
//     front (clear, GPU input checks, bounds, fit)      common_stages.hpp
//     method: Phase::Measure                            BroadPhaseMethod::record
//     method: Phase::Main                               BroadPhaseMethod::record
//     readback of the header                            common_stages.hpp
//
// run() submits front and Measure, waits, lets the method read the header (begin), then
// submits Main; submit() records all of it in one submission after begin() with a
// predicted depth. Then collect() reads the method's outputs; a method whose GPU-sized
// buffers overflowed grows them and answers Again, and the broad phase records
// Phase::Again and submits it on the same executor, within the same deadline, until the
// method answers Done. BroadPhase::record is the one recording path for all of them, and
// the broad phase's executor the one that submits: a method owns no submissions. A stage
// that runs after a collected run (broad/follow_up.hpp: the contact stage) takes the same
// path.
//
// PeelingMethod (the paper: sampling, merging, separation, packing) returns triangle
// records, its peeling steps in chunks of Again submissions where one would run long;
// ReliableMethod (broad/cells/: the cell stage) measures nothing, runs in one
// submission (plus one per overflow or pair-pass chunk) and returns candidate pairs
// (BroadPhaseResult::has_pairs). To add one: a class implementing this interface in its
// own folder under src/broad/ (with a sources.cmake there), its buffers added as rows of
// the BufferTable in its factory, its own gpu::Frame extension behind gpu::Frame::method
// if its shaders need one; BroadPhase::create(device, yourFactory) runs it (docs/rooms.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "broad/buffer_table.hpp"
#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "graph/executor.hpp"

namespace vkcollide::passes {

// The rows every method shares, added by the broad phase before the method's own.
struct CoreBuffers {
    BufferId frame, objects, projection, header, header_readback;
};

// What the broad phase needs to know about a method before a run.
struct MethodTraits {
    // It records measuring passes that run() waits for before the main ones (begin() reads
    // their header); without, run() is one submission (begin() with a prediction).
    bool measures = true;
    // BroadPhaseSettings::resolution must be a power of two in [kMinResolution,
    // kMaxResolution]; otherwise any value in [1, kMaxResolution].
    bool power_of_two_resolution = true;
    // Its results are candidate pairs (BroadPhaseResult::has_pairs), not triangle records:
    // one direction only (the multi-axis union unites records).
    bool pairs = false;
};

// Which of its passes a recording asks the method for. Every recording but Measure ends
// with the header's readback, so collect() reads what the last submission left in it.
enum class Phase {
    Measure,  // after the front: passes that measure the scene (traits().measures)
    Main,     // the main passes
    Again,    // after collect() answered Again: what it asked to run (again, or next)
};

// collect()'s answer.
enum class Collected {
    Done,   // the outputs are in the result
    Again,  // record Phase::Again, run it and collect again: a buffer the GPU sized
            // overflowed and was grown, or the next chunk of work split into submissions
};

class BroadPhaseMethod {
public:
    virtual ~BroadPhaseMethod() = default;
    virtual MethodTraits traits() const noexcept { return {}; }
    // Per run, after the table's buffers are reserved and before the frame is uploaded:
    // per-run choices, the method's own resources, and its fields of `io_frame`.
    [[nodiscard]] virtual Result<void> prepare(const BroadPhaseSettings& settings, const RunShape& shape, gpu::Frame& io_frame) = 0;
    // Makes now every pipeline a run with `settings` may record, whatever its scene and the
    // runs before it: the forms and the stages it would make on first use
    // (CollisionWorld::preparePipelines). A method that makes them all in its factory
    // has nothing to do.
    [[nodiscard]] virtual Result<void> preparePipelines(const BroadPhaseSettings& settings) {
        (void)settings;
        return {};
    }
    // Before Phase::Main is recorded: `measured` is the header of run()'s measuring
    // submission and `measured_passes` its passes' GPU times, or null and empty in
    // submit(), where `predicted_layers` is the caller's prediction of the depth (what the
    // last run measured).
    [[nodiscard]] virtual Result<void> begin(const RunView& run, const gpu::Header* measured,
                                             std::span<const graph::PassTiming> measured_passes, std::uint32_t predicted_layers) = 0;
    // The rows it sizes itself (BufferTable::addOwned, which import() skips) into a graph
    // about to be recorded.
    virtual void import(graph::Graph& g) = 0;
    // Its passes of `phase` (a method without measuring passes records nothing for Measure).
    virtual void record(Phase phase, graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const = 0;
    // After a submission ended: the method's outputs and statistics into `io_result`, or
    // Again (at most kMaxMethodAgains times in a run).
    [[nodiscard]] virtual Result<Collected> collect(const RunView& run, const gpu::Header& header, BroadPhaseResult& io_result) = 0;
    // After record(): the milestone of the recording (graph::Executor::setMilestone), a
    // pass after which the host may start on part of the outputs while the GPU does the
    // rest; none by default. Its callback runs inside the broad phase's collect().
    virtual graph::Executor::Milestone milestone() { return {}; }
    // After collect() failed with InvalidMesh: the object (run index) the method's own
    // input checks blamed, if any (the broad phase adds it to its ObjectFaults).
    virtual std::optional<ObjectFault> fault() const { return std::nullopt; }
    // With BroadPhaseSettings::device_pairs: where the run started last writes its sorted
    // pairs on the GPU (valid from begin() on); nullopt when it writes none.
    virtual std::optional<DevicePairsView> devicePairs() const { return std::nullopt; }
};

// The most submissions of a run after the first (Again answers) before the broad phase
// gives up: an internal error, a guard against a method that never ends. A method bounds
// its own answers (each overflow grows a buffer to what the GPU counted, each chunk of
// the pair pass covers at least 4096 more candidates when automatic), and the run's
// deadline bounds them in time.
inline constexpr std::uint32_t kMaxMethodAgains = 1u << 20;

// Creates a method on `device`, adding its rows to `io_table` (after the core rows).
using MethodFactory = Result<std::unique_ptr<BroadPhaseMethod>> (*)(vk::Device& device, BufferTable& io_table,
                                                                   const CoreBuffers& core);

}  // namespace vkcollide::passes
