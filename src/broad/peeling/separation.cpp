#include "broad/peeling/separation.hpp"

#include "shaders/all.hpp"

namespace vkcollide::passes {

Result<std::unique_ptr<Separation>> Separation::create(vk::Device& device) {
    std::unique_ptr<Separation> s(new Separation());
    if (auto r = makeCompute(device, s->separate_, shaders::separate_comp, "separate"); !r) return r.error();
    return s;
}

void Separation::record(graph::Graph& g, const RunView& run, graph::ResourceId projection, graph::ResourceId bundles,
                        graph::ResourceId sparse, const DepthIds& depth) const {
    auto pass = addPass(g, "separate", graph::PassKind::Compute, Stage::Separation);
    pass.read(projection).read(bundles).write(sparse);
    if (depth.bounds.valid()) pass.read(depth.bounds).read(depth.bundle_depth).write(depth.sparse_depth);
    pass.record([this, run](graph::PassContext& pc) {
        for (std::uint32_t i = 0; i < run.meshes.size(); ++i) {
            bindAndPush(pc, separate_, run.frame_address, i);
            dispatchItems(pc, run.meshes[i].triangle_count);
        }
    });
}

}  // namespace vkcollide::passes
