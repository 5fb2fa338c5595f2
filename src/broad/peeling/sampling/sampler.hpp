// A sampling backend: how paper pass 1 turns triangles into per-ray depth-complexity counts
// and peeling keys. ObjectSampling (object_sampling.hpp) owns the passes every backend
// shares (reduce-max, peel-init, classify, finalize) and asks the active backend for the
// rest; both backends produce the same counts and keys, so everything after them is shared.
//
// To add a backend: implement this interface in its own file here, add a SamplingBackend
// value (vkcollide/types.hpp), create it in ObjectSampling::prepare and teach Auto
// (backend_choice.cpp) when to pick it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "broad/buffer_table.hpp"
#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "graph/graph.hpp"

namespace vkcollide::passes {

// Pass names every backend uses, which PeelingMethod also reads back from the pass times
// (its chunks of peeling steps are sized from them).
inline constexpr std::string_view kDepthComplexityPass = "depth-complexity";
inline constexpr std::string_view kPeelPassPrefix = "peel[", kClassifyPassPrefix = "classify[";
// "peel[step]", "classify[step]".
inline std::string stepPassName(std::string_view prefix, std::uint32_t step) {
    return std::string(prefix) + std::to_string(step) + "]";
}

// The broad phase's buffers that sampling reads and writes, in the graph being recorded.
struct SamplingBuffers {
    graph::ResourceId projection, header, counts, state, front, back;
    graph::ResourceId fragments;  // the 64-bit fragment counts per ray, which the depth-complexity pass writes
};

class Sampler {
public:
    virtual ~Sampler() = default;
    virtual SamplingBackend backend() const noexcept = 0;
    // Sizes the backend's own buffers for the run. Returns the address shaders find in
    // gpu::Frame::compute_sampling (0: none).
    [[nodiscard]] virtual Result<VkDeviceAddress> prepare(const BroadPhaseSettings& settings, const RunShape& shape) = 0;
    // The backend's own buffers into a graph about to be recorded (once per graph).
    virtual void import(graph::Graph& g) = 0;
    // The depth-complexity counts (pass "depth-complexity", after any setup pass it needs).
    virtual void recordDepthComplexity(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const = 0;
    // Before recording the peeling steps: the measured depth complexity, or 0 when unknown
    // (submit(): peeling depth predicted, the scene may be deeper).
    [[nodiscard]] virtual Result<void> preparePeeling(std::uint32_t depth_complexity) = 0;
    // Peeling steps the depth-complexity pass already did (0 or 1; peel-init starts after them).
    virtual std::uint32_t stepsDoneByCount() const noexcept = 0;
    // One peeling step (pass "peel[step]"), recorded before classify[step].
    virtual void recordPeelStep(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t step) const = 0;
    // The backend's own statistics.
    virtual void report(BroadPhaseResult& io_result) const = 0;
};

}  // namespace vkcollide::passes
