// What every broad-phase stage shares: the stage a pass belongs to (for its GPU time), the
// run being recorded, the broad phase's buffers as graph resources, and the dispatch
// helpers. A stage is a class that owns its pipelines and records its passes into a graph
// (docs/rooms.md lists them).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "common/broadphase.h"
#include "graph/executor.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

// The stage a pass belongs to; its GPU time is summed into the matching BroadPhaseResult
// field (addStageTime). A new stage adds a value here and a field there.
enum class Stage : graph::StageTag {
    None = 0,    // not timed into a stage (graph passes that declared nothing)
    Prepare,     // clear, GPU input checks, bounds and fit (timed with sampling, as the paper does)
    Sampling,    // depth complexity, peeling, classification (paper pass 1)
    Merging,     // the ray-bundle mipmap (pass 2)
    Separation,  // kept boxes per triangle (pass 3)
    Packing,     // compaction into the readback buffer (pass 4)
    Readback,    // copies the host reads
    // The cell pair stage (ReliableMethod, broad/cells/):
    Footprints,  // setup, big triangles, scan, fill: every triangle in the cells it may touch
    Pairing,     // the sweep of every cell: candidate pairs
    Filtering,   // canonical-cell dedupe, the double-precision filter, engine triangles' vertices
    Sorting,     // device pairs: the survivors sorted on the GPU (cells/device_pairs.hpp)
    Proximity,   // the proximity pass (src/proximity/)
};
const char* toString(Stage stage) noexcept;
// Adds one pass's GPU time to its stage's field of `io_result`.
void addStageTime(BroadPhaseResult& io_result, const graph::PassTiming& pass);

// Index of a buffer in the broad phase's BufferTable.
using BufferId = std::uint32_t;

// The run being recorded. Refers to the broad phase's own copy of the run's inputs, which
// lives until the next prepare(), so record callbacks (run at submission, after the
// recording functions returned) may capture it by value.
// Vertices per dispatch of the bounds pass at most (gpu::ObjectGpu::vertex_base counts
// within a batch and is 32-bit): one batch unless a scene has more.
inline constexpr std::uint64_t kBoundsBatchVertices = std::uint64_t{1} << 31;

struct RunView {
    const BroadPhaseSettings& settings;
    std::span<const GpuMesh> meshes;
    const gpu::Frame& frame;  // as uploaded
    VkDeviceAddress frame_address = 0;
    bool any_gpu_check = false;  // some mesh has check_on_gpu
    std::span<const gpu::ObjectGpu> objects;  // the meshes as uploaded (triangle bases, transforms)
};

// The table's buffers as resources of one graph (BufferTable::import); invalid ids for
// buffers this run does not use.
struct GraphBuffers {
    std::vector<graph::ResourceId> ids;
    graph::ResourceId operator[](BufferId b) const { return ids.at(b); }
};

// Adds a pass that declares its stage.
graph::PassBuilder addPass(graph::Graph& g, std::string name, graph::PassKind kind, Stage stage);
// Binds `p` and pushes gpu::Push for one dispatch or draw.
void bindAndPush(const graph::PassContext& pc, const vk::Pipeline& p, VkDeviceAddress frame, std::uint32_t object = 0,
                 std::uint32_t step = 0, std::uint32_t level = 0, std::uint32_t coverage = gpu::kCoverageCentre);
// Workgroups for `items` invocations.
std::uint32_t groups(std::uint64_t items, std::uint32_t size = gpu::kGroupSize);
// Records a compute dispatch of `groups` workgroups (vkCmdDispatch), laid out in rows so
// that no dimension exceeds the device's maxComputeWorkGroupCount (a 1D dispatch of 65536
// groups is already past the guaranteed minimum: resolution 4096 per pixel, 16.7M
// triangles per triangle). The shader reads its indices with globalIndex() and
// groupIndex() (spirv/common/dispatch.glsl.inc) and ignores those past its count: the last row
// may be partly beyond it.
void dispatchGroups(const graph::PassContext& pc, std::uint64_t groups);
// The same in rows of at most `max_x` workgroups (at most the device's limit): for stages
// that also give their shaders the row width (their indirect arguments use it too).
void dispatchGroups(const graph::PassContext& pc, std::uint64_t groups, std::uint32_t max_x);
// The same for `items` invocations of `size` per workgroup.
void dispatchItems(const graph::PassContext& pc, std::uint64_t items, std::uint32_t size = gpu::kGroupSize);
// The (x, y) layout dispatchGroups records for `groups` under the limits (x, y); {0, 0}
// when even x * y workgroups are too few (never for the counts vkcollide dispatches:
// the guaranteed 65535^2 covers 2^32 items of 1 per group).
struct DispatchShape {
    std::uint32_t x = 0, y = 0;
};
DispatchShape dispatchShape(std::uint64_t groups, std::uint32_t max_x, std::uint32_t max_y);
// A compute pipeline from embedded SPIR-V with the broad phase's push constants (gpu::Push).
Result<void> makeCompute(vk::Device& device, vk::Pipeline& out, std::span<const std::uint32_t> spirv, const char* name);

}  // namespace vkcollide::passes
