// Dispatch helpers every broad-phase stage shares: push constants, workgroup counts, and
// dispatches laid out in rows within the device's limits.
#pragma once

#include <cstdint>
#include <span>

#include "common/broadphase.h"
#include "graph/pass_context.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

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
// The three dispatches of an exclusive scan by spirv/cells/block_scan.glsl.inc (block sums
// over `blocks` workgroups, the carry in one, the offsets), as steps first_step,
// first_step + 1 and first_step + 2 of `p` with Push.level `level`, each followed by a
// barrier.
void recordBlockScan(const graph::PassContext& pc, const vk::Pipeline& p, VkDeviceAddress frame, std::uint64_t blocks,
                     std::uint32_t max_x, std::uint32_t first_step, std::uint32_t level);
// The same for `items` invocations of `size` per workgroup.
void dispatchItems(const graph::PassContext& pc, std::uint64_t items, std::uint32_t size = gpu::kGroupSize);
// The (x, y) layout dispatchGroups records for `groups` under the limits (x, y); {0, 0}
// when even x * y workgroups are too few (never for the counts vkcollide dispatches:
// the guaranteed 65535^2 covers 2^32 items of 1 per group).
struct DispatchShape {
    std::uint32_t x = 0, y = 0;
};
DispatchShape dispatchShape(std::uint64_t groups, std::uint32_t max_x, std::uint32_t max_y);
// Writes the engine submitted earlier (vertex buffers it skinned or simulated) become
// visible to everything recorded after this barrier: the first command of a run.
void makeEngineWritesVisible(const graph::PassContext& pc);
// A compute pipeline from embedded SPIR-V with the broad phase's push constants (gpu::Push).
Result<void> makeCompute(vk::Device& device, vk::Pipeline& out, std::span<const std::uint32_t> spirv, const char* name);

}  // namespace vkcollide::passes
