// The cell stage's buffers: rows of its BufferTable (added once, by addRows), sized by
// ensureBuffers() for the prepared run and after each overflow; the table refuses by name
// what the device cannot hold before allocating anything.
#include <algorithm>
#include <bit>
#include <string>

#include "broad/cells/cell_stage.hpp"

namespace vkcollide::passes {

void CellStage::addRows() {
    using vk::MemoryKind;
    auto row = [this](Row& out, const char* name, MemoryKind kind, VkBufferUsageFlags usage = 0) {
        out = table_->addOwned(name, kind, usage);
    };
    row(buf_.params, "cells-params", MemoryKind::Upload);
    row(buf_.objects, "cells-objects", MemoryKind::Upload);
    row(buf_.object_flags, "cells-object-flags", MemoryKind::Upload);
    row(buf_.pair_mask, "cells-pair-mask", MemoryKind::Upload);
    row(buf_.projection, "cells-projection", MemoryKind::Upload);
    row(buf_.header, "cells-header", MemoryKind::DeviceLocal);
    row(buf_.header_rb, "cells-header-readback", MemoryKind::Readback);
    row(buf_.triangles, "cells-triangles", MemoryKind::DeviceLocal);
    row(buf_.geometry, "cells-geometry", MemoryKind::DeviceLocal);
    row(buf_.counts, "cells-counts", MemoryKind::DeviceLocal);
    row(buf_.offsets, "cells-offsets", MemoryKind::DeviceLocal);
    row(buf_.block_sums, "cells-block-sums", MemoryKind::DeviceLocal);
    row(buf_.entries, "cells-entries", MemoryKind::DeviceLocal);
    row(buf_.chunk_cells, "cells-chunk-cells", MemoryKind::DeviceLocal);
    row(buf_.big_items, "cells-big-items", MemoryKind::DeviceLocal);
    row(buf_.deep_items, "cells-deep-items", MemoryKind::DeviceLocal);
    row(buf_.sorted, "cells-sorted", MemoryKind::DeviceLocal);
    row(buf_.candidates, "cells-candidates", MemoryKind::DeviceLocal);
    row(buf_.survivors, "cells-survivors", MemoryKind::Readback);  // or DeviceLocal (ensureBuffers)
    row(buf_.args, "cells-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    row(buf_.gpu_triangles, "cells-gpu-triangles", MemoryKind::Readback);
    row(buf_.marks, "cells-marks", MemoryKind::DeviceLocal);
    row(buf_.exact_queue, "cells-exact-queue", MemoryKind::DeviceLocal);
}

std::uint64_t CellStage::roundedCells(std::uint64_t exact) {
    const std::uint64_t step = std::max<std::uint64_t>(1, (std::uint64_t{1} << (std::bit_width(exact) - 1)) / 16);
    return (exact + step - 1) / step * step;
}

std::uint64_t CellStage::recordedCells() const {
    const std::uint64_t rounded = roundedCells(std::uint64_t(resolution_) * resolution_);
    // What all three per-cell buffers hold (ensureBuffers reserves them together).
    const std::uint64_t held = std::min({buf_.counts->size() / 4, buf_.offsets->size() / 4 - 1, buf_.block_sums->size() / 4 * gpu::kCellsScanBlock});
    if (held >= rounded && held <= kRecordedCellsSlack * rounded) return held;
    // The most cells a recent run needed within the band (a run far larger is left out):
    // the same for every run of a scene that swings within a range narrower than the band.
    std::uint64_t most = rounded;
    for (const std::uint64_t c : recent_cells_)
        if (c > most && c <= kRecordedCellsSlack * rounded) most = c;
    return std::min(held, most);
}

Result<void> CellStage::ensureBuffers() {
    using vk::MemoryKind;
    const VkDeviceSize cells = roundedCells(VkDeviceSize(resolution_) * resolution_);
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    const VkDeviceSize objects = objects_.size();
    // Deep items: one per cell deeper than kCellsSmallCell, or ceil(k / kCellsGroupSize) for
    // cells of k > kCellsDeepShared entries; either way at most 2 k / kCellsSmallCell.
    static_assert(gpu::kCellsDeepShared >= 4 * gpu::kCellsGroupSize && gpu::kCellsSmallCell >= gpu::kCellsGroupSize);
    const VkDeviceSize deep = 2 * VkDeviceSize(capacity_.entries) / gpu::kCellsSmallCell + 1;
    // The exact queue, for queued runs only, holds a pair chunk's candidates at most (the
    // pair pass queues only those of its chunk, the exact pass empties it before the next):
    // it cannot overflow.
    const VkDeviceSize exact_queue = exactQueued() ? std::min<VkDeviceSize>(capacity_.candidates, pair_chunk_) : 0;
    const MemoryKind survivors_kind = survivors_on_device_ ? MemoryKind::DeviceLocal : MemoryKind::Readback;
    const RowSize plan[] = {
        rowSize(buf_.params, sizeof(gpu::CellsParams), MemoryKind::Upload),
        rowSize(buf_.objects, objects * sizeof(gpu::ObjectGpu), MemoryKind::Upload),
        rowSize(buf_.object_flags, objects * 4, MemoryKind::Upload),
        rowSize(buf_.pair_mask, (objects * objects + 31) / 32 * 4, MemoryKind::Upload),
        rowSize(buf_.projection, sizeof(gpu::Projection), MemoryKind::Upload),
        rowSize(buf_.header, sizeof(gpu::CellsHeader), MemoryKind::DeviceLocal),
        rowSize(buf_.header_rb, sizeof(gpu::CellsHeader), MemoryKind::Readback),
        rowSize(buf_.triangles, tris * sizeof(gpu::CellsTriangle), MemoryKind::DeviceLocal),
        rowSize(buf_.geometry, tris * sizeof(gpu::CellsGeometry), MemoryKind::DeviceLocal),
        rowSize(buf_.counts, cells * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.offsets, (cells + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.block_sums, (cells + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.entries, VkDeviceSize(capacity_.entries) * sizeof(gpu::CellsEntry), MemoryKind::DeviceLocal),
        rowSize(buf_.chunk_cells, (VkDeviceSize(capacity_.entries) / gpu::kCellsEntryChunk + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.big_items, VkDeviceSize(capacity_.items) * 8, MemoryKind::DeviceLocal),
        rowSize(buf_.deep_items, deep * 8, MemoryKind::DeviceLocal),
        // Scenes without huge cells never grow it past its first few elements.
        rowSize(buf_.sorted, VkDeviceSize(std::max(capacity_.sorted, 16u)) * 8, MemoryKind::DeviceLocal),
        rowSize(buf_.candidates, VkDeviceSize(capacity_.candidates) * sizeof(gpu::CellsCandidate), MemoryKind::DeviceLocal),
        rowSize(buf_.survivors, VkDeviceSize(capacity_.survivors) * 8, survivors_kind),
        rowSize(buf_.args, gpu::kCellsArgsCount * 12, MemoryKind::DeviceLocal),
        rowSize(buf_.gpu_triangles, has_download_ ? VkDeviceSize(capacity_.gpu_triangles) * sizeof(GpuTriangle) : 0, MemoryKind::Readback),
        rowSize(buf_.marks, has_download_ ? (tris + 31) / 32 * 4 : 0, MemoryKind::DeviceLocal),
        rowSize(buf_.exact_queue, exact_queue * 8, MemoryKind::DeviceLocal),
    };
    const std::string what = "cell stage: resolution " + std::to_string(resolution_) + " with " + std::to_string(triangles_) + " triangles";
    if (auto ok = table_->reserve(*device_, plan, what); !ok) return ok;
    // The shaders load and store triangles, geometry and entries as 16-byte vectors
    // (buffer_reference_align in cells_common.glsl.inc). Buffers start at the device's
    // storage alignment, which Vulkan does not bound from below: check.
    for (const auto& [buffer, name] : {std::pair{buf_.triangles, "cells-triangles"}, std::pair{buf_.geometry, "cells-geometry"},
                                       std::pair{buf_.entries, "cells-entries"}})
        if (buffer->address() % 16 != 0)
            return Error(ErrorCode::UnsupportedFeature, std::string("cell stage: the device placed '") + name + "' at address " +
                                                            std::to_string(buffer->address()) + ", not a multiple of 16 bytes");
    return {};
}

}  // namespace vkcollide::passes
