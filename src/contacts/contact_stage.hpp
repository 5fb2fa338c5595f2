// The contact stage: object-level contacts of closed objects from parallel rays
// (DetectSettings::contacts.objects, docs/contacts.md). It runs after a detection's broad phase on
// its own executor, with its own rays, because it needs what the broad phase does not
// keep: every hit of every closed object along a ray, sorted, at a resolution of the
// region where objects overlap (not of the scene).
//
// Why not the compute sampling backend's fragment lists: they are built at the broad
// phase's resolution over the whole scene, hold 64-bit keys (depth bits and triangle id,
// no normal), exist only for the Peeling method with the compute backend, and are
// slot-major with a layer budget chosen for peeling. This stage reuses its coverage idea
// (edge functions at pixel centres, small triangles per invocation, big ones in 8x8 tiles)
// with its own grid and a tie rule of its own (contacts_common.glsl.inc).
//
//   submission 1  contacts-bounds    per triangle of closed objects: world boxes per object
//   host          candidate pairs: closed, allowed, boxes overlapping (sweep on x); the
//                 grid: square pixels over the union of those pairs' box overlaps, seen
//                 along `direction`; the pair table (open addressing, keys written here)
//   submission 2  contacts-clear     counts, header, table
//                 contacts-setup     per triangle: grid-space record; small ones drawn
//                 contacts-tiles     per 8x8 tile of a big triangle (indirect)
//                 contacts-walk      per ray: sort, walk; sums (step 0), extent (step 1)
//                 contacts-readback  header and table to host memory
// A ray list or the tile list too small: the GPU flags it with the size needed, the host
// grows the buffer and runs submission 2 again (never an access out of bounds).
//
// Not thread-safe; one instance per detection. Buffers only grow.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "contacts/contacts.h"
#include "graph/executor.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

struct ContactInput {
    std::span<const GpuMesh> meshes;         // the run's objects (open ones are skipped)
    std::array<float, 3> direction{0, 0, 1}; // of the rays (any length > 0)
    std::uint32_t resolution = gpu::kDefaultContactResolution;  // rays across the region's longer side
    // Whether objects a < b (indices in meshes) may collide; empty: all may.
    std::function<bool(std::uint32_t a, std::uint32_t b)> may_collide;
    std::uint64_t timeout_ns = graph::kDefaultTimeoutNs;  // each submission's longest wait
    // When set, every submission's wait ends by then instead (a detection's timeout_ms).
    std::optional<std::chrono::steady_clock::time_point> deadline;
    std::uint64_t waitNs() const { return graph::waitNs(timeout_ns, deadline); }
    Error timeoutOf(Error e) const { return graph::timeoutOfDetection(timeout_ns, deadline.has_value(), std::move(e)); }
};

// One candidate pair's sums, in world units.
struct StageContact {
    std::uint32_t a = 0, b = 0;      // indices in meshes, a < b
    double volume = 0;
    std::array<double, 3> normal{};  // unit, from a into b; zero when undefined
    double depth = 0;
    std::array<double, 3> point{};   // centroid (volume > 0) or the middle of the boxes' overlap
};

struct ContactStageResult {
    std::vector<StageContact> contacts;   // candidate pairs with sampled volume > 0, sorted (a, b)
    // Every candidate pair (closed, allowed, boxes overlapping), sorted, with the middle
    // of its boxes' overlap (for pairs whose triangles intersect but no ray saw a volume).
    std::vector<std::array<std::uint32_t, 2>> candidates;
    std::vector<std::array<double, 3>> candidate_middles;
    std::uint32_t width = 0, height = 0;  // rays
    std::uint32_t layers = 0;             // entry slots per ray of the last run
    std::uint32_t nested_rays = 0, overlap_rays = 0, runs = 0;
    std::uint64_t fragments = 0;
    double gpu_ms = 0;                    // both submissions (timestamps)
};

class ContactStage {
public:
    static Result<std::unique_ptr<ContactStage>> create(vk::Device& device);
    // Runs both submissions and waits. Errors: InvalidArgument (resolution out of range,
    // naming contacts.resolution), OutOfMemory (ray lists beyond the device's memory),
    // Timeout, DeviceLost.
    [[nodiscard]] Result<ContactStageResult> run(const ContactInput& input);
    std::uint64_t memoryBytes() const noexcept;

private:
    explicit ContactStage(vk::Device& device) : device_(&device), executor_(device) {}
    Result<void> ensure(vk::Buffer& b, VkDeviceSize bytes, vk::MemoryKind kind, const char* name);
    Result<std::vector<std::array<float, 6>>> measureBoxes(const ContactInput& in);
    void recordMain(graph::Graph& g);

    vk::Device* device_;
    struct Pipelines {
        vk::Pipeline bounds, setup, tiles, walk;
    } pipes_;
    struct Buffers {
        vk::Buffer params, objects, active, bounds, bounds_rb, triangles, items, counts, entries;
        vk::Buffer table_init, table, header, args, readback;
    } buf_;
    std::vector<gpu::ObjectGpu> objects_;
    gpu::ContactsParams params_{};
    std::uint32_t table_size_ = 0;
    std::uint32_t layers_ = 16;          // slots per ray (grows, kept between runs)
    std::uint32_t item_capacity_ = 4096; // tile items (grows)
    double last_gpu_ms_ = 0;
    graph::Executor executor_;           // last: destroyed first, waits for work in flight
};

// The open-addressing hash of an object pair, as the shaders compute it (findPair).
std::uint32_t contactPairHash(std::uint32_t a, std::uint32_t b);

}  // namespace vkcollide::passes
