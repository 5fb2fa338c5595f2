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

std::uint64_t groupsFor(std::uint64_t items) { return (items + gpu::kContactsGroupSize - 1) / gpu::kContactsGroupSize; }

std::string mib(VkDeviceSize bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

}  // namespace

std::uint32_t contactPairHash(std::uint32_t a, std::uint32_t b) {
    std::uint32_t h = (a * 0x9E3779B1u) ^ ((b + 0x7F4A7C15u) * 0x85EBCA77u);
    return h ^ (h >> 15);
}

Result<std::unique_ptr<ContactStage>> ContactStage::create(vk::Device& device) {
    std::unique_ptr<ContactStage> cs(new ContactStage(device));
    auto& P = cs->pipes_;
    for (auto r : {makeCompute(device, P.bounds, shaders::contacts_bounds_comp, "contacts-bounds"),
                   makeCompute(device, P.setup, shaders::contacts_setup_comp, "contacts-setup"),
                   makeCompute(device, P.tiles, shaders::contacts_tiles_comp, "contacts-tiles"),
                   makeCompute(device, P.walk, shaders::contacts_walk_comp, "contacts-walk")})
        if (!r) return r.error();
    return cs;
}

Result<void> ContactStage::ensure(vk::Buffer& b, VkDeviceSize bytes, vk::MemoryKind kind, const char* name) {
    bytes = std::max<VkDeviceSize>(bytes, 16);
    if (b.valid() && b.size() >= bytes) return {};
    b.reset();  // free before allocating the bigger one
    auto r = vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, kind, name);
    if (!r) return r.error();
    b = std::move(*r);
    return {};
}

std::uint64_t ContactStage::memoryBytes() const noexcept {
    std::uint64_t n = 0;
    for (const vk::Buffer* b : {&buf_.params, &buf_.objects, &buf_.active, &buf_.bounds, &buf_.bounds_rb, &buf_.triangles,
                                &buf_.items, &buf_.counts, &buf_.entries, &buf_.table_init, &buf_.table, &buf_.header, &buf_.args,
                                &buf_.readback})
        n += b->size();
    return n;
}

// Submission 1: every closed object's world box.
Result<std::vector<std::array<float, 6>>> ContactStage::measureBoxes(const ContactInput& in) {
    const std::uint32_t n = static_cast<std::uint32_t>(in.meshes.size());
    std::vector<std::uint32_t> active(n);
    for (std::uint32_t i = 0; i < n; ++i) active[i] = in.meshes[i].open ? 0u : 1u;
    std::memcpy(buf_.active.mapped(), active.data(), n * 4);
    buf_.active.flush();
    std::memcpy(buf_.params.mapped(), &params_, sizeof params_);
    buf_.params.flush();
    graph::Graph g;
    const auto bounds = g.importBuffer("contacts-bounds", buf_.bounds);
    const auto bounds_rb = g.importBuffer("contacts-bounds-readback", buf_.bounds_rb, true);
    const VkBuffer bounds_buffer = buf_.bounds.handle(), rb_buffer = buf_.bounds_rb.handle();
    const VkDeviceSize half = VkDeviceSize(n) * 12;
    addPass(g, "contacts-bounds-clear", PassKind::Transfer, Stage::None).use(bounds, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(bounds_buffer, 0, half, 0xFFFFFFFFu);
        pc.fillBuffer(bounds_buffer, half, half, 0u);
    });
    const VkDeviceAddress params = buf_.params.address();
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
    auto report = executor_.run(g, in.waitNs());
    if (!report) return in.timeoutOf(report.error());
    last_gpu_ms_ = report->total_gpu_ms;
    buf_.bounds_rb.invalidate(0, 2 * half);
    const auto* words = static_cast<const std::uint32_t*>(buf_.bounds_rb.mapped());
    std::vector<std::array<float, 6>> boxes(n);
    for (std::uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t lo = words[i * 3 + k], hi = words[(n + i) * 3 + k];
            // Untouched minima stay 0xFFFFFFFF (NaN as a float): no box.
            // Untouched entries keep their clear values: no box (min > max).
            boxes[i][k] = lo == 0xFFFFFFFFu ? INFINITY : orderedToFloat(lo);
            boxes[i][3 + k] = hi == 0u ? -INFINITY : orderedToFloat(hi);
        }
    return boxes;
}

