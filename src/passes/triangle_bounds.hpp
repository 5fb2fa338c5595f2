// Depth-aware separation's first pass: every triangle's sampling-space box and padded depth
// range (gpu::TriangleBounds), once per run after the fit and before the peeling, so that
// classification (depth ranges of the fragments it compares) and separation (the
// triangle's (x, y, depth) box) read them instead of transforming vertices again. One
// pass ("triangle-bounds"), one dispatch per object. The buffer stays valid after the run:
// a later GPU stage can read the kept triangles' boxes beside `sparse` / `sparse_depth`.
#pragma once

#include <memory>

#include "passes/stage.hpp"

namespace vkcollide::passes {

class TriangleBounds {
public:
    static Result<std::unique_ptr<TriangleBounds>> create(vk::Device& device);
    void record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bounds) const;

private:
    TriangleBounds() = default;
    vk::Pipeline tri_bounds_;
};

}  // namespace vkcollide::passes
