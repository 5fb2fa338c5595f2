// The one validation gate: every rule the API's input must meet, checked here once, before
// anything is uploaded or recorded. The layers below (src/broad/, src/detect/) assert these rules
// instead of checking them again.
//
// Each check returns the broken rule as an Error whose message does not name the object;
// the world prefixes "object <id> ('<name>'): " once (ObjectRegistry::who).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "broad/broad_phase_types.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::vk {
struct Device;
}

namespace vkcollide::validation {

// Every entry finite.
Result<void> checkTransform(const Transform3x4& transform);
// validateMesh's rules, and fewer than 2^30 triangles.
Result<void> checkHostMesh(const HostMesh& mesh);
// New positions of a host mesh: the same count, every one finite.
Result<void> checkVertices(std::span<const Float3> positions, std::uint32_t vertex_count);
Result<void> checkTypicalEdge(float typical_edge_length);
// A host mesh's object-space box (min x, y, z, max x, y, z) under `transform` within the
// sampling range: every world coordinate, and every product and sum the GPU forms on the
// way (in float), within +-gpu::kMaxWorldCoordinate (LimitExceeded otherwise).
Result<void> checkWorldRange(const std::array<float, 6>& box, const Transform3x4& transform);
// The box of `positions` (at least one).
std::array<float, 6> boxOf(std::span<const Float3> positions);
// The error for a NaN or infinite vertex (checkVertices' and updateVertices' words).
Error nonFiniteVertex(std::size_t index);

// A GpuMeshDesc's layout: handles, counts, format, stride and offset alignment, index type,
// 16-bit reach, and that the declared sizes cover what the counts need (16-bit indices are
// read in whole 4-byte words: the buffer must cover the padding).
Result<void> checkGpuMeshDesc(const GpuMeshDesc& desc);
// setGpuMeshBuffers: the same vertex count, index count, position format and index type.
Result<void> checkSameTopology(const GpuMeshDesc& was, const GpuMeshDesc& now);
// The bytes of each buffer a detection reads from its offset on (the layout's rules met).
VkDeviceSize vertexBytes(const GpuMeshDesc& desc);
VkDeviceSize indexBytes(const GpuMeshDesc& desc);

// Settings after automatic ones are filled in (resolveSettings): method, axes, resolution
// (per method), direction, epsilons, region, and (peeling) coverage and backend against
// each other and the device.
Result<void> checkSettings(const DetectSettings& resolved, const vk::Device& device);
// DetectSettings::reliable.device_pairs and pair_sort Gpu: the reliable method, the exact decision on
// the GPU (shaderFloat64), a capacity within kMaxDevicePairCapacity; host_pairs = false only
// with device_pairs and without contacts (checkSettings calls it).
Result<void> checkDevicePairs(const DetectSettings& resolved, const vk::Device& device);
// DetectSettings::proximity: the reliable method, shaderFloat64, a finite distance in
// [0, 2^60], a capacity within kMaxProximityCapacity (checkSettings calls it).
Result<void> checkProximity(const DetectSettings& resolved, const vk::Device& device);
// `what` (device_pairs, pair_sort Gpu: pairs formed on the GPU for the result) with a pair
// filter the world applies only on the host (no mask kept).
Result<void> checkSortedOnGpuFilter(const std::string& what, bool on, bool filter_on_host_only, std::size_t live_objects);
// The reliable method's limit on an object (host meshes' largest |coordinate| is measured
// when their geometry changes; GPU meshes pass 0 and are checked on the GPU).
Result<void> checkReliableObject(const Transform3x4& transform, float max_abs_position);
// The objects of one detection: at least one, fewer than 2^30 triangles in all.
Result<void> checkScene(std::span<const passes::GpuMesh> meshes);

}  // namespace vkcollide::validation
