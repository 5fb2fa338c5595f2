#include "broad/cells/cell_stage.hpp"

#include <algorithm>
#include <bit>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#include "shaders/all.hpp"

namespace vkcollide::passes {
namespace {

static_assert(sizeof(gpu::CellsTriangle) == 96 && sizeof(gpu::CellsGeometry) == 64);
static_assert(sizeof(gpu::CellsEntry) == 16 && sizeof(gpu::CellsCandidate) == 12);
// A workgroup of the shallow sweep takes one tile: the cells that begin in a chunk of entries.
static_assert(gpu::kCellsEntryChunk == gpu::kCellsGroupSize);
static_assert(sizeof(gpu::CellsHeader) == 136 && sizeof(gpu::CellsParams) == 264);
static_assert(offsetof(gpu::CellsHeader, candidates) == 56 && offsetof(gpu::CellsHeader, box_cells) == 64 &&
              offsetof(gpu::CellsHeader, comparisons) == 72 && offsetof(gpu::CellsHeader, exact_tests) == 80 &&
              offsetof(gpu::CellsHeader, exact_neighbours) == 84 &&
              offsetof(gpu::CellsHeader, repeats) == 96 &&
              offsetof(gpu::CellsHeader, sweep_entries_begin) == 104 &&
              offsetof(gpu::CellsHeader, huge_cells) == 124 && offsetof(gpu::CellsHeader, exact_queued) == 128);  // kHeaderCandidates, ... in cells_common.glsl.inc
static_assert(sizeof(gpu::CellsGpuTriangle) == sizeof(GpuTriangle) && offsetof(gpu::CellsGpuTriangle, v) == offsetof(GpuTriangle, v));
static_assert(sizeof(CandidatePair) == 8);
static_assert(sizeof(gpu::Projection) == 64 && sizeof(gpu::ObjectGpu) == 88);

// Element counts beyond which a buffer index would not fit the shaders' 32-bit signed
// access chains.
constexpr std::uint64_t kMaxElements = 0x7FFFFFFFull;

// 1.25x what a run needed, within the budget (which holds what was needed).
std::uint32_t grown(std::uint64_t needed, std::uint32_t budget) {
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(needed, std::min<std::uint64_t>(budget, needed + needed / 4 + 1024)));
}

bool moderate(float x) { return std::isfinite(x) && std::fabs(x) < 4.611686018427388e18f; }

// A compute program of the stage (no bindings: every buffer through device addresses).
Result<void> makePipeline(vk::Device& device, vk::Pipeline& out, std::span<const std::uint32_t> code, const char* name) {
    auto p = vk::Pipeline::createCompute(device, code, {}, sizeof(gpu::Push), name);
    if (!p) return p.error();
    out = std::move(*p);
    return {};
}

// The stage's programs, each named once: programs() lists them for create()'s limit check,
// the slots below pick a run's forms for ensurePipelines() and the recording.
using Program = CellStage::Program;
constexpr Program kSetup{shaders::cells_setup_comp, "cells-setup"}, kSetupNoFp64{shaders::cells_setup_nofp64_comp, "cells-setup-nofp64"},
    kBig{shaders::cells_big_comp, "cells-big"}, kScan{shaders::cells_scan_comp, "cells-scan"},
    kFill{shaders::cells_fill_comp, "cells-fill"}, kFillPerFootprint{shaders::cells_fill_per_footprint_comp, "cells-fill-per-footprint"},
    kSweep{shaders::cells_sweep_comp, "cells-sweep"}, kSweepPlain{shaders::cells_sweep_plain_comp, "cells-sweep-plain"},
    kDeepSort{shaders::cells_deep_sort_comp, "cells-deep-sort"}, kDeep{shaders::cells_deep_comp, "cells-deep"},
    kDeepGuarded{shaders::cells_deep_guarded_comp, "cells-deep-guarded"}, kArgs{shaders::cells_args_comp, "cells-args"},
    kPairsNoFp64{shaders::cells_pairs_nofp64_comp, "cells-pairs-nofp64"},
    kPairsInline{shaders::cells_pairs_inline_comp, "cells-pairs-inline"}, kPairsFilter{shaders::cells_pairs_comp, "cells-pairs"},
    kExact{shaders::cells_exact_comp, "cells-exact"};

}  // namespace

