// Every buffer the broad phase owns, in one table: each row says how big the buffer is for a
// run, which memory it lives in, where the shaders find its address (a gpu::Frame field) and
// whether the host reads it after a submission. From the rows, and nowhere else, come the
// memory check before a run, the allocation, the graph imports and the frame's addresses.
//
// The broad phase adds the rows every method needs (frame, objects, projection, header);
// a method adds its own when it is created (PeelingMethod::addRows). Buffers only grow:
// a run that needs less keeps the bigger buffer.
#pragma once

#include <cstdint>
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
    // Bytes this run needs; 0: not used this run (not allocated, address 0).
    VkDeviceSize (*size)(const RunShape& shape);
    // The gpu::Frame field that holds its address, or null.
    std::uint64_t gpu::Frame::*frame_slot = nullptr;
    // The host reads it after a submission (the graph makes the GPU's writes visible).
    bool host_readback = false;
    // Zeroed at the start of every run (the front stage's clear pass), over the run's size.
    bool cleared = false;
};

class BufferTable {
public:
    BufferId add(const BufferRow& row);

    // Bytes each row needs for `shape`, in row order.
    std::vector<VkDeviceSize> plan(const RunShape& shape) const;
    VkDeviceSize planBytes(const RunShape& shape) const;
    // Refuses (OutOfMemory) what the device cannot hold before allocating anything, then
    // makes every buffer this run uses at least its planned size.
    [[nodiscard]] Result<void> reserve(vk::Device& device, const RunShape& shape);
    // The run's addresses into their frame fields (0 for rows this run does not use).
    void fillFrame(gpu::Frame& io_frame) const;
    // Imports every buffer this run uses into `g`.
    GraphBuffers import(graph::Graph& g);
    // The run's rows that the front stage zeroes, with their sizes.
    std::vector<std::pair<BufferId, VkDeviceSize>> cleared() const;

    vk::Buffer& buffer(BufferId id) { return entries_.at(id).buffer; }
    const vk::Buffer& buffer(BufferId id) const { return entries_.at(id).buffer; }
    bool used(BufferId id) const { return entries_.at(id).run_size > 0; }
    // Bytes of every buffer held (not only this run's).
    std::uint64_t bytes() const noexcept;

private:
    struct Entry {
        BufferRow row;
        vk::Buffer buffer;
        VkDeviceSize run_size = 0;  // the last reserve()'s plan
    };
    std::vector<Entry> entries_;
};

}  // namespace vkcollide::passes
