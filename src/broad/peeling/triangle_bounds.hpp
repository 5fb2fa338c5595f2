// Depth-aware separation's first pass: every triangle's sampling-space box, padded depth
// range and plane (gpu::TriangleBounds), once per run after the fit and before the peeling,
// so that classification (windows of the fragments it compares) and separation (the
// triangle's (x, y, depth) box) read them instead of transforming vertices again. Edge-on
// triangles (thin and steep: rays may never see them) also leave their depth range at
// every ray within kNearReachPx of them (`edge_depth`, cleared by the front stage). One
// pass ("triangle-bounds"), one dispatch per object. The buffer stays valid after the run:
// a later GPU stage can read the kept triangles' boxes beside `sparse` / `sparse_depth`.
#pragma once

#include <memory>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

class TriangleBounds {
public:
    static Result<std::unique_ptr<TriangleBounds>> create(vk::Device& device);
    void record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bounds,
                graph::ResourceId edge_depth) const;

private:
    TriangleBounds() = default;
    vk::Pipeline tri_bounds_;
};

}  // namespace vkcollide::passes