Result<std::unique_ptr<CellStage>> CellStage::create(vk::Device& device, BufferTable* table) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &subgroup;
    device.instance_fns.vkGetPhysicalDeviceProperties2(device.physical, &props);
    const VkSubgroupFeatureFlags needed =
        VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) || (subgroup.supportedOperations & needed) != needed)
        return Error(ErrorCode::UnsupportedFeature,
                     "the cell stage needs subgroup basic, ballot and arithmetic operations in compute shaders, which " +
                         device.info.name + " lacks");
    std::unique_ptr<CellStage> cp(new CellStage(device));
    if (!table) {
        cp->own_table_ = std::make_unique<BufferTable>();
        table = cp->own_table_.get();
    }
    cp->table_ = table;
    cp->addRows();
    // No pipeline yet: prepare() makes the ones a run needs (CellStage::ensurePipelines), so
    // that a world that never runs the reliable method, or never a variant, compiles none of
    // it (the pair pass alone took a third of a world's compiling on lavapipe). A device
    // below a program's limits is refused here, by name, as before anything runs.
    for (const Program& program : programs(device.shader_float64))
        if (auto ok = vk::Pipeline::checkComputeLimits(device, program.code, program.name); !ok) return ok.error();
    return cp;
}

// Every program the stage may run on a device with or without float64.
std::vector<CellStage::Program> CellStage::programs(bool float64) {
    std::vector<Program> all = {kBig, kScan, kFill, kFillPerFootprint, kSweep, kSweepPlain, kDeepSort, kDeep, kDeepGuarded, kArgs};
    if (float64) all.insert(all.end(), {kSetup, kPairsInline, kPairsFilter, kExact});
    else all.insert(all.end(), {kSetupNoFp64, kPairsNoFp64});
    return all;
}

// A run's forms: the fill per cell or per footprint, the shallow sweep with or without its
// repeat checks, the deep sweep with or without the loop guard, and the pair pass without
// float64, with the exact decision inside, or filtering (and queueing for the exact pass).
CellStage::Slot CellStage::fillSlot() {
    return fill_per_cell_ ? Slot{&pipes_.fill, &kFill} : Slot{&pipes_.fill_per_footprint, &kFillPerFootprint};
}
CellStage::Slot CellStage::shallowSweepSlot() {
    return plain_sweep_ ? Slot{&pipes_.sweep_plain, &kSweepPlain} : Slot{&pipes_.sweep, &kSweep};
}
CellStage::Slot CellStage::deepSweepSlot() {
    return loopGuard() != ~0u ? Slot{&pipes_.deep_guarded, &kDeepGuarded} : Slot{&pipes_.deep, &kDeep};
}
CellStage::Slot CellStage::pairSlot() {
    if (!filterSupported()) return {&pipes_.pairs, &kPairsNoFp64};
    if (use_exact_ && !exactQueued()) return {&pipes_.pairs_inline, &kPairsInline};
    return {&pipes_.pairs_filter, &kPairsFilter};
}

// The programs this run records, each made once (shared with the device's other worlds:
// vk::Pipeline::share).
Result<void> CellStage::ensurePipelines() {
    auto& P = pipes_;
    const Slot needs[] = {
        {&P.setup, filterSupported() ? &kSetup : &kSetupNoFp64},
        {&P.big, &kBig},
        {&P.scan, &kScan},
        fillSlot(),
        shallowSweepSlot(),
        {&P.deep_sort, &kDeepSort},
        deepSweepSlot(),
        {&P.args, &kArgs},
        pairSlot(),
        {exactQueued() ? &P.exact : nullptr, &kExact},
    };
    for (const Slot& n : needs)
        if (n.pipeline && n.pipeline->handle() == VK_NULL_HANDLE)
            if (auto ok = makePipeline(*device_, *n.pipeline, n.program->code, n.program->name); !ok) return ok.error();
    return {};
}

void CellStage::chooseForms(const CellStageSettings& settings) {
    use_exact_ = settings.exact && filterSupported();
    using Checks = CellStageSettings::RepeatChecks;
    Checks checks = settings.repeat_checks;
    if (checks == Checks::Auto)
        checks = device_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? Checks::FromShallow : Checks::DeepChunksOnly;
    plain_sweep_ = checks == Checks::DeepChunksOnly;
    using FillSlots = CellStageSettings::FillSlots;
    fill_per_cell_ = settings.fill_slots == FillSlots::Auto ? device_->properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU
                                                            : settings.fill_slots == FillSlots::PerCell;
    loop_guard_ = settings.loop_guard;
}

// The exact decision's two forms follow the last run's candidates (ExactPass::Auto), so
// both are made unless the settings fix one; the rest follows the device and the settings.
Result<void> CellStage::makeEveryPipeline(const CellStageSettings& settings) {
    chooseForms(settings);
    const bool kept = exact_queued_;
    Result<void> ok{};
    for (const bool queued : {false, true}) {
        if (settings.exact_pass != ExactPass::Auto && queued != (settings.exact_pass == ExactPass::Queued)) continue;
        exact_queued_ = queued;
        if (ok = ensurePipelines(); !ok) break;
    }
    exact_queued_ = kept;
    return ok;
}

