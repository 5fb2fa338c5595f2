#include "passes/triangle_bounds.hpp"

#include "shaders/all.hpp"

namespace vkcollide::passes {

Result<std::unique_ptr<TriangleBounds>> TriangleBounds::create(vk::Device& device) {
    std::unique_ptr<TriangleBounds> t(new TriangleBounds());
    for (auto r : {makeCompute(device, t->tri_bounds_, shaders::tri_bounds_comp, "triangle-bounds"),
                   makeCompute(device, t->tri_edges_, shaders::tri_edges_comp, "triangle-edges")})
        if (!r) return r.error();
    return t;
}

void TriangleBounds::record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bounds,
                            graph::ResourceId vertex_depth) const {
    addPass(g, "triangle-bounds", graph::PassKind::Compute, Stage::Sampling)
        .read(projection)
        .write(bounds)
        .readWrite(vertex_depth)
        .record([this, run](graph::PassContext& pc) {
            // Push.step: the object's first vertex in vertex_depth.
            std::uint32_t vertex_base = 0;
            for (std::uint32_t i = 0; i < run.meshes.size(); ++i) {
                bindAndPush(pc, tri_bounds_, run.frame_address, i, vertex_base);
                pc.fns().vkCmdDispatch(pc.cmd, groups(run.meshes[i].triangle_count), 1, 1);
                vertex_base += run.meshes[i].vertex_count;
            }
            pc.shaderBarrier();  // every edge-on triangle's range is at its vertices
            vertex_base = 0;
            for (std::uint32_t i = 0; i < run.meshes.size(); ++i) {
                bindAndPush(pc, tri_edges_, run.frame_address, i, vertex_base);
                pc.fns().vkCmdDispatch(pc.cmd, groups(run.meshes[i].triangle_count), 1, 1);
                vertex_base += run.meshes[i].vertex_count;
            }
        });
}

}  // namespace vkcollide::passes
