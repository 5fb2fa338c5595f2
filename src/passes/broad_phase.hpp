// The GPU broad phase (paper passes 1-4) on the render graph:
//   1. object sampling: bounds -> fit -> depth complexity -> peeling steps + classification
//   2. ray merging: the ray-bundle mipmap
//   3. primitive separation: each triangle keeps (bundles under its corners) ∩ (its box)
//   4. packing: paper count/shift/move or a scan compaction, into a host-visible buffer
// Two submissions per run: the first measures depth complexity (the host reads it to
// choose the number of peeling steps), the second does the rest.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "broadphase.h"
#include "graph/executor.hpp"
#include "passes/compute_sampling.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/types.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

using vkcollide::Coverage;
using vkcollide::PackingMethod;

// A mesh as the GPU sees it. Addresses come from buffers created with
// SHADER_DEVICE_ADDRESS usage; positions are three floats at `vertices + i * stride`.
// 16-bit index data must be readable in whole 4-byte words (pad the buffer by 2 bytes).
struct GpuMesh {
    VkDeviceAddress vertices = 0;
    std::uint32_t vertex_stride = 12;
    std::uint32_t vertex_count = 0;
    VkDeviceAddress indices = 0;
    bool index16 = false;
    std::uint32_t triangle_count = 0;
    Transform3x4 transform = kIdentity3x4;  // row-major 3x4 object->world
    bool open = false;
    // Geometry only the GPU holds (an engine's buffers): each run checks its indices and
    // positions there (host meshes are checked before upload).
    bool check_on_gpu = false;
};

struct BroadPhaseSettings {
    std::uint32_t resolution = 256;                 // power of two, 4..16384
    std::array<float, 3> direction{0, 0, 1};        // projection direction (any length > 0)
    std::uint32_t layer_cap = 0;                    // 0: peel every layer
    bool dual = false;                              // front and back peeling at once
    PackingMethod packing = PackingMethod::Scan;
    float open_epsilon = 0;                         // world units; open-surface depth proximity
    float closed_epsilon = 0;                       // world units; closed surfaces this close touch
    Coverage coverage = Coverage::Centre;           // never Best (the API resolves it)
    float fit_margin = gpu::kFitMargin;             // relative margin of the automatic fit
    bool keep_ray_image = false;                    // read back the collision-ray image
    // Sample this world box instead of fitting the scene: min x,y,z then max x,y,z.
    std::optional<std::array<float, 6>> region;
    // Object sampling on the graphics pipeline or in compute (same rays and records);
    // Auto picks per device and scene (chooseSamplingBackend in compute_sampling.hpp).
    SamplingBackend backend = SamplingBackend::Auto;
    ComputeSamplingTuning compute;
};

struct BroadPhaseResult {
    std::vector<CandidateTriangle> records;  // in global triangle order
    std::vector<std::uint8_t> ray_image;     // N*N, row-major, 1 = collision ray (if kept)
    std::uint32_t depth_complexity = 0;
    std::uint32_t layers = 0;                // layers peeled: min(depth complexity, cap)
    std::uint32_t peel_steps = 0;            // peeling passes recorded (half with dual)
    std::uint32_t collision_rays = 0;
    std::uint32_t triangles = 0;
    // The sampling projection used (world -> [0,1]^2 image, depth): the caller's region, or
    // the fit repeated on the host from the bounds the GPU measured (passes/projection.hpp).
    gpu::Projection projection{};
    std::vector<graph::PassTiming> passes;   // both submissions, in order
    SamplingBackend backend = SamplingBackend::Raster;  // the one that ran (never Auto)
    std::string backend_reason;              // one line: why
    std::uint64_t fragments = 0;             // covered pixels summed over all triangles
    std::uint32_t compute_small = 0, compute_big = 0, compute_items = 0;  // compute backend's triangle lists
    bool compute_fragment_lists = false;     // compute backend peeled from per-ray fragment lists
    double sampling_ms = 0, merging_ms = 0, separation_ms = 0, packing_ms = 0, readback_ms = 0;
};

// Device memory the broad phase needs for a resolution and triangle count (bytes, all buffers).
VkDeviceSize broadPhaseMemory(std::uint32_t resolution, std::uint32_t triangles, std::uint32_t objects);