Result<void> CellStage::prepare(const CellStageInput& in, const CellStageSettings& settings) {
    if (in.objects.empty()) return Error(ErrorCode::InvalidArgument, "cell stage: no objects");
    if (in.resolution < 1 || in.resolution > gpu::kCellsMaxResolution)
        return Error(ErrorCode::InvalidArgument, "cell stage: resolution " + std::to_string(in.resolution) + " is not in [1, " +
                                                     std::to_string(gpu::kCellsMaxResolution) + "]");
    if (in.projection.has_value() == (in.projection_address != 0))
        return Error(ErrorCode::InvalidArgument, "cell stage: give either a host projection or a projection address, not both or neither");
    if (in.projection) {  // rows of 2^62 or more are scaled on the GPU (cells_setup.comp)
        for (const gpu::vec4& row : in.projection->row)
            if (!std::isfinite(row.x) || !std::isfinite(row.y) || !std::isfinite(row.z) || !std::isfinite(row.w))
                return Error(ErrorCode::InvalidArgument, "cell stage: projection entries must be finite");
    }
    if (!in.self_collision.empty() && in.self_collision.size() != in.objects.size())
        return Error(ErrorCode::InvalidArgument, "cell stage: self_collision has " + std::to_string(in.self_collision.size()) +
                                                     " entries for " + std::to_string(in.objects.size()) + " objects");
    if (!in.download.empty() && in.download.size() != in.objects.size())
        return Error(ErrorCode::InvalidArgument, "cell stage: download has " + std::to_string(in.download.size()) + " entries for " +
                                                     std::to_string(in.objects.size()) + " objects");
    const std::uint64_t mask_words = (std::uint64_t(in.objects.size()) * in.objects.size() + 31) / 32;
    if (!in.pair_mask.empty() && in.pair_mask.size() != mask_words)
        return Error(ErrorCode::InvalidArgument, "cell stage: pair_mask has " + std::to_string(in.pair_mask.size()) + " words for " +
                                                     std::to_string(in.objects.size()) + " objects (" + std::to_string(mask_words) + " needed)");
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
        const gpu::ObjectGpu& o = in.objects[i];
        const std::string who = "cell stage: object " + std::to_string(i) + " ";
        if (o.triangle_base != total)
            return Error(ErrorCode::InvalidArgument, who + "has triangle_base " + std::to_string(o.triangle_base) +
                                                         ", not the sum of the counts before it (" + std::to_string(total) + ")");
        if (o.triangle_count > 0) {
            if (o.vertex_count == 0) return Error(ErrorCode::InvalidMesh, who + "has triangles but no vertices");
            if (!o.vertices || !o.indices) return Error(ErrorCode::InvalidArgument, who + "has a null vertex or index address");
            if (o.vertex_stride < 12 || o.vertex_stride % 4 != 0 || o.vertices % 4 != 0 || o.indices % 4 != 0)
                return Error(ErrorCode::InvalidArgument, who + "needs 4-byte aligned positions and indices and a stride of at least 12");
        }
        for (const gpu::vec4& row : o.model)
            if (!moderate(row.x) || !moderate(row.y) || !moderate(row.z) || !moderate(row.w))
                return Error(ErrorCode::InvalidArgument, who + "has a transform entry that is not finite or not below 2^62");
        total += o.triangle_count;
    }
    if (total >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidArgument, "cell stage: more than 2^30 triangles");
    if (!(settings.proximity_pad >= 0) || !moderate(settings.proximity_pad))
        return Error(ErrorCode::InvalidArgument, "cell stage: proximity_pad must be finite, at least 0 and below 2^62");

    objects_.assign(in.objects.begin(), in.objects.end());
    triangles_ = static_cast<std::uint32_t>(total);
    resolution_ = in.resolution;
    recent_cells_[recent_next_] = roundedCells(std::uint64_t(resolution_) * resolution_);
    recent_next_ = (recent_next_ + 1) % kRecentRuns;
    projection_address_ = in.projection_address;
    use_filter_ = settings.filter && filterSupported();
    chooseForms(settings);
    if (settings.exact_pass != ExactPass::Auto) exact_queued_ = settings.exact_pass == ExactPass::Queued;
    else if (last_canonical_ != ~std::uint64_t{0} && last_canonical_ >= kExactQueuedFrom) exact_queued_ = true;
    else if (last_canonical_ < kExactInlineBelow) exact_queued_ = false;
    skip_unhelpful_filter_ = settings.skip_unhelpful_filter;
    if (filterSkippable() && filter_skips_left_ > 0) {
        --filter_skips_left_;
        use_filter_ = false;
    }
    proximity_pad_ = settings.proximity_pad;
    survivors_on_device_ = settings.survivors_on_device;
    has_self_ = std::any_of(in.self_collision.begin(), in.self_collision.end(), [](std::uint8_t s) { return s != 0; });
    has_pair_mask_ = !in.pair_mask.empty() || static_cast<bool>(in.may_collide);
    download_triangles_ = 0;
    for (std::size_t i = 0; i < in.download.size(); ++i)
        if (in.download[i]) download_triangles_ += in.objects[i].triangle_count;
    has_download_ = download_triangles_ > 0;
    runs_ = 0;
    bad_input_.reset();
    pair_chunk_ = settings.pair_chunk ? settings.pair_chunk : automaticPairChunk();
    sweep_dedupe_ = plain_sweep_ ? gpu::kCellsDeepShared + 1 : gpu::kCellsSweepDedupe;
    if (auto ok = ensurePipelines(); !ok) return ok.error();
    auto_sweep_work_ = settings.sweep_work == 0;
    sweep_work_ = auto_sweep_work_ ? automaticSweepWork() : settings.sweep_work;
    next_chunk_ = 0;
    asked_budget_ = settings.max_candidate_pairs;
    budget_ = static_cast<std::uint32_t>(std::min(settings.max_candidate_pairs, kMaxElements));
    const std::uint32_t device_limit = device_->properties.limits.maxComputeWorkGroupCount[0];
    max_groups_x_ = settings.max_workgroups_x ? std::min(settings.max_workgroups_x, device_limit) : device_limit;

    // Capacities: the caller's, else what earlier runs needed, else an estimate; a new
    // buffer never holds more elements than the budget (what earlier runs with a larger
    // budget allocated is kept: it costs nothing more).
    const std::uint64_t tris = std::max<std::uint64_t>(triangles_, 1);
    const std::uint64_t most = std::max<std::uint32_t>(budget_, 1);
    auto pick = [most](std::uint32_t asked, std::uint32_t current, std::uint64_t estimate) {
        if (asked) return static_cast<std::uint32_t>(std::min<std::uint64_t>(asked, most));
        if (current) return current;
        return static_cast<std::uint32_t>(std::min(most, estimate));
    };
    capacity_.entries = pick(settings.initial.entries, capacity_.entries, std::max<std::uint64_t>(8 * tris, 4096));
    capacity_.items = pick(settings.initial.items, capacity_.items, std::max<std::uint64_t>(tris / 32, 1024));
    capacity_.candidates = pick(settings.initial.candidates, capacity_.candidates, std::max<std::uint64_t>(2 * tris, 4096));
    capacity_.survivors = pick(settings.initial.survivors, capacity_.survivors, std::max<std::uint64_t>(tris / 2, 4096));
    if (has_download_)  // never more than the download objects' triangles
        capacity_.gpu_triangles = pick(settings.initial.gpu_triangles, capacity_.gpu_triangles,
                                       std::min<std::uint64_t>(download_triangles_, std::max<std::uint64_t>(capacity_.survivors, 4096)));
    if (auto ok = ensureBuffers(); !ok) return ok.error();

    // Per-run uploads: objects, object flags, the pair mask and the projection.
    std::memcpy(buf_.objects->mapped(), objects_.data(), objects_.size() * sizeof(gpu::ObjectGpu));
    buf_.objects->flush();
    if (has_self_ || has_download_) {
        auto* flags = static_cast<std::uint32_t*>(buf_.object_flags->mapped());
        for (std::size_t i = 0; i < objects_.size(); ++i)
            flags[i] = (has_self_ && in.self_collision[i] ? gpu::kCellsObjectSelf : 0u) |
                       (has_download_ && in.download[i] ? gpu::kCellsObjectDownload : 0u);
        buf_.object_flags->flush();
    }
    if (!in.pair_mask.empty()) {
        std::memcpy(buf_.pair_mask->mapped(), in.pair_mask.data(), in.pair_mask.size_bytes());
        buf_.pair_mask->flush();
    } else if (has_pair_mask_) {
        const std::uint64_t n = objects_.size();
        auto* bits = static_cast<std::uint32_t*>(buf_.pair_mask->mapped());
        std::memset(bits, 0, (n * n + 31) / 32 * 4);
        for (std::uint32_t a = 0; a < n; ++a)
            for (std::uint32_t b = a + 1; b < n; ++b)
                if (in.may_collide(a, b)) bits[(a * n + b) >> 5] |= 1u << ((a * n + b) & 31);
        buf_.pair_mask->flush();
    }
    if (in.projection) {
        std::memcpy(buf_.projection->mapped(), &*in.projection, sizeof(gpu::Projection));
        buf_.projection->flush();
    }
    writeParams();
    return {};
}

