// Paper pass 3, primitive separation: each triangle keeps the box of the collision-ray
// bundles under its corners intersected with its own screen box (empty: not a candidate),
// one invocation per triangle, written to the sparse per-triangle array. One pass ("separate").
// Depth-aware (docs/broadphase.md): (x, y, depth) boxes, the triangle's from the
// triangle-bounds pass, and its kept depth range beside `sparse` in `sparse_depth`.
#pragma once

#include <memory>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

class Separation {
public:
    static Result<std::unique_ptr<Separation>> create(vk::Device& device);
    // Depth-aware separation's buffers; invalid ids when off.
    struct DepthIds {
        graph::ResourceId bounds, bundle_depth, sparse_depth;
    };
    void record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bundles, graph::ResourceId sparse,
                const DepthIds& depth) const;

private:
    Separation() = default;
    vk::Pipeline separate_;
};

}  // namespace vkcollide::passes
