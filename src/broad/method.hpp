// The seam between the broad phase and a method. Every run records
//
//     front (clear, GPU input checks, bounds, fit)      common_stages.hpp
//     method: measuring passes                          BroadPhaseMethod::recordMeasure
//     method: main passes                               BroadPhaseMethod::recordMain
//     readback of the header                            common_stages.hpp
//
// run() submits the first two, waits, lets the method read the header (afterMeasure), then
// submits the main passes; submit() records all of it in one submission after predict().
// BroadPhase::record is the one recording path for both.
//
// PeelingMethod (the paper: sampling, merging, separation, packing) returns triangle
// records; ReliableMethod (broad/cells/: the cell pair stage) measures nothing, runs in one
// submission and returns candidate pairs (BroadPhaseResult::has_pairs). To add one: a class implementing this interface in its own folder under
// src/broad/ (with a sources.cmake there), its buffers added as rows of the BufferTable
// in its factory, its own gpu::Frame extension behind gpu::Frame::method if its shaders
// need one; BroadPhase::create(device, yourFactory) runs it (docs/rooms.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "broad/buffer_table.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

// The rows every method shares, added by the broad phase before the method's own.
struct CoreBuffers {
    BufferId frame, objects, projection, header, header_readback;
};

// What the broad phase needs to know about a method before a run.
struct MethodTraits {
    // It records measuring passes that run() waits for before the main ones (afterMeasure);
    // without, run() is one submission (predict(), then collect()).
    bool measures = true;
    // BroadPhaseSettings::resolution must be a power of two in [kMinResolution,
    // kMaxResolution]; otherwise any value in [1, kMaxResolution].
    bool power_of_two_resolution = true;
    // Its results are candidate pairs (BroadPhaseResult::has_pairs), not triangle records:
    // one direction only (the multi-axis union unites records).
    bool pairs = false;
};

class BroadPhaseMethod {
public:
    virtual ~BroadPhaseMethod() = default;
    virtual MethodTraits traits() const noexcept { return {}; }
    // Per run, after the table's buffers are reserved and before the frame is uploaded:
    // per-run choices, the method's own resources, and its fields of `io_frame`.
    [[nodiscard]] virtual Result<void> prepare(const BroadPhaseSettings& settings, const RunShape& shape, gpu::Frame& io_frame) = 0;
    // Its own resources (outside the table) into a graph about to be recorded.
    virtual void import(graph::Graph& g) = 0;
    // Passes that measure the scene, after the front stage.
    virtual void recordMeasure(graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const = 0;
    // run(), between the submissions: the header the measuring submission wrote.
    [[nodiscard]] virtual Result<void> afterMeasure(const RunView& run, const gpu::Header& header) = 0;
    // submit(), instead of afterMeasure: nothing is measured yet; `layers` is the caller's
    // prediction of the depth (what the last run measured).
    [[nodiscard]] virtual Result<void> predict(const RunView& run, std::uint32_t layers) = 0;
    // The method's main passes.
    virtual void recordMain(graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const = 0;
    // After the last submission: the method's outputs and statistics into `io_result`.
    [[nodiscard]] virtual Result<void> collect(const RunView& run, const gpu::Header& header, BroadPhaseResult& io_result) = 0;
    // After collect() failed with InvalidMesh: the object (run index) the method's own
    // input checks blamed, if any (the broad phase adds it to its ObjectFaults).
    virtual std::optional<ObjectFault> fault() const { return std::nullopt; }
    // Submissions of its own (outside the broad phase's executor) whose GPU work goes on
    // after a Timeout: busy() polls them, settle() waits up to timeout_ns for them.
    virtual bool busy() const { return false; }
    [[nodiscard]] virtual Result<void> settle(std::uint64_t /*timeout_ns*/) { return {}; }
    // Bytes of GPU memory the method holds outside the table.
    virtual std::uint64_t memoryBytes() const noexcept { return 0; }
    // With BroadPhaseSettings::device_pairs: where the run started last writes its sorted
    // pairs on the GPU (valid from predict() on); nullopt when it writes none.
    virtual std::optional<DevicePairsView> devicePairs() const { return std::nullopt; }
};

// Creates a method on `device`, adding its rows to `io_table` (after the core rows).
using MethodFactory = Result<std::unique_ptr<BroadPhaseMethod>> (*)(vk::Device& device, BufferTable& io_table,
                                                                   const CoreBuffers& core);

}  // namespace vkcollide::passes
