#include "broad/peeling/sampling/compute_sampler.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "broad/peeling/sampling/backend_choice.hpp"
#include "common/broadphase.h"
#include "shaders/all.hpp"

namespace vkcollide::passes {
namespace {

using graph::PassContext;
using graph::PassKind;

constexpr std::uint32_t kMesaVendor = 0x10005;  // VK_VENDOR_ID_MESA: llvmpipe

}  // namespace

Result<std::unique_ptr<ComputeSampler>> ComputeSampler::create(vk::Device& device, BufferTable& table) {
    if (!computeSamplingSupported(device))
        return Error(ErrorCode::UnsupportedFeature,
                     "compute sampling needs subgroup ballot and arithmetic in compute shaders and at most 16 sub-pixel bits");
    std::unique_ptr<ComputeSampler> cs(new ComputeSampler(device, table));
    for (auto r : {makeCompute(device, cs->setup_, shaders::csample_setup_comp, "csample-setup"),
                   makeCompute(device, cs->bin_, shaders::csample_bin_comp, "csample-bin"),
                   makeCompute(device, cs->args_, shaders::csample_args_comp, "csample-args"),
                   makeCompute(device, cs->count_, shaders::csample_count_comp, "csample-count"),
                   makeCompute(device, cs->peel_, shaders::csample_peel_comp, "csample-peel"),
                   makeCompute(device, cs->gather_pipe_, shaders::csample_gather_comp, "csample-gather"),
                   makeCompute(device, cs->pick_, shaders::csample_pick_comp, "csample-pick")})
        if (!r) return r.error();
    using vk::MemoryKind;
    cs->frame_ = table.addOwned("csample-frame", MemoryKind::Upload);
    cs->triangles_ = table.addOwned("csample-triangles", MemoryKind::DeviceLocal);
    cs->lists_ = table.addOwned("csample-lists", MemoryKind::DeviceLocal);
    cs->items_ = table.addOwned("csample-items", MemoryKind::DeviceLocal);
    cs->counters_ = table.addOwned("csample-counters", MemoryKind::DeviceLocal);
    cs->args_buf_ = table.addOwned("csample-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    cs->fill_ = table.addOwned("csample-fill", MemoryKind::DeviceLocal);
    cs->fragments_ = table.addOwned("csample-fragments", MemoryKind::DeviceLocal);
    return cs;
}

// Rows sized by what this step knows (the table refuses what the device cannot hold).
Result<void> ComputeSampler::reserve(std::initializer_list<RowSize> sizes) const {
    return table_->reserve(*device_, std::span<const RowSize>(sizes.begin(), sizes.size()),
                           "compute sampling: resolution " + std::to_string(resolution_) + " with " + std::to_string(triangles_count_) +
                               " triangles");
}

Result<VkDeviceAddress> ComputeSampler::prepare(const BroadPhaseSettings& settings, const RunShape& shape) {
    using vk::MemoryKind;
    const std::uint32_t resolution = shape.resolution, triangles = shape.triangles;
    const ComputeSamplingTuning& tuning = settings.compute;
    const std::uint32_t bits = device_->properties.limits.subPixelPrecisionBits;
    const std::uint32_t tris = std::max(triangles, 1u);
    const VkDeviceSize items = VkDeviceSize(tris) + gpu::kCsExtraItems;
    resolution_ = resolution;
    triangles_count_ = triangles;
    if (auto ok = reserve({rowSize(frame_, sizeof(gpu::CsFrame), MemoryKind::Upload),
                           rowSize(triangles_, VkDeviceSize(tris) * sizeof(gpu::CsTriangle), MemoryKind::DeviceLocal),
                           rowSize(lists_, VkDeviceSize(tris) * 8, MemoryKind::DeviceLocal),
                           rowSize(items_, items * 8, MemoryKind::DeviceLocal),
                           rowSize(counters_, sizeof(gpu::CsCounters), MemoryKind::DeviceLocal),
                           rowSize(args_buf_, 16, MemoryKind::DeviceLocal)});
        !ok)
        return ok.error();
    list_budget_ = tuning.list_budget_bytes;
    fuse_ = tuning.fuse_first_step && list_budget_ == 0;
    fragment_lists_ = false;
    gather_ = false;
    // Layers the count pass stores: as many as the last run needed (at least the tuning's),
    // within the budget.
    const std::uint64_t layer_bytes = std::uint64_t(resolution) * resolution * 8;
    list_layers_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(std::max(next_list_layers_, tuning.list_layers),
                                                                      list_budget_ / layer_bytes));
    if (list_layers_ > 0) {
        // The lists are a shortcut: where the device cannot hold them beside the rest, this
        // run's steps draw instead (the same keys).
        if (auto ok = reserve({rowSize(fragments_, layer_bytes * list_layers_, MemoryKind::DeviceLocal)}); !ok) {
            if (ok.error().code() != ErrorCode::OutOfMemory) return ok.error();
            list_layers_ = 0;
            list_budget_ = 0;
        }
    }
    bool snapped = device_->properties.vendorID != kMesaVendor;
    if (tuning.depth_plane != ComputeSamplingTuning::DepthPlane::Device)
        snapped = tuning.depth_plane == ComputeSamplingTuning::DepthPlane::Snapped;
    gpu::CsFrame cf{};
    cf.triangles = triangles_->address();
    cf.small = lists_->address();
    cf.big = lists_->address() + VkDeviceSize(tris) * 4;
    cf.items = items_->address();
    cf.counters = counters_->address();
    cf.args = args_buf_->address();
    cf.item_capacity = static_cast<std::uint32_t>(items_->size() / 8);
    cf.subpixel_bits = bits;
    cf.small_box = tuning.small_box;
    cf.tie_rule = gpu::kCsTieTopLeft;  // lavapipe and (measured) the H200: see tests
    cf.fuse_first_step = fuse_ ? 1u : 0u;
    cf.depth_snapped = snapped ? 1u : 0u;
    cf.list_layers = list_layers_;
    cf.list_capacity = list_layers_ > 0 ? static_cast<std::uint32_t>(fragments_->size() / layer_bytes) : 0;
    cf.fragments = list_layers_ > 0 ? fragments_->address() : 0;
    std::memcpy(frame_->mapped(), &cf, sizeof(cf));
    frame_->flush();
    return frame_->address();
}

Result<void> ComputeSampler::preparePeeling(std::uint32_t measured_depth) {
    // Rays deeper than kMaxRayFragments are not peeled (reduce-max marks them colliding), so
    // the lists need at most that many layers; gather stores no more than the list holds.
    const std::uint32_t depth_complexity = std::min(measured_depth, gpu::kMaxRayFragments);
    const std::uint64_t layer_bytes = std::uint64_t(resolution_) * resolution_ * 8;
    const std::uint64_t bytes = layer_bytes * depth_complexity;
    fragment_lists_ = list_budget_ > 0 && depth_complexity > 0 && bytes <= list_budget_;
    gather_ = fragment_lists_ && depth_complexity > list_layers_;
    if (fragment_lists_) next_list_layers_ = std::max(next_list_layers_, depth_complexity);
    if (!gather_) return {};
    // The table frees a smaller buffer before it allocates the bigger one.
    const VkDeviceSize fill_bytes = VkDeviceSize(resolution_) * resolution_ * 4;
    if (auto ok = reserve({rowSize(fragments_, bytes, vk::MemoryKind::DeviceLocal), rowSize(fill_, fill_bytes, vk::MemoryKind::DeviceLocal)});
        !ok) {
        // Lists the device cannot hold beside the rest: the steps draw (as in prepare()).
        if (ok.error().code() != ErrorCode::OutOfMemory) return ok;
        fragment_lists_ = gather_ = false;
        return {};
    }
    auto* cf = static_cast<gpu::CsFrame*>(frame_->mapped());
    cf->fragments = fragments_->address();
    cf->list_capacity = static_cast<std::uint32_t>(std::min<std::uint64_t>(fragments_->size() / layer_bytes, gpu::kMaxRayFragments));
    cf->fill = fill_->address();
    frame_->flush();
    return {};
}

void ComputeSampler::import(graph::Graph& g) {
    ids_ = {importRow(g, triangles_), importRow(g, lists_),
            importRow(g, items_), importRow(g, counters_),
            importRow(g, args_buf_), {}, {}};
    if (fill_->valid()) ids_.fill = importRow(g, fill_);
    if (fragments_->valid()) ids_.fragments = importRow(g, fragments_);
}

void ComputeSampler::recordDepthComplexity(graph::Graph& g, const RunView& run, const SamplingBuffers& shared) const {
    const Ids& ids = ids_;
    const VkDeviceAddress frame = run.frame_address;
    const std::uint32_t total = run.frame.triangle_count;
    // Counters are cleared and then counted by atomics within the pass, so one pass holds
    // the four steps with a shader barrier between dependent ones.
    auto setup = addPass(g, "csample-setup", PassKind::Compute, Stage::Sampling);
    setup.read(shared.projection).readWrite(shared.header).write(ids.triangles).write(ids.lists).write(ids.items);
    setup.readWrite(ids.counters).write(ids.args);
    if (fuse_) setup.write(shared.front).write(shared.back);
    const std::uint32_t reset_groups = fuse_ ? groups(std::uint64_t(resolution_) * resolution_) : 1u;
    setup.record([this, frame, total, reset_groups](PassContext& pc) {
            bindAndPush(pc, args_, frame, 0, 0);
            dispatchGroups(pc, reset_groups);
            pc.shaderBarrier();
            bindAndPush(pc, setup_, frame);
            dispatchItems(pc, total);
            pc.shaderBarrier();
            bindAndPush(pc, bin_, frame);
            dispatchItems(pc, total);
            pc.shaderBarrier();
            bindAndPush(pc, args_, frame, 0, 1);
            pc.dispatch(1, 1, 1);
        });
    auto count = addPass(g, std::string(kDepthComplexityPass), PassKind::Compute, Stage::Sampling);
    count.indirect(ids.args).read(ids.triangles).read(ids.lists).read(ids.items).read(ids.counters).readWrite(shared.fragments);
    if (fuse_) count.readWrite(shared.front).readWrite(shared.back);
    if (list_layers_ > 0) count.write(ids.fragments);
    count.record([this, frame](PassContext& pc) {
            bindAndPush(pc, count_, frame);
            pc.dispatchIndirect(args_buf_->handle(), 0);
        });
}

void ComputeSampler::recordPeelStep(graph::Graph& g, const RunView& run, const SamplingBuffers& shared, std::uint32_t step) const {
    const Ids& ids = ids_;
    const VkDeviceAddress frame = run.frame_address;
    const bool dual = run.frame.dual != 0;
    if (fragment_lists_) {
        const std::uint32_t pixel_groups = groups(std::uint64_t(resolution_) * resolution_);
        if (step == 0 && gather_) {
            addPass(g, "csample-gather", PassKind::Compute, Stage::Sampling)
                .indirect(ids.args)
                .read(ids.triangles)
                .read(ids.lists)
                .read(ids.items)
                .read(ids.counters)
                .readWrite(ids.fill)
                .write(ids.fragments)
                .record([this, frame, pixel_groups](PassContext& pc) {
                    bindAndPush(pc, args_, frame, 0, 2);  // fill counts to 0
                    dispatchGroups(pc, pixel_groups);
                    pc.shaderBarrier();
                    bindAndPush(pc, gather_pipe_, frame);
                    pc.dispatchIndirect(args_buf_->handle(), 0);
                });
        }
        auto pick = addPass(g, stepPassName(kPeelPassPrefix, step), PassKind::Compute, Stage::Sampling);
        pick.read(ids.fragments).read(shared.counts).read(shared.state).readWrite(shared.front);
        if (dual) pick.readWrite(shared.back);
        pick.record([this, frame, step, pixel_groups](PassContext& pc) {
            bindAndPush(pc, pick_, frame, 0, step);
            dispatchGroups(pc, pixel_groups);
        });
        return;
    }
    if (step == 0 && fuse_) return;
    auto peel = addPass(g, stepPassName(kPeelPassPrefix, step), PassKind::Compute, Stage::Sampling);
    peel.indirect(ids.args).read(ids.triangles).read(ids.lists).read(ids.items).read(ids.counters);
    peel.read(shared.state).readWrite(shared.front);
    if (dual) peel.readWrite(shared.back);
    peel.record([this, frame, step](PassContext& pc) {
        bindAndPush(pc, peel_, frame, 0, step);
        pc.dispatchIndirect(args_buf_->handle(), 0);
    });
}

}  // namespace vkcollide::passes
