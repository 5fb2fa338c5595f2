#include "broad/buffer_table.hpp"

#include <algorithm>
#include <cstdio>

namespace vkcollide::passes {
namespace {

std::string gibText(VkDeviceSize bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f GiB", double(bytes) / double(1ull << 30));
    return buf;
}

}  // namespace

BufferId BufferTable::add(const BufferRow& row) {
    entries_.push_back({row, {}, 0, row.kind});
    return static_cast<BufferId>(entries_.size() - 1);
}

TableRow BufferTable::addOwned(const char* name, vk::MemoryKind kind, VkBufferUsageFlags usage, bool engine_reads) {
    BufferRow row{name, kind, nullptr};
    row.usage = usage;
    row.engine_reads = engine_reads;
    const BufferId id = add(row);
    return {id, &entries_[id].buffer, name};
}

std::vector<VkDeviceSize> BufferTable::plan(const RunShape& shape) const {
    std::vector<VkDeviceSize> sizes;
    for (const Entry& e : entries_) sizes.push_back(e.row.size ? e.row.size(shape) : e.run_size);
    return sizes;
}

VkDeviceSize BufferTable::planBytes(const RunShape& shape) const {
    VkDeviceSize total = 0;
    for (VkDeviceSize s : plan(shape)) total += s;
    return total;
}

// Refuse what the device cannot hold before allocating anything: a clear OutOfMemory
// instead of a driver failure half-way (or a validation error for a buffer above
// maxBufferSize). The heap size is an upper bound: the engine's own allocations live
// there too, and vkAllocateMemory may still fail (OutOfMemory).
Result<void> BufferTable::checkFits(const vk::Device& device, const std::vector<VkDeviceSize>& sizes, const std::string& what) const {
    std::vector<VkDeviceSize> per_heap(device.memory.memoryHeapCount, 0);
    VkDeviceSize total = 0;
    const VkDeviceSize limit = std::min(device.max_buffer_size, device.max_allocation_size);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        const Entry& e = entries_[i];
        if (sizes[i] > limit)
            return Error(ErrorCode::OutOfMemory, what + " needs a '" + e.row.name + "' buffer of " + gibText(sizes[i]) +
                                                     ", more than the device's largest buffer (" + gibText(limit) +
                                                     "): lower the resolution or split the scene");
        const VkMemoryPropertyFlags required =
            e.kind == vk::MemoryKind::DeviceLocal ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
        if (auto type = device.findMemoryType(~0u, required)) per_heap[device.memory.memoryTypes[*type].heapIndex] += sizes[i];
        total += sizes[i];
    }
    for (std::uint32_t h = 0; h < per_heap.size(); ++h)
        if (per_heap[h] > device.memory.memoryHeaps[h].size)
            return Error(ErrorCode::OutOfMemory, what + " needs " + gibText(total) + " of device memory, more than the " +
                                                     gibText(device.memory.memoryHeaps[h].size) +
                                                     " memory heap holds: lower the resolution or split the scene");
    return {};
}

Result<void> BufferTable::grow(vk::Device& device, std::size_t i, VkDeviceSize bytes) {
    Entry& e = entries_[i];
    e.run_size = bytes;
    if (bytes == 0 || (e.buffer.valid() && e.buffer.size() >= bytes)) return {};
    drop(e);  // free the smaller one first: peak memory is the new size, not both
    auto r = vk::Buffer::create(device, bytes, e.row.usage, e.kind, e.row.name);
    if (!r) return r.error();
    e.buffer = std::move(*r);
    return {};
}

void BufferTable::drop(Entry& e) {
    if (e.row.engine_reads && e.buffer.valid()) replaced_new_.push_back(std::move(e.buffer));
    e.buffer.reset();
}

void BufferTable::retire() {
    replaced_old_ = std::move(replaced_new_);
    replaced_new_.clear();
}

Result<void> BufferTable::reserve(vk::Device& device, const RunShape& shape) {
    const std::vector<VkDeviceSize> sizes = plan(shape);
    const std::string what = "resolution " + std::to_string(shape.resolution) + " with " + std::to_string(shape.triangles) + " triangles";
    if (auto ok = checkFits(device, sizes, what); !ok) return ok;
    for (std::size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].row.size)
            if (auto ok = grow(device, i, sizes[i]); !ok) return ok;
    return {};
}

Result<void> BufferTable::reserve(vk::Device& device, std::span<const RowSize> rows, const std::string& what) {
    std::vector<VkDeviceSize> sizes(entries_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i) sizes[i] = entries_[i].run_size;
    for (const RowSize& r : rows) {
        Entry& e = entries_.at(r.id);
        if (e.kind != r.kind) {
            drop(e);  // a buffer in the other kind of memory is made again
            e.kind = r.kind;
        }
        sizes[r.id] = r.bytes;
    }
    if (auto ok = checkFits(device, sizes, what); !ok) return ok;
    for (const RowSize& r : rows)
        if (auto ok = grow(device, r.id, r.bytes); !ok) return ok;
    return {};
}

void BufferTable::fillFrame(gpu::Frame& frame) const {
    for (const Entry& e : entries_)
        if (e.row.frame_slot) frame.*e.row.frame_slot = e.run_size > 0 ? e.buffer.address() : 0;
}

GraphBuffers BufferTable::import(graph::Graph& g) {
    GraphBuffers out;
    out.ids.resize(entries_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        Entry& e = entries_[i];
        if (e.row.size && e.run_size > 0) out.ids[i] = g.importBuffer(e.row.name, e.buffer, e.row.host_readback);
    }
    return out;
}

std::vector<std::pair<BufferId, VkDeviceSize>> BufferTable::cleared() const {
    std::vector<std::pair<BufferId, VkDeviceSize>> out;
    for (std::size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].row.cleared && entries_[i].run_size > 0) out.push_back({static_cast<BufferId>(i), entries_[i].run_size});
    return out;
}

std::uint64_t BufferTable::bytes() const noexcept {
    std::uint64_t n = 0;
    for (const Entry& e : entries_) n += e.buffer.valid() ? e.buffer.memoryBytes() : 0;
    for (const auto* list : {&replaced_new_, &replaced_old_})
        for (const vk::Buffer& b : *list) n += b.memoryBytes();
    return n;
}

}  // namespace vkcollide::passes
