#include "broad/peeling/sampling/raster_sampler.hpp"

#include "shaders/all.hpp"

namespace vkcollide::passes {

using graph::PassContext;
using graph::PassKind;

Result<std::unique_ptr<RasterSampler>> RasterSampler::create(vk::Device& device) {
    std::unique_ptr<RasterSampler> rs(new RasterSampler());
    auto raster = [&](vk::Pipeline& out, std::span<const std::uint32_t> frag, const char* name, bool conservative) -> Result<void> {
        vk::Pipeline::RasterDesc rd;
        rd.vertex_spirv = shaders::sample_vert;
        rd.fragment_spirv = frag;
        rd.conservative = conservative;
        auto p = vk::Pipeline::createRaster(device, rd, {}, sizeof(gpu::Push), name);
        if (!p) return p.error();
        out = std::move(*p);
        return {};
    };
    for (auto r : {raster(rs->count_, shaders::count_frag, "count", false), raster(rs->peel_, shaders::peel_frag, "peel", false)})
        if (!r) return r.error();
    if (device.conservative_rasterization)
        if (auto r = raster(rs->count_conservative_, shaders::count_frag, "count-conservative", true); !r) return r.error();
    return rs;
}

// One object's triangles in a sampling pass, with the run's coverage. The count pass
// draws thin triangles enlarged (dilation) or through the overestimating pipeline (a
// second draw), so they flag every ray they touch; those rays are done before peeling,
// so the peeling passes draw only the other triangles, exactly as the count pass did.
void RasterSampler::drawObject(const PassContext& pc, const RunView& run, const vk::Pipeline& plain,
                               const vk::Pipeline& conservative, std::uint32_t object, std::uint32_t step, bool count_pass) const {
    const VkDeviceAddress frame = run.frame_address;
    const std::uint32_t vertices = run.meshes[object].triangle_count * 3;
    const Coverage coverage = run.settings.coverage;
    if (!count_pass && coverage != Coverage::Centre) {
        bindAndPush(pc, plain, frame, object, step, 0, gpu::kCoverageSkipThin);
        pc.draw(vertices);
        return;
    }
    switch (coverage) {
        case Coverage::Centre:
            bindAndPush(pc, plain, frame, object, step);
            pc.draw(vertices);
            break;
        case Coverage::Dilate:
            bindAndPush(pc, plain, frame, object, step, 0, gpu::kCoverageDilate);
            pc.draw(vertices);
            break;
        case Coverage::Conservative:
        case Coverage::Best:  // resolved by the API before a run; never here
            bindAndPush(pc, plain, frame, object, step, 0, gpu::kCoverageSkipThin);
            pc.draw(vertices);
            bindAndPush(pc, conservative, frame, object, step, 0, gpu::kCoverageOnlyThin);
            pc.draw(vertices);
            break;
    }
}

void RasterSampler::recordDepthComplexity(graph::Graph& g, const RunView& run, const SamplingBuffers& b) const {
    const std::uint32_t n = run.frame.resolution;
    addPass(g, std::string(kDepthComplexityPass), PassKind::Raster, Stage::Sampling)
        .renderArea(n, n)
        .read(b.projection)
        .readWrite(b.fragments)
        .record([this, run](PassContext& pc) {
            for (std::uint32_t i = 0; i < run.meshes.size(); ++i) drawObject(pc, run, count_, count_conservative_, i, 0, true);
        });
}

void RasterSampler::recordPeelStep(graph::Graph& g, const RunView& run, const SamplingBuffers& b, std::uint32_t step) const {
    const std::uint32_t n = run.frame.resolution;
    auto peel = addPass(g, stepPassName(kPeelPassPrefix, step), PassKind::Raster, Stage::Sampling);
    peel.renderArea(n, n).read(b.projection).read(b.state).readWrite(b.front);
    if (run.frame.dual) peel.readWrite(b.back);
    peel.record([this, run, step](PassContext& pc) {
        // No conservative draw when peeling: thin triangles' rays are done already.
        for (std::uint32_t i = 0; i < run.meshes.size(); ++i) drawObject(pc, run, peel_, peel_, i, step, false);
    });
}

}  // namespace vkcollide::passes
