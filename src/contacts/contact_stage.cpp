#include "contacts/contact_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "contacts/contact_grid.hpp"
#include "shaders/all.hpp"

namespace vkcollide::passes {
namespace {

using graph::PassContext;
using graph::PassKind;
using graph::Use;

static_assert(sizeof(gpu::ContactsParams) == 176 && sizeof(gpu::ContactsHeader) == 32);
static_assert(sizeof(gpu::CtTriangle) == 72 && sizeof(gpu::ContactsPair) == 80);

// Ray lists beyond this are refused (OutOfMemory naming contacts.resolution): the stage
// must not take the memory the engine and the broad phase need.
constexpr VkDeviceSize kMaxListBytes = VkDeviceSize(1) << 30;
constexpr std::uint32_t kMaxRuns = 6;
// Loop iterations kept below DeviceInfo::loop_iteration_limit for what the walk does not
// count (its flush: at most a few hundred a subgroup).
constexpr std::uint32_t kLoopGuardMargin = 5535;

std::uint64_t groupsFor(std::uint64_t items) { return (items + gpu::kContactsGroupSize - 1) / gpu::kContactsGroupSize; }

std::string mib(VkDeviceSize bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

}  // namespace

std::uint32_t contactPairHash(std::uint32_t a, std::uint32_t b) {
    std::uint32_t h = (a * 0x9E3779B1u) ^ ((b + 0x7F4A7C15u) * 0x85EBCA77u);
    return h ^ (h >> 15);
}

Result<std::unique_ptr<FollowUpStage>> ContactStage::create(vk::Device& device, BufferTable& table) {
    std::unique_ptr<ContactStage> cs(new ContactStage(device, table));
    auto& P = cs->pipes_;
    for (auto r : {makeCompute(device, P.bounds, shaders::contacts_bounds_comp, "contacts-bounds"),
                   makeCompute(device, P.setup, shaders::contacts_setup_comp, "contacts-setup"),
                   makeCompute(device, P.tiles, shaders::contacts_tiles_comp, "contacts-tiles"),
                   makeCompute(device, P.walk, shaders::contacts_walk_comp, "contacts-walk")})
        if (!r) return r.error();
    cs->addRows();
    return std::unique_ptr<FollowUpStage>(std::move(cs));
}

void ContactStage::addRows() {
    using vk::MemoryKind;
    Rows& r = rows_;
    r.params = table_->addOwned("contacts-params", MemoryKind::Upload);
    r.active = table_->addOwned("contacts-active", MemoryKind::Upload);
    r.bounds = table_->addOwned("contacts-bounds", MemoryKind::DeviceLocal);
    r.bounds_rb = table_->addOwned("contacts-bounds-readback", MemoryKind::Readback);
    r.triangles = table_->addOwned("contacts-triangles", MemoryKind::DeviceLocal);
    r.items = table_->addOwned("contacts-items", MemoryKind::DeviceLocal);
    r.counts = table_->addOwned("contacts-counts", MemoryKind::DeviceLocal);
    r.entries = table_->addOwned("contacts-entries", MemoryKind::DeviceLocal);
    r.table_init = table_->addOwned("contacts-table-init", MemoryKind::Upload);
    r.table = table_->addOwned("contacts-table", MemoryKind::DeviceLocal);
    r.header = table_->addOwned("contacts-header", MemoryKind::DeviceLocal);
    r.args = table_->addOwned("contacts-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    r.readback = table_->addOwned("contacts-readback", MemoryKind::Readback);
}

// Rows sized by what this step knows; the others keep their size.
Result<void> ContactStage::reserve(std::initializer_list<RowSize> sizes) {
    return table_->reserve(*device_, std::span<const RowSize>(sizes.begin(), sizes.size()),
                           "contacts: " + std::to_string(objects_) + " objects with " + std::to_string(params_.triangle_count) +
                               " triangles");
}

// Submission 1: every closed object's world box.
void ContactStage::recordBounds(graph::Graph& g) {
    const auto bounds = importRow(g, rows_.bounds);
    const auto bounds_rb = importRow(g, rows_.bounds_rb, true);
    const VkBuffer bounds_buffer = rows_.bounds->handle(), rb_buffer = rows_.bounds_rb->handle();
    const VkDeviceSize half = VkDeviceSize(objects_) * 12;
    addPass(g, "contacts-bounds-clear", PassKind::Transfer, Stage::None).use(bounds, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(bounds_buffer, 0, half, 0xFFFFFFFFu);
        pc.fillBuffer(bounds_buffer, half, half, 0u);
    });
    const VkDeviceAddress params = rows_.params->address();
    const std::uint64_t tri_groups = groupsFor(params_.triangle_count);
    const std::uint32_t max_x = params_.max_groups_x;
    addPass(g, "contacts-bounds", PassKind::Compute, Stage::None).readWrite(bounds).record([this, params, tri_groups, max_x](PassContext& pc) {
        bindAndPush(pc, pipes_.bounds, params);
        dispatchGroups(pc, tri_groups, max_x);
    });
    addPass(g, "contacts-bounds-readback", PassKind::Transfer, Stage::None)
        .use(bounds, Use::TransferSrc)
        .use(bounds_rb, Use::TransferDst)
        .record([=](PassContext& pc) {
            VkBufferCopy copy{0, 0, 2 * half};
            pc.copyBuffer(bounds_buffer, rb_buffer, copy);
        });
}

std::vector<std::array<float, 6>> ContactStage::readBoxes() const {
    const std::uint32_t n = objects_;
    rows_.bounds_rb->invalidate(0, VkDeviceSize(n) * 24);
    const auto* words = static_cast<const std::uint32_t*>(rows_.bounds_rb->mapped());
    std::vector<std::array<float, 6>> boxes(n);
    for (std::uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t lo = words[i * 3 + k], hi = words[(n + i) * 3 + k];
            // Untouched entries keep their clear values: no box (min > max).
            boxes[i][k] = lo == 0xFFFFFFFFu ? INFINITY : orderedToFloat(lo);
            boxes[i][3 + k] = hi == 0u ? -INFINITY : orderedToFloat(hi);
        }
    return boxes;
}

// Submission 2: clear, setup (+ small triangles), tiles, walk (sums, then extents), readback.
void ContactStage::recordMain(graph::Graph& g) {
    const auto counts = importRow(g, rows_.counts);
    const auto header = importRow(g, rows_.header);
    const auto table = importRow(g, rows_.table);
    const auto table_init = importRow(g, rows_.table_init);
    const auto tris = importRow(g, rows_.triangles);
    const auto items = importRow(g, rows_.items);
    const auto entries = importRow(g, rows_.entries);
    const auto args = importRow(g, rows_.args);
    const auto readback = importRow(g, rows_.readback, true);
    const VkBuffer counts_b = rows_.counts->handle(), header_b = rows_.header->handle(), table_b = rows_.table->handle();
    const VkBuffer init_b = rows_.table_init->handle(), args_b = rows_.args->handle(), rb_b = rows_.readback->handle();
    const VkDeviceSize rays = VkDeviceSize(params_.width) * params_.height;
    const VkDeviceSize table_bytes = VkDeviceSize(table_size_) * sizeof(gpu::ContactsPair);
    const VkDeviceAddress params = rows_.params->address();
    const std::uint32_t max_x = params_.max_groups_x;
    const std::uint64_t tri_groups = groupsFor(params_.triangle_count), ray_groups = groupsFor(rays);

    addPass(g, "contacts-clear", PassKind::Transfer, Stage::None)
        .use(counts, Use::TransferDst)
        .use(header, Use::TransferDst)
        .use(table_init, Use::TransferSrc)
        .use(table, Use::TransferDst)
        .record([=](PassContext& pc) {
            pc.fillBuffer(counts_b, 0, rays * 4, 0);
            pc.fillBuffer(header_b, 0, sizeof(gpu::ContactsHeader), 0);
            VkBufferCopy copy{0, 0, table_bytes};
            pc.copyBuffer(init_b, table_b, copy);
        });
    addPass(g, "contacts-setup", PassKind::Compute, Stage::None)
        .write(tris)
        .write(items)
        .readWrite(counts)
        .readWrite(entries)
        .readWrite(header)
        .write(args)
        .record([this, params, tri_groups, max_x](PassContext& pc) {
            bindAndPush(pc, pipes_.setup, params);
            dispatchGroups(pc, tri_groups, max_x);
            pc.shaderBarrier();
            bindAndPush(pc, pipes_.tiles, params, 0, 1);  // the tile pass's arguments
            pc.dispatch(1, 1, 1);
        });
    addPass(g, "contacts-tiles", PassKind::Compute, Stage::None)
        .indirect(args)
        .read(tris)
        .read(items)
        .readWrite(counts)
        .readWrite(entries)
        .readWrite(header)
        .record([this, params, args_b](PassContext& pc) {
            bindAndPush(pc, pipes_.tiles, params, 0, 0);
            pc.dispatchIndirect(args_b, 0);
        });
    addPass(g, "contacts-walk", PassKind::Compute, Stage::None)
        .read(tris)
        .read(counts)
        .readWrite(entries)
        .readWrite(table)
        .readWrite(header)
        .record([this, params, ray_groups, max_x](PassContext& pc) {
            bindAndPush(pc, pipes_.walk, params, 0, 0);
            dispatchGroups(pc, ray_groups, max_x);
            pc.shaderBarrier();
            bindAndPush(pc, pipes_.walk, params, 0, 1);
            dispatchGroups(pc, ray_groups, max_x);
        });
    addPass(g, "contacts-readback", PassKind::Transfer, Stage::None)
        .use(header, Use::TransferSrc)
        .use(table, Use::TransferSrc)
        .use(readback, Use::TransferDst)
        .record([=](PassContext& pc) {
            VkBufferCopy copies[2] = {{0, 0, sizeof(gpu::ContactsHeader)}, {0, sizeof(gpu::ContactsHeader), table_bytes}};
            pc.copyBuffer(header_b, rb_b, copies[0]);
            pc.copyBuffer(table_b, rb_b, copies[1]);
        });
}

void ContactStage::record(graph::Graph& g, const RunView&) {
    if (step_ == Step::Bounds)
        recordBounds(g);
    else
        recordMain(g);
}

Result<Collected> ContactStage::begin(const RunView& run) {
    out_ = ContactStageResult{};
    step_ = Step::Bounds;
    if (in_.resolution < gpu::kMinContactResolution || in_.resolution > gpu::kMaxContactResolution)
        return Error(ErrorCode::InvalidArgument, "contacts.resolution " + std::to_string(in_.resolution) + " is not in [" +
                                                     std::to_string(gpu::kMinContactResolution) + ", " +
                                                     std::to_string(gpu::kMaxContactResolution) + "]");
    const std::uint32_t n = static_cast<std::uint32_t>(run.meshes.size());
    std::uint64_t total = 0;
    bool any_closed = false;
    for (const GpuMesh& m : run.meshes) {
        total += m.triangle_count;
        any_closed = any_closed || (!m.open && m.triangle_count > 0);
    }
    // No closed object, or fewer than two: no contact (not an error).
    if (!any_closed || n < 2 || total == 0 || total > gpu::kMaxTriangles) return Collected::Done;
    objects_ = n;
    params_ = {};
    params_.triangle_count = static_cast<std::uint32_t>(total);
    using vk::MemoryKind;
    if (auto ok = reserve({rowSize(rows_.params, sizeof(gpu::ContactsParams), MemoryKind::Upload),
                           rowSize(rows_.active, VkDeviceSize(n) * 4, MemoryKind::Upload),
                           rowSize(rows_.bounds, VkDeviceSize(n) * 24, MemoryKind::DeviceLocal),
                           rowSize(rows_.bounds_rb, VkDeviceSize(n) * 24, MemoryKind::Readback)});
        !ok)
        return ok.error();
    // The broad phase's objects as it uploaded them: the same triangle bases and transforms.
    params_.objects = run.objects_address;
    params_.object_active = rows_.active->address();
    params_.bounds = rows_.bounds->address();
    params_.object_count = n;
    params_.max_groups_x = device_->properties.limits.maxComputeWorkGroupCount[0];
    params_.max_weight = gpu::kContactMaxWeight;
    // A device that ends a shader invocation's loops past some count without an error
    // (llvmpipe): the walk counts its loops against a bound below it and fails by name.
    const std::uint32_t limit = device_->info.loop_iteration_limit;
    params_.loop_guard = limit == 0 ? ~0u : limit - std::min(limit, kLoopGuardMargin);
    auto* active = static_cast<std::uint32_t*>(rows_.active->mapped());
    for (std::uint32_t i = 0; i < n; ++i) active[i] = run.meshes[i].open ? 0u : 1u;
    rows_.active->flush();
    std::memcpy(rows_.params->mapped(), &params_, sizeof params_);
    rows_.params->flush();
    return Collected::Again;
}

Result<Collected> ContactStage::collect(const RunView& run, const graph::ExecutionReport& report) {
    out_.gpu_ms += report.total_gpu_ms;
    if (step_ == Step::Bounds) return afterBounds(run);
    ++out_.runs;
    rows_.readback->invalidate(0, sizeof(gpu::ContactsHeader) + VkDeviceSize(table_size_) * sizeof(gpu::ContactsPair));
    gpu::ContactsHeader h;
    std::memcpy(&h, rows_.readback->mapped(), sizeof h);
    if (h.flags == 0) {
        readContacts(h);
        return Collected::Done;
    }
    if (h.flags & gpu::kContactsLoopLimit)
        return Error(ErrorCode::LimitExceeded,
                     "contacts: a ray crosses more surfaces (" + std::to_string(h.max_fragments) + " hits on one ray at contacts.resolution " +
                         std::to_string(in_.resolution) + ") than " + vk::loopLimitPhrase(*device_, "sorts and walks") +
                         ": fewer surfaces stacked along the direction, or detect on a GPU");
    if (h.flags & gpu::kContactsOverflowLayers) layers_ = std::max(layers_ + 1, h.max_fragments + h.max_fragments / 4);
    if (h.flags & gpu::kContactsOverflowItems) item_capacity_ = std::max(item_capacity_ + 1, h.items_needed + h.items_needed / 4);
    if (out_.runs == kMaxRuns)
        return Error(ErrorCode::OutOfMemory, "contacts: ray lists still overflowed after " + std::to_string(kMaxRuns) + " runs (" +
                                                 std::to_string(layers_) + " hits per ray)");
    if (auto ok = prepareMain(); !ok) return ok.error();
    return Collected::Again;
}

Result<Collected> ContactStage::afterBounds(const RunView& run) {
    const std::uint32_t n = objects_;
    const std::vector<std::array<float, 6>> boxes = readBoxes();
    std::vector<std::uint8_t> closed(n);
    for (std::uint32_t i = 0; i < n; ++i) closed[i] = run.meshes[i].open ? 0 : 1;
    ContactCandidates cand = findContactCandidates(boxes, closed, in_.may_collide);
    out_.candidates = cand.pairs;
    out_.candidate_middles = cand.middles;
    if (cand.pairs.empty()) return Collected::Done;
    grid_ = fitContactGrid(in_.direction, cand.region, in_.resolution);
    step_ = Step::Main;

    // Objects drawn: those in a candidate pair.
    auto* active = static_cast<std::uint32_t*>(rows_.active->mapped());
    std::fill(active, active + n, 0u);
    for (const auto& [a, b] : cand.pairs) active[a] = active[b] = 1u;
    rows_.active->flush();
    // The table: keys written here, never full (at most half the slots used).
    table_size_ = 16;
    while (table_size_ < 2 * cand.pairs.size()) table_size_ *= 2;
    const VkDeviceSize table_bytes = VkDeviceSize(table_size_) * sizeof(gpu::ContactsPair);
    const VkDeviceSize rays = VkDeviceSize(grid_.width) * grid_.height;
    using vk::MemoryKind;
    if (auto ok = reserve({rowSize(rows_.table_init, table_bytes, MemoryKind::Upload),
                           rowSize(rows_.table, table_bytes, MemoryKind::DeviceLocal),
                           rowSize(rows_.header, sizeof(gpu::ContactsHeader), MemoryKind::DeviceLocal),
                           rowSize(rows_.readback, sizeof(gpu::ContactsHeader) + table_bytes, MemoryKind::Readback),
                           rowSize(rows_.args, 16, MemoryKind::DeviceLocal),
                           rowSize(rows_.triangles, VkDeviceSize(params_.triangle_count) * sizeof(gpu::CtTriangle), MemoryKind::DeviceLocal),
                           rowSize(rows_.counts, rays * 4, MemoryKind::DeviceLocal)});
        !ok)
        return ok.error();
    auto* init = static_cast<gpu::ContactsPair*>(rows_.table_init->mapped());
    std::memset(init, 0, table_bytes);
    for (const auto& [a, b] : cand.pairs) {
        std::uint32_t s = contactPairHash(a, b) & (table_size_ - 1);
        while (init[s].b_plus_one != 0) s = (s + 1) & (table_size_ - 1);
        init[s].a = a;
        init[s].b_plus_one = b + 1;
    }
    for (std::uint32_t s = 0; s < table_size_; ++s) init[s].extent_min = 0xFFFFFFFFu;  // empty interval: min > max
    rows_.table_init->flush();
    if (auto ok = prepareMain(); !ok) return ok.error();
    return Collected::Again;
}

Result<void> ContactStage::prepareMain() {
    const VkDeviceSize rays = VkDeviceSize(grid_.width) * grid_.height;
    const VkDeviceSize list_bytes = rays * layers_ * 8;
    if (list_bytes > kMaxListBytes)
        return Error(ErrorCode::OutOfMemory, "contacts: " + std::to_string(rays) + " rays with up to " + std::to_string(layers_) +
                                                 " hits each need " + mib(list_bytes) + " of ray lists (more than " +
                                                 mib(kMaxListBytes) + "); lower contacts.resolution");
    using vk::MemoryKind;
    if (auto ok = reserve({rowSize(rows_.entries, list_bytes, MemoryKind::DeviceLocal),
                           rowSize(rows_.items, VkDeviceSize(item_capacity_) * 8, MemoryKind::DeviceLocal)});
        !ok)
        return ok;
    params_.triangles = rows_.triangles->address();
    params_.items = rows_.items->address();
    params_.counts = rows_.counts->address();
    params_.entries = rows_.entries->address();
    params_.table = rows_.table->address();
    params_.header = rows_.header->address();
    params_.args = rows_.args->address();
    params_.layers = layers_;
    params_.item_capacity = item_capacity_;
    params_.table_mask = table_size_ - 1;
    writeGridParams(grid_, layers_, params_);
    std::memcpy(rows_.params->mapped(), &params_, sizeof params_);
    rows_.params->flush();
    return {};
}

void ContactStage::readContacts(const gpu::ContactsHeader& h) {
    out_.width = grid_.width;
    out_.height = grid_.height;
    out_.layers = layers_;
    out_.nested_rays = h.nested_rays;
    out_.overlap_rays = h.overlap_rays;
    out_.fragments = h.fragments;
    const auto* pairs = reinterpret_cast<const gpu::ContactsPair*>(static_cast<const char*>(rows_.readback->mapped()) + sizeof h);
    for (std::uint32_t s = 0; s < table_size_; ++s) {
        if (pairs[s].b_plus_one == 0) continue;
        StageContact c;
        c.a = pairs[s].a;
        c.b = pairs[s].b_plus_one - 1;
        if (contactFromSums(pairs[s], grid_, params_.fixed_scale, c)) out_.contacts.push_back(c);
    }
    std::sort(out_.contacts.begin(), out_.contacts.end(), [](const StageContact& x, const StageContact& y) {
        return x.a < y.a || (x.a == y.a && x.b < y.b);
    });
}

}  // namespace vkcollide::passes
