#include "broad/peeling/triangle_bounds.hpp"

#include "shaders/all.hpp"

namespace vkcollide::passes {

Result<std::unique_ptr<TriangleBounds>> TriangleBounds::create(vk::Device& device) {
    std::unique_ptr<TriangleBounds> t(new TriangleBounds());
    if (auto r = makeCompute(device, t->tri_bounds_, shaders::tri_bounds_comp, "triangle-bounds"); !r) return r.error();
    return t;
}

void TriangleBounds::record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bounds,
                            graph::ResourceId edge_depth) const {
    addPass(g, "triangle-bounds", graph::PassKind::Compute, Stage::Sampling)
        .read(projection)
        .write(bounds)
        .readWrite(edge_depth)
        .record([this, run](graph::PassContext& pc) {
            for (std::uint32_t i = 0; i < run.meshes.size(); ++i) {
                bindAndPush(pc, tri_bounds_, run.frame_address, i);
                dispatchItems(pc, run.meshes[i].triangle_count);
            }
        });
}

}  // namespace vkcollide::passes
