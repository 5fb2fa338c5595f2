// Paper pass 2, ray merging: the ray-bundle mipmap. Level 0 (written by finalize) holds each
// collision ray's pixel box (and with depth-aware separation its depth interval, in
// `bundle_depth`); each coarser level unites 2x2 texels of the one below, so separation can
// ask "which collision rays lie under this box" with a few texel reads.
// One pass ("merge"), one dispatch per level with a barrier between levels.
#pragma once

#include <memory>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

class Merging {
public:
    static Result<std::unique_ptr<Merging>> create(vk::Device& device);
    // `bundle_depth`: invalid unless depth-aware.
    void record(graph::Graph& g, const RunView& run, graph::ResourceId bundles, graph::ResourceId bundle_depth) const;

private:
    Merging() = default;
    vk::Pipeline merge_;
};

}  // namespace vkcollide::passes