// Submission 2: clear, setup (+ small triangles), tiles, walk (sums, then extents), readback.
void ContactStage::recordMain(graph::Graph& g) {
    const auto counts = g.importBuffer("contacts-counts", buf_.counts);
    const auto header = g.importBuffer("contacts-header", buf_.header);
    const auto table = g.importBuffer("contacts-table", buf_.table);
    const auto table_init = g.importBuffer("contacts-table-init", buf_.table_init);
    const auto tris = g.importBuffer("contacts-triangles", buf_.triangles);
    const auto items = g.importBuffer("contacts-items", buf_.items);
    const auto entries = g.importBuffer("contacts-entries", buf_.entries);
    const auto args = g.importBuffer("contacts-args", buf_.args);
    const auto readback = g.importBuffer("contacts-readback", buf_.readback, true);
    const VkBuffer counts_b = buf_.counts.handle(), header_b = buf_.header.handle(), table_b = buf_.table.handle();
    const VkBuffer init_b = buf_.table_init.handle(), args_b = buf_.args.handle(), rb_b = buf_.readback.handle();
    const VkDeviceSize rays = VkDeviceSize(params_.width) * params_.height;
    const VkDeviceSize table_bytes = VkDeviceSize(table_size_) * sizeof(gpu::ContactsPair);
    const VkDeviceAddress params = buf_.params.address();
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

Result<ContactStageResult> ContactStage::run(const ContactInput& in) {
    if (in.resolution < gpu::kMinContactResolution || in.resolution > gpu::kMaxContactResolution)
        return Error(ErrorCode::InvalidArgument, "contacts.resolution " + std::to_string(in.resolution) + " is not in [" +
                                                     std::to_string(gpu::kMinContactResolution) + ", " +
                                                     std::to_string(gpu::kMaxContactResolution) + "]");
    ContactStageResult out;
    const std::uint32_t n = static_cast<std::uint32_t>(in.meshes.size());
    std::uint64_t total = 0;
    bool any_closed = false;
    objects_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const GpuMesh& m = in.meshes[i];
        objects_[i] = objectGpu(m, static_cast<std::uint32_t>(total));
        total += m.triangle_count;
        any_closed = any_closed || (!m.open && m.triangle_count > 0);
    }
    // No closed object, or fewer than two: no contact (not an error).
    if (!any_closed || n < 2 || total == 0 || total > gpu::kMaxTriangles) return out;
    using vk::MemoryKind;
    for (auto r : {ensure(buf_.params, sizeof(gpu::ContactsParams), MemoryKind::Upload, "contacts-params"),
                   ensure(buf_.objects, VkDeviceSize(n) * sizeof(gpu::ObjectGpu), MemoryKind::Upload, "contacts-objects"),
                   ensure(buf_.active, VkDeviceSize(n) * 4, MemoryKind::Upload, "contacts-active"),
                   ensure(buf_.bounds, VkDeviceSize(n) * 24, MemoryKind::DeviceLocal, "contacts-bounds"),
                   ensure(buf_.bounds_rb, VkDeviceSize(n) * 24, MemoryKind::Readback, "contacts-bounds-readback")})
        if (!r) return r.error();
    std::memcpy(buf_.objects.mapped(), objects_.data(), n * sizeof(gpu::ObjectGpu));
    buf_.objects.flush();
    params_ = {};
    params_.objects = buf_.objects.address();
    params_.object_active = buf_.active.address();
    params_.bounds = buf_.bounds.address();
    params_.triangle_count = static_cast<std::uint32_t>(total);
    params_.object_count = n;
    params_.max_groups_x = device_->properties.limits.maxComputeWorkGroupCount[0];
    params_.max_weight = gpu::kContactMaxWeight;

    auto boxes = measureBoxes(in);
    if (!boxes) return boxes.error();
    out.gpu_ms = last_gpu_ms_;
    std::vector<std::uint8_t> closed(n);
    for (std::uint32_t i = 0; i < n; ++i) closed[i] = in.meshes[i].open ? 0 : 1;
    ContactCandidates cand = findContactCandidates(*boxes, closed, in.may_collide);
    out.candidates = cand.pairs;
    out.candidate_middles = cand.middles;
    if (cand.pairs.empty()) return out;
    const ContactGrid grid = fitContactGrid(in.direction, cand.region, in.resolution);

    // Objects drawn: those in a candidate pair.
    std::vector<std::uint32_t> active(n, 0u);
    for (const auto& [a, b] : cand.pairs) active[a] = active[b] = 1u;
    std::memcpy(buf_.active.mapped(), active.data(), n * 4);
    buf_.active.flush();
    // The table: keys written here, never full (at most half the slots used).
    table_size_ = 16;
    while (table_size_ < 2 * cand.pairs.size()) table_size_ *= 2;
    const VkDeviceSize table_bytes = VkDeviceSize(table_size_) * sizeof(gpu::ContactsPair);
    const VkDeviceSize rays = VkDeviceSize(grid.width) * grid.height;
    for (auto r : {ensure(buf_.table_init, table_bytes, MemoryKind::Upload, "contacts-table-init"),
                   ensure(buf_.table, table_bytes, MemoryKind::DeviceLocal, "contacts-table"),
                   ensure(buf_.header, sizeof(gpu::ContactsHeader), MemoryKind::DeviceLocal, "contacts-header"),
                   ensure(buf_.readback, sizeof(gpu::ContactsHeader) + table_bytes, MemoryKind::Readback, "contacts-readback"),
                   ensure(buf_.args, 16, MemoryKind::DeviceLocal, "contacts-args"),
                   ensure(buf_.triangles, total * sizeof(gpu::CtTriangle), MemoryKind::DeviceLocal, "contacts-triangles"),
                   ensure(buf_.counts, rays * 4, MemoryKind::DeviceLocal, "contacts-counts")})
        if (!r) return r.error();
    auto* init = static_cast<gpu::ContactsPair*>(buf_.table_init.mapped());
    std::memset(init, 0, table_bytes);
    for (const auto& [a, b] : cand.pairs) {
        std::uint32_t s = contactPairHash(a, b) & (table_size_ - 1);
        while (init[s].b_plus_one != 0) s = (s + 1) & (table_size_ - 1);
        init[s].a = a;
        init[s].b_plus_one = b + 1;
    }
    for (std::uint32_t s = 0; s < table_size_; ++s) init[s].extent_min = 0xFFFFFFFFu;  // empty interval: min > max
    buf_.table_init.flush();

    for (std::uint32_t attempt = 0; attempt < kMaxRuns; ++attempt) {
        const VkDeviceSize list_bytes = rays * layers_ * 8;
        if (list_bytes > kMaxListBytes)
            return Error(ErrorCode::OutOfMemory, "contacts: " + std::to_string(rays) + " rays with up to " + std::to_string(layers_) +
                                                     " hits each need " + mib(list_bytes) + " of ray lists (more than " +
                                                     mib(kMaxListBytes) + "); lower contacts.resolution");
        for (auto r : {ensure(buf_.entries, list_bytes, MemoryKind::DeviceLocal, "contacts-entries"),
                       ensure(buf_.items, VkDeviceSize(item_capacity_) * 8, MemoryKind::DeviceLocal, "contacts-items")})
            if (!r) return r.error();
        params_.triangles = buf_.triangles.address();
        params_.items = buf_.items.address();
        params_.counts = buf_.counts.address();
        params_.entries = buf_.entries.address();
        params_.table = buf_.table.address();
        params_.header = buf_.header.address();
        params_.args = buf_.args.address();
        params_.layers = layers_;
        params_.item_capacity = item_capacity_;
        params_.table_mask = table_size_ - 1;
        writeGridParams(grid, layers_, params_);
        std::memcpy(buf_.params.mapped(), &params_, sizeof params_);
        buf_.params.flush();
        graph::Graph g;
        recordMain(g);
        auto report = executor_.run(g, in.waitNs());
        if (!report) return in.timeoutOf(report.error());
        out.gpu_ms += report->total_gpu_ms;
        ++out.runs;
        buf_.readback.invalidate(0, sizeof(gpu::ContactsHeader) + table_bytes);
        gpu::ContactsHeader h;
        std::memcpy(&h, buf_.readback.mapped(), sizeof h);
        if (h.flags & gpu::kContactsOverflowLayers) layers_ = std::max(layers_ + 1, h.max_fragments + h.max_fragments / 4);
        if (h.flags & gpu::kContactsOverflowItems) item_capacity_ = std::max(item_capacity_ + 1, h.items_needed + h.items_needed / 4);
        if (h.flags != 0) continue;
        out.width = grid.width;
        out.height = grid.height;
        out.layers = layers_;
        out.nested_rays = h.nested_rays;
        out.overlap_rays = h.overlap_rays;
        out.fragments = h.fragments;
        const auto* pairs = reinterpret_cast<const gpu::ContactsPair*>(static_cast<const char*>(buf_.readback.mapped()) + sizeof h);
        for (std::uint32_t s = 0; s < table_size_; ++s) {
            if (pairs[s].b_plus_one == 0) continue;
            StageContact c;
            c.a = pairs[s].a;
            c.b = pairs[s].b_plus_one - 1;
            if (contactFromSums(pairs[s], grid, params_.fixed_scale, c)) out.contacts.push_back(c);
        }
        std::sort(out.contacts.begin(), out.contacts.end(), [](const StageContact& x, const StageContact& y) {
            return x.a < y.a || (x.a == y.a && x.b < y.b);
        });
        return out;
    }
    return Error(ErrorCode::OutOfMemory, "contacts: ray lists still overflowed after " + std::to_string(kMaxRuns) + " runs (" +
                                             std::to_string(layers_) + " hits per ray)");
}

}  // namespace vkcollide::passes
