#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

const char* toString(Stage stage) noexcept {
    switch (stage) {
        case Stage::None: return "none";
        case Stage::Prepare: return "prepare";
        case Stage::Sampling: return "sampling";
        case Stage::Merging: return "merging";
        case Stage::Separation: return "separation";
        case Stage::Packing: return "packing";
        case Stage::Readback: return "readback";
        case Stage::Footprints: return "footprints";
        case Stage::Pairing: return "pairing";
        case Stage::Filtering: return "filtering";
        case Stage::Sorting: return "sorting";
        case Stage::Proximity: return "proximity";
    }
    return "?";
}

void addStageTime(BroadPhaseResult& r, const graph::PassTiming& pass) {
    switch (static_cast<Stage>(pass.stage)) {
        case Stage::Prepare:
        case Stage::Sampling: r.sampling_ms += pass.gpu_ms; break;
        case Stage::Merging: r.merging_ms += pass.gpu_ms; break;
        case Stage::Separation: r.separation_ms += pass.gpu_ms; break;
        case Stage::Packing: r.packing_ms += pass.gpu_ms; break;
        case Stage::Footprints: r.footprints_ms += pass.gpu_ms; break;
        case Stage::Pairing: r.pairing_ms += pass.gpu_ms; break;
        case Stage::Filtering: r.filtering_ms += pass.gpu_ms; break;
        case Stage::Sorting: r.sorting_ms += pass.gpu_ms; break;
        case Stage::Proximity: r.proximity_ms += pass.gpu_ms; break;
        case Stage::None:
        case Stage::Readback: break;
    }
}

graph::PassBuilder addPass(graph::Graph& g, std::string name, graph::PassKind kind, Stage stage) {
    return g.addPass(std::move(name), kind).stage(static_cast<graph::StageTag>(stage));
}

}  // namespace vkcollide::passes
