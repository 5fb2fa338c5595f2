// The contact stage: object-level contacts of closed objects from parallel rays
// (DetectSettings::contacts.objects, docs/contacts.md). A follow-up stage of a detection's
// broad phase (broad/follow_up.hpp): it runs after the broad phase was collected, on that
// run's objects as uploaded, on its executor, its buffers rows of its table, with rays of
// its own, because it needs what the broad phase does not keep: every hit of every closed
// object along a ray, sorted, at a resolution of the region where objects overlap (not of
// the scene).
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
// Not thread-safe; one per broad phase (BroadPhase::followUp). Buffers only grow.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "broad/follow_up.hpp"
#include "contacts/contact_grid.hpp"
#include "contacts/contacts.h"

namespace vkcollide::passes {

// What a run needs beside the broad phase's objects (open ones are skipped).
struct ContactInput {
    std::array<float, 3> direction{0, 0, 1}; // of the rays (any length > 0)
    std::uint32_t resolution = gpu::kDefaultContactResolution;  // rays across the region's longer side
    // Whether objects a < b (run indices) may collide; empty: all may.
    std::function<bool(std::uint32_t a, std::uint32_t b)> may_collide;
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

class ContactStage final : public FollowUpStage {
public:
    // The factory BroadPhase::followUp takes.
    static Result<std::unique_ptr<FollowUpStage>> create(vk::Device& device, BufferTable& io_table);
    // The next run's input; the run is BroadPhase::runFollowUp's. Its errors:
    // InvalidArgument (resolution out of range, naming contacts.resolution), OutOfMemory
    // (ray lists beyond the device's memory or kMaxListBytes), Timeout, DeviceLost.
    void setInput(ContactInput input) { in_ = std::move(input); }
    // The last run's result.
    const ContactStageResult& result() const noexcept { return out_; }

    const char* name() const noexcept override { return "the contact stage"; }
    Result<Collected> begin(const RunView& run) override;
    void record(graph::Graph& g, const RunView& run) override;
    Result<Collected> collect(const RunView& run, const graph::ExecutionReport& report) override;

private:
    ContactStage(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}
    void addRows();
    Result<void> reserve(std::initializer_list<RowSize> sizes);
    void recordBounds(graph::Graph& g);
    void recordMain(graph::Graph& g);
    std::vector<std::array<float, 6>> readBoxes() const;
    // After submission 1: candidates, grid, pair table; Done when no pair is a candidate.
    Result<Collected> afterBounds(const RunView& run);
    // Sizes the ray lists and the tile list for the next submission 2.
    Result<void> prepareMain();
    void readContacts(const gpu::ContactsHeader& header);

    vk::Device* device_;
    BufferTable* table_;
    struct Pipelines {
        vk::Pipeline bounds, setup, tiles, walk;
    } pipes_;
    struct Rows {
        TableRow params, active, bounds, bounds_rb, triangles, items, counts, entries;
        TableRow table_init, table, header, args, readback;
    } rows_;
    ContactInput in_;
    ContactStageResult out_;
    enum class Step { Bounds, Main } step_ = Step::Bounds;
    ContactGrid grid_;
    gpu::ContactsParams params_{};
    std::uint32_t objects_ = 0;
    std::uint32_t table_size_ = 0;
    std::uint32_t layers_ = 16;          // slots per ray (grows, kept between runs)
    std::uint32_t item_capacity_ = 4096; // tile items (grows)
};

// The open-addressing hash of an object pair, as the shaders compute it (findPair).
std::uint32_t contactPairHash(std::uint32_t a, std::uint32_t b);

}  // namespace vkcollide::passes
