#include "broad/peeling/merging.hpp"

#include "shaders/all.hpp"

namespace vkcollide::passes {

Result<std::unique_ptr<Merging>> Merging::create(vk::Device& device) {
    std::unique_ptr<Merging> m(new Merging());
    if (auto r = makeCompute(device, m->merge_, shaders::merge_comp, "merge"); !r) return r.error();
    return m;
}

void Merging::record(graph::Graph& g, const RunView& run, graph::ResourceId bundles, graph::ResourceId bundle_depth) const {
    const std::uint32_t n = run.frame.resolution, levels = run.frame.levels;
    auto pass = addPass(g, "merge", graph::PassKind::Compute, Stage::Merging);
    pass.readWrite(bundles);
    if (bundle_depth.valid()) pass.readWrite(bundle_depth);
    pass.record([this, frame = run.frame_address, n, levels](graph::PassContext& pc) {
        for (std::uint32_t l = 1; l < levels; ++l) {
            bindAndPush(pc, merge_, frame, 0, 0, l);
            dispatchItems(pc, VkDeviceSize(n >> l) * (n >> l));
            if (l + 1 < levels) pc.shaderBarrier();  // level l+1 reads level l
        }
    });
}

}  // namespace vkcollide::passes
