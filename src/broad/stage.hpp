// The stage a broad-phase pass belongs to, for its GPU time: every pass declares one
// (addPass) and its time is summed into the matching BroadPhaseResult field. A stage is a
// class that owns its pipelines and records its passes into a graph (docs/rooms.md lists
// them); run_view.hpp has the run they record, dispatch.hpp the dispatch helpers.
#pragma once

#include <string>

#include "broad/broad_phase_types.hpp"
#include "graph/executor.hpp"

namespace vkcollide::passes {

// The stage a pass belongs to; its GPU time is summed into the matching BroadPhaseResult
// field (addStageTime). A new stage adds a value here and a field there.
enum class Stage : graph::StageTag {
    None = 0,    // not timed into a stage (graph passes that declared nothing)
    Prepare,     // clear, GPU input checks, bounds and fit (timed with sampling, as the paper does)
    Sampling,    // depth complexity, peeling, classification (paper pass 1)
    Merging,     // the ray-bundle mipmap (pass 2)
    Separation,  // kept boxes per triangle (pass 3)
    Packing,     // compaction into the readback buffer (pass 4)
    Readback,    // copies the host reads
    // The cell stage (ReliableMethod, broad/cells/):
    Footprints,  // setup, big triangles, scan, fill: every triangle in the cells it may touch
    Pairing,     // the sweep of every cell: candidate pairs
    Filtering,   // canonical-cell dedupe, the double-precision filter, engine triangles' vertices
    Sorting,     // device pairs: the survivors sorted on the GPU (cells/device_pairs.hpp)
    Proximity,   // the proximity pass (src/proximity/)
};
const char* toString(Stage stage) noexcept;
// Adds one pass's GPU time to its stage's field of `io_result`.
void addStageTime(BroadPhaseResult& io_result, const graph::PassTiming& pass);

// Adds a pass that declares its stage.
graph::PassBuilder addPass(graph::Graph& g, std::string name, graph::PassKind kind, Stage stage);
}  // namespace vkcollide::passes