class BroadPhase {
public:
    static Result<std::unique_ptr<BroadPhase>> create(vk::Device& device);
    // Two submissions with a host wait between them: the first measures the depth
    // complexity, the second peels exactly that many layers (or the cap).
    [[nodiscard]] Result<BroadPhaseResult> run(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings);
    // One submission that peels `layers` layers (at most the cap) whatever the depth
    // complexity turns out to be: rays with more layers become collision rays
    // (conservative). collect() waits and reads the result; it reports the depth
    // complexity measured in the same submission.
    [[nodiscard]] Result<void> submit(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings, std::uint32_t layers);
    [[nodiscard]] Result<BroadPhaseResult> collect();
    bool pending() const noexcept { return pending_; }
    // After an InvalidMesh error from the GPU input check: the objects it named (run
    // indices), each with its own error; at most one per kind of problem, so others may be bad too.
    struct BadObject {
        std::uint32_t object;
        Error error;
    };
    const std::vector<BadObject>& badObjects() const noexcept { return bad_objects_; }
    // Bytes of the GPU buffers the broad phase holds (its own, not the meshes').
    std::uint64_t memoryBytes() const noexcept;

private:
    explicit BroadPhase(vk::Device& device) : device_(&device), executor_(device) {}
    struct Resources {
        graph::ResourceId header, header_rb, counts, projection, front, back, state, bundles, sparse, records, scratch, rays;
        ComputeSampling::Ids compute;  // the compute backend's buffers, when it runs
    };
    // Checks the run's inputs, sizes the buffers, uploads objects, frame and projection.
    Result<void> prepare(std::span<const GpuMesh> meshes, const BroadPhaseSettings& settings);
    Resources importResources(graph::Graph& g, bool full);
    void recordMeasure(graph::Graph& g, const Resources& r) const;
    void recordPeelToPack(graph::Graph& g, const Resources& r, std::uint32_t steps) const;
    // The small result header, copied where the host can read it.
    void addHeaderReadback(graph::Graph& g, graph::ResourceId header, graph::ResourceId header_rb) const;
    void drawObject(const graph::PassContext& pc, const vk::Pipeline& plain, const vk::Pipeline& conservative,
                    VkDeviceAddress frame_addr, std::uint32_t object, std::uint32_t step, bool count_pass) const;
    gpu::Header readHeader();
    gpu::Projection hostProjection(const gpu::Header& h) const;
    Result<void> checkInputs(const gpu::Header& header);
    static void addTimings(BroadPhaseResult& result, const graph::ExecutionReport& report);
    bool computeBackend() const noexcept { return frame_.backend.backend == SamplingBackend::Compute; }
    Result<void> ensureBuffers(std::uint32_t resolution, std::uint32_t triangles, std::uint32_t objects, bool ray_image);

    vk::Device* device_;
    graph::Executor executor_;
    bool pending_ = false;
    std::vector<BadObject> bad_objects_;
    // The run being recorded or in flight.
    struct Prepared {
        gpu::Frame frame{};
        BroadPhaseSettings settings;
        std::vector<GpuMesh> meshes;
        bool any_gpu_check = false;
        BackendChoice backend;
        std::uint32_t measured_layers = 0, steps = 0;
        BroadPhaseResult first;  // timings of a separate measuring submission
    } frame_;
    std::unique_ptr<ComputeSampling> compute_;  // created on first use
    std::uint32_t last_triangles_ = 0;          // the previous run's scene, for Auto
    double last_fragments_per_triangle_ = -1;
    struct Pipelines {
        vk::Pipeline validate, bounds, fit, count, peel, reduce_max, peel_init, classify, finalize, merge, separate;
        vk::Pipeline count_conservative;  // only where the device rasterises conservatively
        vk::Pipeline pack_rowcount, scan_counts, pack_shift, pack_move, scan_blocksum, scan_scatter;
    } pipes_;
    struct Buffers {
        std::uint32_t resolution = 0, triangles = 0, objects = 0;
        vk::Buffer frame, objects_buf, projection, header, header_rb, counts, front, back, state, bundles, sparse,
            records, scratch, ray_image;
    } buf_;
};

}  // namespace vkcollide::passes