void CellStage::writeParams() {
    gpu::CellsParams p{};
    p.objects = buf_.objects->address();
    p.object_flags = has_self_ || has_download_ ? buf_.object_flags->address() : 0;
    p.pair_mask = has_pair_mask_ ? buf_.pair_mask->address() : 0;
    p.projection = projection_address_ ? projection_address_ : buf_.projection->address();
    p.header = buf_.header->address();
    p.triangles = buf_.triangles->address();
    p.geometry = buf_.geometry->address();
    p.counts = buf_.counts->address();
    p.offsets = buf_.offsets->address();
    p.block_sums = buf_.block_sums->address();
    p.entries = buf_.entries->address();
    p.chunk_cells = buf_.chunk_cells->address();
    p.big_items = buf_.big_items->address();
    p.deep_items = buf_.deep_items->address();
    p.candidates = buf_.candidates->address();
    p.survivors = buf_.survivors->address();
    p.args = buf_.args->address();
    p.gpu_triangles = has_download_ ? buf_.gpu_triangles->address() : 0;
    p.marks = has_download_ ? buf_.marks->address() : 0;
    p.sorted = buf_.sorted->address();
    p.exact_queue = exactQueued() ? buf_.exact_queue->address() : 0;
    p.exact_queue_capacity = exactQueued() ? static_cast<std::uint32_t>(buf_.exact_queue->size() / 8) : 0;
    p.sorted_capacity = static_cast<std::uint32_t>(buf_.sorted->size() / 8);
    p.loop_guard = loopGuard();
    p.gpu_triangle_capacity = has_download_ ? capacity_.gpu_triangles : 0;
    p.resolution = resolution_;
    p.cell_count = resolution_ * resolution_;
    p.object_count = static_cast<std::uint32_t>(objects_.size());
    p.triangle_count = triangles_;
    p.entry_capacity = capacity_.entries;
    p.item_capacity = capacity_.items;
    p.deep_capacity = static_cast<std::uint32_t>(buf_.deep_items->size() / 8);
    p.candidate_capacity = capacity_.candidates;
    p.survivor_capacity = capacity_.survivors;
    p.block_count = (p.cell_count + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    p.max_groups_x = max_groups_x_;
    p.use_filter = use_filter_ ? 1u : 0u;
    p.exact = use_exact_ ? 1u : 0u;
    p.budget = budget_;
    p.keep_neighbours = proximity_pad_ > 0 ? 1u : 0u;
    p.proximity_pad = proximity_pad_;
    p.pair_chunk = pair_chunk_;
    p.sweep_dedupe = sweep_dedupe_;
    p.sweep_work = sweep_work_;
    std::memcpy(buf_.params->mapped(), &p, sizeof p);
    buf_.params->flush();
}

Result<void> CellStage::checkFailure(const gpu::CellsHeader& h) {
    const std::uint32_t errors = h.flags & ~(gpu::kCellsOverflowMask | gpu::kCellsOverBudget);
    if (!errors) return {};
    if (errors & gpu::kCellsInconsistent)
        return Error(ErrorCode::VulkanError, "cell stage: the fill found more footprints than the count (internal error)");
    if (errors & gpu::kCellsLoopLimit)
        return Error(ErrorCode::LimitExceeded,
                     "cell stage: a deep cell needs more than " + std::to_string(loopGuard()) +
                         " loop iterations in one shader invocation at resolution " + std::to_string(resolution_) + " (" +
                         std::to_string(triangles_) + " triangles) (up to " + std::to_string(h.max_cell) +
                         " footprints in one cell), and " + device_->info.name +
                         " ends longer loops silently (" + std::to_string(device_->info.loop_iteration_limit) +
                         " iterations in all): lower the resolution, or detect on a GPU");
    std::string where = "triangle " + std::to_string(h.bad_triangle);
    for (std::size_t i = objects_.size(); i-- > 0;) {
        if (objects_[i].triangle_base <= h.bad_triangle && objects_[i].triangle_count > 0) {
            const std::uint32_t local = h.bad_triangle - objects_[i].triangle_base;
            where = "object " + std::to_string(i) + ", triangle " + std::to_string(local);
            bad_input_ = BadInput{errors, static_cast<std::uint32_t>(i), local};
            break;
        }
    }
    if (errors & gpu::kCellsBadIndex) return Error(ErrorCode::InvalidMesh, "cell stage: " + where + " has an index beyond its vertices");
    if (errors & gpu::kCellsBadPosition)
        return Error(ErrorCode::InvalidMesh, "cell stage: " + where + " has a position or transform entry that is not finite or not below 2^62");
    return Error(ErrorCode::InvalidMesh, "cell stage: " + where + " has a world coordinate not below 2^62");
}

// Past the budget: the count the run needed, the budget, and what to change. The setup
// sums every triangle's box and the scan every cell's pairs; the candidates are counted
// by the sweep's chunks so far, and no more chunks are swept once they pass the budget
// (the budget bounds the sweep's time): then the count is a lower bound, and says so.
Result<void> CellStage::checkBudget(const gpu::CellsHeader& h) const {
    const std::string budget = asked_budget_ > budget_ ? "the stage's limit of " + std::to_string(budget_) + " (32-bit buffer indices)"
                                                       : "limits.max_candidate_pairs (" + std::to_string(budget_) + ")";
    const std::string where = " at resolution " + std::to_string(resolution_) + " (" + std::to_string(triangles_) + " triangles)";
    if (h.box_cells > budget_)
        return Error(ErrorCode::LimitExceeded, "cell stage: the triangles' footprint boxes span " + std::to_string(h.box_cells) +
                                                   " cells" + where + ", more than " + budget +
                                                   ": lower the resolution or raise limits.max_candidate_pairs");
    const std::uint64_t comparisons = std::uint64_t{budget_} * gpu::kCellsComparisonsPerBudget;
    // Counted by the scan (nothing swept yet), or grown by the sort and sweep of huge cells.
    const bool counted_by_scan = h.sweep_items_end == 0 && h.sweep_entries_end == 0;
    if (h.comparisons > comparisons)
        return Error(ErrorCode::LimitExceeded,
                     "cell stage: " + std::to_string(h.comparisons) +
                         (counted_by_scan ? " pairs of footprints share a cell"
                                          : " or more comparisons of footprints sharing a cell (the sweep stopped at the budget, in cells "
                                            "of more than " + std::to_string(gpu::kCellsDeepShared) + " footprints)") +
                         where + " (up to " + std::to_string(h.max_cell) + " footprints in one cell), more than " +
                         std::to_string(gpu::kCellsComparisonsPerBudget) + " x " + budget + " = " + std::to_string(comparisons) +
                         " the sweep may compare: stacked or repeated triangles? Lower the resolution or raise limits.max_candidate_pairs");
    // Every overlapping pair the sweep found, written or dropped as a repeat in a deep cell.
    if (const std::uint64_t overlapping = h.candidates + h.repeats; overlapping > budget_)
        return Error(ErrorCode::LimitExceeded, "cell stage: " + std::to_string(overlapping) +
                                                   (h.sweep_pending ? " or more candidate pairs (the sweep stopped at the budget, after " +
                                                                          std::to_string(h.sweep_entries_end) + " of " + std::to_string(h.entries) +
                                                                          " footprints and " + std::to_string(h.sweep_items_end) + " of " +
                                                                          std::to_string(h.deep_items) + " deep-cell work items)"
                                                                    : std::string(" candidate pairs")) +
                                                   where + " (up to " + std::to_string(h.max_cell) +
                                                   " footprints in one cell; triangles that may collide, with overlapping depth in a "
                                                   "cell), more than " +
                                                   budget + ": stacked or repeated triangles?");
    if (h.flags & gpu::kCellsOverBudget)  // never without one of the counts above
        return Error(ErrorCode::VulkanError, "cell stage: the budget flag is set but no count exceeds it (internal error)");
    return {};
}

Result<CellStage::Outcome> CellStage::finish(CellStageStats& s) {
    survivor_count_ = gpu_triangle_count_ = 0;
    buf_.header_rb->invalidate();
    gpu::CellsHeader h;
    std::memcpy(&h, buf_.header_rb->mapped(), sizeof h);
    if (auto ok = checkFailure(h); !ok) return ok.error();
    if (auto ok = checkBudget(h); !ok) return ok.error();
    // The chunk just swept (bounds as cells_args.comp sized it), for noteSweepTime().
    const double deepest = std::max(h.max_cell, 1u);
    last_sweep_chunk_work_ = double(h.sweep_entries_end - h.sweep_entries_begin) * std::min(deepest, double(gpu::kCellsSmallCell)) +
                             double(h.sweep_items_end - h.sweep_items_begin) * gpu::kCellsGroupSize *
                                 std::min(deepest, double(gpu::kCellsDeepShared));
    // The sweep goes on through a candidate overflow (its count sizes the rerun's buffer).
    if (h.sweep_pending && (h.flags & ~gpu::kCellsOverflowCandidates) == 0) return Outcome::MoreSweep;
    if (h.flags & gpu::kCellsOverflowMask) {
        // Only the first overflow's count is reliable (later passes did nothing): grow it,
        // and the rerun reports the next one if any. Within the budget every need is at
        // most the budget: entries <= box cells, items <= box cells / 64 (a big triangle's
        // box has more than 64 cells, an item covers up to 4096), survivors <= candidates.
        if (h.flags & gpu::kCellsOverflowItems) capacity_.items = std::max(capacity_.items, grown(h.items, budget_));
        if (h.flags & gpu::kCellsOverflowEntries) capacity_.entries = std::max(capacity_.entries, grown(h.entries, budget_));
        // The huge cells' sort data reaches to the end of the last one (at most the entries).
        if (h.flags & gpu::kCellsOverflowSorted) capacity_.sorted = std::max(capacity_.sorted, grown(h.sorted_need, budget_));
        if (h.flags & gpu::kCellsOverflowCandidates) {
            capacity_.candidates = std::max(capacity_.candidates, grown(h.candidates, budget_));
            // The sweep counted every candidate, and each gives at most one survivor: room
            // for them all now (up to kSurvivorsForCandidates, 8 bytes each), so the rerun
            // does not overflow the survivors and run the whole stage once more.
            const std::uint64_t all = std::min<std::uint64_t>({h.candidates, budget_, kSurvivorsForCandidates});
            capacity_.survivors = std::max(capacity_.survivors, static_cast<std::uint32_t>(all));
        }
        // A chunk of the pair pass that overflows counts only the survivors so far: size for
        // every candidate (and every download triangle) then, so one rerun is enough.
        const bool chunks_left = h.pairs_done < std::min<std::uint64_t>(h.candidates, capacity_.candidates);
        const std::uint32_t all_candidates = static_cast<std::uint32_t>(std::min<std::uint64_t>(h.candidates, budget_));
        if (h.flags & gpu::kCellsOverflowSurvivors)
            capacity_.survivors = std::max({capacity_.survivors, grown(h.survivors, budget_), chunks_left ? all_candidates : 0u});
        if (h.flags & gpu::kCellsOverflowTriangles)
            capacity_.gpu_triangles = std::max(
                capacity_.gpu_triangles,
                chunks_left ? std::max(download_triangles_, 1u)
                            : std::min(grown(h.gpu_triangles, static_cast<std::uint32_t>(kMaxElements)), std::max(download_triangles_, 1u)));
        if (auto ok = ensureBuffers(); !ok) return ok.error();
        writeParams();
        ++runs_;
        return Outcome::Rerun;
    }
    if (h.pairs_done < std::min<std::uint64_t>(h.candidates, capacity_.candidates)) return Outcome::MorePairs;
    ++runs_;
    s = CellStageStats{};
    s.entries = h.entries;
    s.box_cells = h.box_cells;
    s.comparisons = h.comparisons;
    s.big_triangles = h.big_triangles;
    s.items = h.items;
    s.deep_cells = h.deep_cells;
    s.huge_cells = h.huge_cells;
    s.max_cell = h.max_cell;
    s.candidate_cells = h.candidate_cells;
    s.candidates = h.candidates;
    s.neighbours = h.neighbours;
    s.duplicates = h.duplicates;
    s.repeats = h.repeats;
    s.sweep_chunks = sweep_chunks_;
    s.pair_chunks = next_chunk_;
    s.filtered = h.filtered;
    s.survivors = h.survivors;
    s.gpu_triangles = h.gpu_triangles;
    s.runs = runs_;
    s.filter_ran = use_filter_;
    s.exact_ran = use_exact_;
    s.exact_tests = h.exact_tests;
    s.exact_neighbours = h.exact_neighbours;
    s.exact_queued = exactQueued();
    if (use_exact_) last_canonical_ = h.candidates - std::min<std::uint64_t>(h.candidates, h.duplicates);
    if (filterSkippable() && last_canonical_ > 0 && double(h.filtered) < kFilterUsefulShare * double(last_canonical_))
        filter_skips_left_ = kFilterRecheckRuns;
    survivor_count_ = h.survivors;
    gpu_triangle_count_ = has_download_ ? h.gpu_triangles : 0;
    if (survivor_count_ && !survivors_on_device_) buf_.survivors->invalidate(0, VkDeviceSize(survivor_count_) * 8);
    if (gpu_triangle_count_) buf_.gpu_triangles->invalidate(0, VkDeviceSize(gpu_triangle_count_) * sizeof(GpuTriangle));
    return Outcome::Complete;
}

std::span<const CandidatePair> CellStage::survivors() const noexcept {
    if (!survivor_count_ || survivors_on_device_) return {};
    return {static_cast<const CandidatePair*>(buf_.survivors->mapped()), survivor_count_};
}

std::span<const GpuTriangle> CellStage::gpuTriangles() const noexcept {
    if (!gpu_triangle_count_) return {};
    return {static_cast<const GpuTriangle*>(buf_.gpu_triangles->mapped()), gpu_triangle_count_};
}

Result<CellStage::Outcome> CellStage::finish(CellStageResult& out) {
    auto outcome = finish(out.stats);
    if (!outcome || *outcome != Outcome::Complete) return outcome;
    const std::span<const CandidatePair> raw = survivors();
    std::vector<std::uint64_t> keys(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) keys[i] = (std::uint64_t(raw[i].a) << 32) | raw[i].b;
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    out.stats.host_duplicates = raw.size() - keys.size();
    out.pairs.resize(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i)
        out.pairs[i] = {static_cast<std::uint32_t>(keys[i] >> 32), static_cast<std::uint32_t>(keys[i] & 0xFFFFFFFFu)};
    return Outcome::Complete;
}

Result<CellStageResult> CellStage::run(graph::Executor& executor, const CellStageInput& input, const CellStageSettings& settings) {
    if (input.projection_address != 0)
        return Error(ErrorCode::InvalidArgument, "cell stage: run() needs a host projection (record() takes a projection address)");
    if (auto ok = prepare(input, settings); !ok) return ok.error();
    CellStageResult out;
    Outcome next = Outcome::Rerun;  // what to record: the whole stage first
    for (;;) {
        graph::Graph g;
        if (next == Outcome::MorePairs) {
            recordPairChunk(g);
        } else if (next == Outcome::MoreSweep) {
            recordSweepChunk(g);
        } else {
            out.passes.clear();  // the run's passes: a rerun starts over
            out.gpu_ms = 0;
            record(g);
        }
        auto report = executor.run(g);
        if (!report) return report.error();
        out.passes.insert(out.passes.end(), report->passes.begin(), report->passes.end());
        out.gpu_ms += report->total_gpu_ms;
        auto outcome = finish(out);
        if (!outcome) return outcome.error();
        noteSweepTime(report->passes);
        if (*outcome == Outcome::Complete) {
            notePairPassTime(out.passes, out.stats.candidates);
            return out;
        }
        if (*outcome == Outcome::Rerun && runs_ >= std::max(settings.max_runs, 1u))
            return Error(ErrorCode::OutOfMemory, "cell stage: buffers still overflowed after " + std::to_string(runs_) + " runs (entries " +
                                                     std::to_string(capacity_.entries) + ", candidates " +
                                                     std::to_string(capacity_.candidates) + ")");
        next = *outcome;
    }
}

// A device that ends a shader invocation's loops past some count without an error
// (DeviceInfo::loop_iteration_limit: llvmpipe's 65,535 for all of them together): the deep
// sweep, the huge cells' sort and the device pairs' and proximity records' sorts count theirs
// against a bound below it and fail by name instead. Other devices: no bound.
std::uint32_t CellStage::loopGuard() const {
    const std::uint32_t limit = device_->info.loop_iteration_limit;
    return limit == 0 || !loop_guard_ ? ~0u : limit - std::min(limit, kLoopGuardMargin);
}

// What the device sweeps in about kSweepChunkTargetMs at the rate its last sweep chunk
// measured; before any, on a CPU implementation such as lavapipe (some 10^5 comparisons a
// millisecond with the repeat checks) about 2 * 10^7, on a GPU the whole sweep.
std::uint32_t CellStage::automaticSweepWork() const {
    double rate = sweep_rate_;
    if (rate <= 0) {
        if (device_->properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return ~0u;
        rate = 1.0e5;
    }
    const double work = rate * kSweepChunkTargetMs;
    return work >= double(~0u - 1) ? ~0u : static_cast<std::uint32_t>(std::max(work, 4096.0));
}

void CellStage::noteSweepTime(std::span<const graph::PassTiming> passes) {
    double gpu_ms = 0;
    for (auto p = passes.rbegin(); p != passes.rend(); ++p)
        if (p->name == kSweepPassName) {
            gpu_ms = p->gpu_ms;
            break;
        }
    // Too little work to time reliably says nothing about the rate.
    if (gpu_ms > 1.0 && last_sweep_chunk_work_ >= 4096) sweep_rate_ = last_sweep_chunk_work_ / gpu_ms;
    // The next chunk, of this run or the next, at the new rate: the parameters are read by
    // the next submission only.
    if (auto_sweep_work_) {
        const std::uint32_t work = automaticSweepWork();
        if (work != sweep_work_) {
            sweep_work_ = work;
            writeParams();
        }
    }
}

// What the device decides in about kPairChunkTargetMs: at the rate the last complete run
// measured, or before any, a guess by device type (a CPU implementation such as lavapipe
// decides about a hundred candidates a millisecond, a GPU millions).
std::uint32_t CellStage::automaticPairChunk() const {
    double rate = pair_rate_;
    if (rate <= 0) rate = device_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 100.0 : 1.0e6;
    return static_cast<std::uint32_t>(std::clamp(rate * kPairChunkTargetMs, 4096.0, double(kMaxElements)));
}

void CellStage::notePairPassTime(std::span<const graph::PassTiming> passes, std::uint64_t candidates) {
    double gpu_ms = 0;
    for (const graph::PassTiming& p : passes)
        if (p.name == kPairPassName || p.name == kExactPassName) gpu_ms += p.gpu_ms;
    // Too little work to time reliably says nothing about the rate.
    if (gpu_ms > 1.0 && candidates >= 1024) pair_rate_ = double(candidates) / gpu_ms;
}

std::uint64_t CellStage::memoryBytes() const noexcept {
    std::uint64_t total = 0;
    for (const Row* r : {&buf_.params, &buf_.objects, &buf_.object_flags, &buf_.pair_mask, &buf_.projection, &buf_.header,
                         &buf_.header_rb, &buf_.triangles, &buf_.geometry, &buf_.counts, &buf_.offsets, &buf_.block_sums,
                         &buf_.entries, &buf_.chunk_cells, &buf_.big_items, &buf_.deep_items, &buf_.sorted, &buf_.candidates,
                         &buf_.survivors, &buf_.args, &buf_.gpu_triangles, &buf_.marks, &buf_.exact_queue})
        total += (*r)->memoryBytes();
    return total;
}

}  // namespace vkcollide::passes
