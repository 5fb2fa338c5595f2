// CellStage::ensureBuffers: the stage's buffers planned for the prepared run, refused by
// name when the device cannot hold them, then created (they only grow).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <string>

#include "broad/cells/cell_stage.hpp"

namespace vkcollide::passes {
namespace {

std::string gibText(VkDeviceSize bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", double(bytes) / double(1ull << 30));
    return text;
}

}  // namespace

Result<void> CellStage::ensureBuffers() {
    using vk::MemoryKind;
    const VkDeviceSize limit = std::min(device_->max_buffer_size, device_->max_allocation_size);
    // Cells rounded up to a sixteenth of their power of two: a resolution that grows by a
    // few cells a frame re-creates the per-cell buffers only now and then (each re-creation
    // also means a recorded command buffer cannot be submitted again).
    const VkDeviceSize exact_cells = VkDeviceSize(resolution_) * resolution_;
    const VkDeviceSize cell_step = std::max<VkDeviceSize>(1, (VkDeviceSize{1} << (std::bit_width(exact_cells) - 1)) / 16);
    const VkDeviceSize cells = (exact_cells + cell_step - 1) / cell_step * cell_step;
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    const VkDeviceSize objects = objects_.size();
    // Deep items: one per cell deeper than kCellsSmallCell, or ceil(k / kCellsGroupSize) for
    // cells of k > kCellsDeepShared entries; either way at most 2 k / kCellsSmallCell.
    static_assert(gpu::kCellsDeepShared >= 4 * gpu::kCellsGroupSize && gpu::kCellsSmallCell >= gpu::kCellsGroupSize);
    const VkDeviceSize deep = 2 * VkDeviceSize(capacity_.entries) / gpu::kCellsSmallCell + 1;
    const MemoryKind survivors_kind = survivors_on_device_ ? MemoryKind::DeviceLocal : MemoryKind::Readback;
    // A survivor buffer in the other kind of memory is made again.
    if (buf_.survivors.valid() && survivors_in_ != survivors_kind) buf_.survivors.reset();
    survivors_in_ = survivors_kind;
    struct Plan {
        vk::Buffer* buffer;
        VkDeviceSize size;
        MemoryKind kind;
        VkBufferUsageFlags usage;
        const char* name;
    };
    const Plan plan[] = {
        {&buf_.params, sizeof(gpu::CellsParams), MemoryKind::Upload, 0, "cells-params"},
        {&buf_.objects, objects * sizeof(gpu::ObjectGpu), MemoryKind::Upload, 0, "cells-objects"},
        {&buf_.object_flags, objects * 4, MemoryKind::Upload, 0, "cells-object-flags"},
        {&buf_.pair_mask, (objects * objects + 31) / 32 * 4, MemoryKind::Upload, 0, "cells-pair-mask"},
        {&buf_.projection, sizeof(gpu::Projection), MemoryKind::Upload, 0, "cells-projection"},
        {&buf_.header, sizeof(gpu::CellsHeader), MemoryKind::DeviceLocal, 0, "cells-header"},
        {&buf_.header_rb, sizeof(gpu::CellsHeader), MemoryKind::Readback, 0, "cells-header-readback"},
        {&buf_.triangles, tris * sizeof(gpu::CellsTriangle), MemoryKind::DeviceLocal, 0, "cells-triangles"},
        {&buf_.geometry, tris * sizeof(gpu::CellsGeometry), MemoryKind::DeviceLocal, 0, "cells-geometry"},
        {&buf_.counts, cells * 4, MemoryKind::DeviceLocal, 0, "cells-counts"},
        {&buf_.offsets, (cells + 1) * 4, MemoryKind::DeviceLocal, 0, "cells-offsets"},
        {&buf_.block_sums, (cells + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock * 4, MemoryKind::DeviceLocal, 0, "cells-block-sums"},
        {&buf_.entries, VkDeviceSize(capacity_.entries) * sizeof(gpu::CellsEntry), MemoryKind::DeviceLocal, 0, "cells-entries"},
        {&buf_.entry_cells, VkDeviceSize(capacity_.entries) * 4, MemoryKind::DeviceLocal, 0, "cells-entry-cells"},
        {&buf_.big_items, VkDeviceSize(capacity_.items) * 8, MemoryKind::DeviceLocal, 0, "cells-big-items"},
        {&buf_.deep_items, deep * 8, MemoryKind::DeviceLocal, 0, "cells-deep-items"},
        {&buf_.candidates, VkDeviceSize(capacity_.candidates) * sizeof(gpu::CellsCandidate), MemoryKind::DeviceLocal, 0, "cells-candidates"},
        {&buf_.survivors, VkDeviceSize(capacity_.survivors) * 8, survivors_kind, 0, "cells-survivors"},
        {&buf_.args, gpu::kCellsArgsCount * 12, MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, "cells-args"},
        {&buf_.gpu_triangles, has_download_ ? VkDeviceSize(capacity_.gpu_triangles) * sizeof(GpuTriangle) : 0, MemoryKind::Readback, 0,
         "cells-gpu-triangles"},
        {&buf_.marks, has_download_ ? (tris + 31) / 32 * 4 : 0, MemoryKind::DeviceLocal, 0, "cells-marks"},
    };
    // Refuse what the device cannot hold before allocating anything (as the broad phase's
    // table does): the heap sizes bound what fits, the engine's allocations live there too.
    std::array<VkDeviceSize, VK_MAX_MEMORY_HEAPS> per_heap{};
    VkDeviceSize total = 0;
    for (const Plan& p : plan) {
        const VkMemoryPropertyFlags required =
            p.kind == MemoryKind::DeviceLocal ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
        if (auto type = device_->findMemoryType(~0u, required)) per_heap[device_->memory.memoryTypes[*type].heapIndex] += p.size;
        total += p.size;
    }
    for (std::uint32_t h = 0; h < device_->memory.memoryHeapCount; ++h)
        if (per_heap[h] > device_->memory.memoryHeaps[h].size)
            return Error(ErrorCode::OutOfMemory, "cell stage: resolution " + std::to_string(resolution_) + " with " +
                                                     std::to_string(triangles_) + " triangles needs " + gibText(total) +
                                                     " of device memory, more than the " + gibText(device_->memory.memoryHeaps[h].size) +
                                                     " memory heap holds: lower the resolution or split the scene");
    for (const Plan& p : plan) {
        const VkDeviceSize size = std::max<VkDeviceSize>(p.size, 16);
        if (size > limit)
            return Error(ErrorCode::OutOfMemory, std::string("cell stage: the '") + p.name + "' buffer would need " + gibText(size) +
                                                     ", more than the device's largest buffer (" + gibText(limit) +
                                                     "): lower the resolution or split the scene");
        if (p.buffer->valid() && p.buffer->size() >= size) continue;
        p.buffer->reset();  // free the smaller one first
        auto made = vk::Buffer::create(*device_, size, p.usage, p.kind, p.name);
        if (!made) return made.error();
        *p.buffer = std::move(*made);
    }
    // The shaders load and store entries as 16-byte vectors (buffer_reference_align in
    // cells_common.glsl.inc). Buffers start at the device's storage alignment, which Vulkan
    // does not bound from below: check.
    if (buf_.entries.address() % 16 != 0)
        return Error(ErrorCode::UnsupportedFeature, "cell stage: the device placed 'cells-entries' at address " +
                                                        std::to_string(buf_.entries.address()) + ", not a multiple of 16 bytes");
    return {};
}

}  // namespace vkcollide::passes
