// Every buffer the broad phase owns, in one table: each row says how big the buffer is for a
// run, which memory it lives in, where the shaders find its address (a gpu::Frame field) and
// whether the host reads it after a submission. From the rows, and nowhere else, come the
// memory check before a run, the allocation, the graph imports and the frame's addresses.
//
// The broad phase adds the rows every method needs (frame, objects, projection, header);
// a method adds its own when it is created (PeelingMethod::addRows). A stage whose sizes
// come from what the GPU counted (the cell stage's capacities, grown after an overflow)
// adds rows it sizes itself (BufferRow::size null) and reserves them when it knows them;
// the memory check covers every row either way. Buffers only grow: a run that needs less
// keeps the bigger buffer. A row's buffer stays where it is for the table's life, except
// that a grown row the engine reads (device pairs) keeps its old buffer until retire().
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "common/broadphase.h"
#include "vk/resources.hpp"

namespace vkcollide::passes {

// The shape of a run that buffer sizes depend on.
struct RunShape {
    std::uint32_t resolution = 0;
    std::uint32_t triangles = 0;
    std::uint32_t objects = 0;
    bool ray_image = false;  // BroadPhaseSettings::keep_ray_image
    bool depth_aware = false;  // BroadPhaseSettings::depth_aware
};

struct BufferRow {
    const char* name;  // the buffer's debug name and its graph resource name
    vk::MemoryKind kind;
    // Bytes this run needs; 0: not used this run (not allocated, address 0). Null: the
    // row's owner sizes it (reserve() with RowSize) and imports it into its graphs itself.
    VkDeviceSize (*size)(const RunShape& shape);
    // The gpu::Frame field that holds its address, or null.
    std::uint64_t gpu::Frame::*frame_slot = nullptr;
    // The host reads it after a submission (the graph makes the GPU's writes visible).
    bool host_readback = false;
    // Zeroed at the start of every run (the front stage's clear pass), over the run's size.
    bool cleared = false;
    // Usage beyond storage, transfer and device address (e.g. indirect dispatch arguments).
    VkBufferUsageFlags usage = 0;
    // The engine reads it after a run (device pairs): a buffer it replaces is kept until
    // retire() was called twice more, instead of being freed at once.
    bool engine_reads = false;
};

// What an owner-sized row needs for the run: its bytes and, where that changes between
// runs, its memory (a buffer in the other kind is made again).
struct RowSize {
    BufferId id;
    VkDeviceSize bytes;
    vk::MemoryKind kind;
};

// An owner-sized row as its owner holds it: the id, the buffer, which stays in place while
// the table lives, and the row's name (importRow names the graph resource with it).
struct TableRow {
    BufferId id = 0;
    vk::Buffer* buffer = nullptr;
    const char* name = "";
    vk::Buffer* operator->() const noexcept { return buffer; }
    operator vk::Buffer&() const noexcept { return *buffer; }
};

// An owner-sized row into a graph about to be recorded, under its row's name;
// `host_readback` as BufferRow's.
inline graph::ResourceId importRow(graph::Graph& g, const TableRow& row, bool host_readback = false) {
    return g.importBuffer(row.name, *row.buffer, host_readback);
}

// What an owner-sized row needs, at least 16 bytes: every such buffer exists, so its
// address is valid in a run that does not use it.
inline RowSize rowSize(const TableRow& row, VkDeviceSize bytes, vk::MemoryKind kind) {
    return {row.id, bytes < 16 ? VkDeviceSize(16) : bytes, kind};
}

class BufferTable {
public:
    BufferId add(const BufferRow& row);
    // A row its owner sizes (reserve() with RowSize) and imports itself.
    TableRow addOwned(const char* name, vk::MemoryKind kind, VkBufferUsageFlags usage = 0, bool engine_reads = false);
    // At a detection's start: frees the engine-read buffers replaced before the last call,
    // so reads the engine ordered before the next detection never meet a freed buffer.
    void retire();

    // Bytes each row needs for `shape`, in row order.
    std::vector<VkDeviceSize> plan(const RunShape& shape) const;
    VkDeviceSize planBytes(const RunShape& shape) const;
    // Refuses (OutOfMemory) what the device cannot hold before allocating anything, then
    // makes every buffer this run uses at least its planned size. The owner-sized rows
    // count with what they last reserved.
    [[nodiscard]] Result<void> reserve(vk::Device& device, const RunShape& shape);
    // The same for owner-sized rows: `sizes` replaces what they need, every other row
    // counts with its last plan; errors begin with `what` ("cell stage: resolution 64 with
    // 120 triangles").
    [[nodiscard]] Result<void> reserve(vk::Device& device, std::span<const RowSize> sizes, const std::string& what);
    // The run's addresses into their frame fields (0 for rows this run does not use).
    void fillFrame(gpu::Frame& io_frame) const;
    // Imports every buffer this run uses into `g`.
    GraphBuffers import(graph::Graph& g);
    // The run's rows that the front stage zeroes, with their sizes.
    std::vector<std::pair<BufferId, VkDeviceSize>> cleared() const;

    vk::Buffer& buffer(BufferId id) { return entries_.at(id).buffer; }
    const vk::Buffer& buffer(BufferId id) const { return entries_.at(id).buffer; }
    bool used(BufferId id) const { return entries_.at(id).run_size > 0; }
    // Bytes of every buffer held (not only this run's; replaced engine-read ones too).
    std::uint64_t bytes() const noexcept;

private:
    struct Entry {
        BufferRow row;
        vk::Buffer buffer;
        VkDeviceSize run_size = 0;  // the last reserve()'s plan
        vk::MemoryKind kind;        // where the buffer lives (the row's, or its RowSize's)
    };
    // Refuses what the device cannot hold: a buffer above its largest, or more on a heap than it has.
    Result<void> checkFits(const vk::Device& device, const std::vector<VkDeviceSize>& sizes, const std::string& what) const;
    // Makes entry i's buffer at least `bytes` in its kind (freeing the smaller one first).
    Result<void> grow(vk::Device& device, std::size_t i, VkDeviceSize bytes);
    // Replaces entry i's buffer (freed, or kept for retire() when the engine reads it).
    void drop(Entry& e);
    std::deque<Entry> entries_;  // a deque: rows added later leave the others' buffers in place
    // Engine-read buffers replaced since the last retire(), and before it.
    std::vector<vk::Buffer> replaced_new_, replaced_old_;
};

}  // namespace vkcollide::passes
