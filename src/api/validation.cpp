#include "api/validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "cells/cells.h"
#include "common/broadphase.h"
#include "contacts/contacts.h"
#include "core/mesh_rules.hpp"
#include "vk/device.hpp"

namespace vkcollide::validation {
namespace {

Error invalid(const std::string& rule) { return Error(ErrorCode::InvalidArgument, rule); }
bool finiteNonNegative(float x) { return x >= 0 && std::isfinite(x); }

}  // namespace

Result<void> checkTransform(const Transform3x4& transform) {
    for (float t : transform)
        if (!std::isfinite(t)) return invalid("transform is not finite");
    return {};
}

Result<void> checkHostMesh(const HostMesh& mesh) {
    if (auto ok = checkMeshRules(mesh); !ok) return ok;
    if (mesh.triangleCount() >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidMesh, "has 2^30 triangles or more");
    return {};
}

Result<void> checkVertices(std::span<const Float3> positions, std::uint32_t vertex_count) {
    if (positions.size() != vertex_count)
        return invalid(std::to_string(positions.size()) + " positions given for " + std::to_string(vertex_count) + " vertices");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
            return nonFiniteVertex(i);
    return {};
}

Error nonFiniteVertex(std::size_t index) {
    return Error(ErrorCode::InvalidMesh, "vertex " + std::to_string(index) + " is NaN or infinite");
}

std::array<float, 6> boxOf(std::span<const Float3> positions) {
    std::array<float, 6> b{positions[0].x, positions[0].y, positions[0].z, positions[0].x, positions[0].y, positions[0].z};
    for (const Float3& p : positions) {
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) b[a] = std::min(b[a], c[a]), b[a + 3] = std::max(b[a + 3], c[a]);
    }
    return b;
}

Result<void> checkWorldRange(const std::array<float, 6>& box, const Transform3x4& t) {
    // Per world axis, the sum of the terms' magnitudes bounds the coordinate and every
    // partial sum of toWorld's dot product (common.glsl.inc), in double (exact enough).
    double reach = 0;
    for (int r = 0; r < 3; ++r) {
        double bound = std::fabs(double(t[r * 4 + 3]));
        for (int a = 0; a < 3; ++a) bound += std::fabs(double(t[r * 4 + a])) * std::max(std::fabs(double(box[a])), std::fabs(double(box[a + 3])));
        reach = std::max(reach, bound);
    }
    if (reach <= double(gpu::kMaxWorldCoordinate)) return {};
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", reach);
    return Error(ErrorCode::LimitExceeded, std::string("vertex coordinates under the transform reach ") + text +
                                               " world units, beyond the sampling range of +-1e30 (the projection would need "
                                               "subnormal or infinite floats): scale or move the object");
}

Result<void> checkTypicalEdge(float typical_edge_length) {
    if (!finiteNonNegative(typical_edge_length)) return invalid("typical_edge_length must be finite and >= 0");
    return {};
}

Result<void> checkGpuMeshDesc(const GpuMeshDesc& d) {
    if (d.vertex_buffer == VK_NULL_HANDLE || d.index_buffer == VK_NULL_HANDLE)
        return invalid("vertex or index buffer is VK_NULL_HANDLE");
    if (d.index_count == 0 || d.vertex_count == 0) return Error(ErrorCode::InvalidMesh, "empty mesh (no indices or no vertices)");
    if (d.index_count % 3 != 0)
        return Error(ErrorCode::InvalidMesh, "index count " + std::to_string(d.index_count) + " is not a multiple of 3");
    if (d.index_count / 3 >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidMesh, "has 2^30 triangles or more");
    std::uint32_t position_bytes = 0;
    if (d.position_format == VK_FORMAT_R32G32B32_SFLOAT) position_bytes = 12;
    else if (d.position_format == VK_FORMAT_R32G32B32A32_SFLOAT) position_bytes = 16;
    else
        return Error(ErrorCode::UnsupportedFeature, "position format " + std::to_string(int(d.position_format)) +
                                                        " is not supported (use VK_FORMAT_R32G32B32_SFLOAT or R32G32B32A32_SFLOAT)");
    if (d.vertex_stride < position_bytes || d.vertex_stride % 4 != 0 || d.vertex_offset % 4 != 0 || d.index_offset % 4 != 0)
        return invalid("vertex stride " + std::to_string(d.vertex_stride) +
                       " must hold a position and be a multiple of 4; offsets must be multiples of 4");
    if (d.index_type != VK_INDEX_TYPE_UINT32 && d.index_type != VK_INDEX_TYPE_UINT16)
        return Error(ErrorCode::UnsupportedFeature, "index type must be VK_INDEX_TYPE_UINT16 or VK_INDEX_TYPE_UINT32");
    const bool index16 = d.index_type == VK_INDEX_TYPE_UINT16;
    if (index16 && d.vertex_count > 65536)
        return Error(ErrorCode::InvalidMesh, std::to_string(d.vertex_count) + " vertices cannot be reached by 16-bit indices");
    const VkDeviceSize vertex_end = d.vertex_offset + VkDeviceSize(d.vertex_count - 1) * d.vertex_stride + position_bytes;
    // 16-bit indices are read in whole 4-byte words.
    const VkDeviceSize index_end = d.index_offset + (index16 ? (VkDeviceSize(d.index_count) * 2 + 3) / 4 * 4 : VkDeviceSize(d.index_count) * 4);
    if (vertex_end > d.vertex_buffer_size)
        return Error(ErrorCode::BufferTooSmall, "vertex buffer of " + std::to_string(d.vertex_buffer_size) + " bytes is smaller than the " +
                                                    std::to_string(vertex_end) + " bytes its " + std::to_string(d.vertex_count) + " vertices need");
    if (index_end > d.index_buffer_size)
        return Error(ErrorCode::BufferTooSmall, "index buffer of " + std::to_string(d.index_buffer_size) + " bytes is smaller than the " +
                                                    std::to_string(index_end) + " bytes its " + std::to_string(d.index_count) + " indices need" +
                                                    (index16 ? " (16-bit indices are read in whole 4-byte words: pad by 2 bytes)" : ""));
    return {};
}

Result<void> checkSameTopology(const GpuMeshDesc& was, const GpuMeshDesc& now) {
    const auto differs = [](const char* what, std::uint64_t a, std::uint64_t b) {
        return invalid(std::string("setGpuMeshBuffers keeps the topology: ") + what + " " + std::to_string(b) + " differs from the " +
                       std::to_string(a) + " the object was added with (remove it and add it again instead)");
    };
    if (now.vertex_count != was.vertex_count) return differs("vertex count", was.vertex_count, now.vertex_count);
    if (now.index_count != was.index_count) return differs("index count", was.index_count, now.index_count);
    if (now.position_format != was.position_format) return differs("position format", was.position_format, now.position_format);
    if (now.index_type != was.index_type) return differs("index type", was.index_type, now.index_type);
    return {};
}

VkDeviceSize vertexBytes(const GpuMeshDesc& d) {
    const VkDeviceSize position_bytes = d.position_format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 12;
    return VkDeviceSize(d.vertex_count - 1) * d.vertex_stride + position_bytes;
}

VkDeviceSize indexBytes(const GpuMeshDesc& d) {
    // 16-bit indices are read in whole 4-byte words.
    return d.index_type == VK_INDEX_TYPE_UINT16 ? (VkDeviceSize(d.index_count) * 2 + 3) / 4 * 4 : VkDeviceSize(d.index_count) * 4;
}

namespace {

// What pairs sorted on the GPU need (device_pairs, pair_sort Gpu): the reliable method and
// its exact decision on the GPU, so shaderFloat64. `what` names the setting.
Result<void> checkSortedOnGpu(const std::string& what, const DetectSettings& s, const vk::Device& device) {
    if (s.method != DetectMethod::Reliable)
        return invalid(what + " belongs to the reliable method (the peeling method forms its pairs on the host)");
    if (s.reliable.exact == ExactDecision::Cpu)
        return invalid(what + " needs the exact decision on the GPU (exact Auto or Gpu, not Cpu: the CPU decides its pairs on the host)");
    if (!device.shader_float64)
        return Error(ErrorCode::UnsupportedFeature, what + " needs the exact decision on the GPU, so shaderFloat64, which " +
                                                        device.info.name + " lacks (or the adopted device did not enable)");
    return {};
}

}  // namespace

Result<void> checkDevicePairs(const DetectSettings& s, const vk::Device& device) {
    if (!s.reliable.host_pairs && !s.reliable.device_pairs)
        return invalid("reliable.host_pairs = false needs reliable.device_pairs = true: the pairs would be kept nowhere");
    if (!s.reliable.host_pairs && s.contacts.objects)
        return invalid("reliable.host_pairs = false with contacts.objects: object contacts are built from the host's pairs");
    if (s.reliable.pair_sort == PairSort::Gpu)
        if (auto ok = checkSortedOnGpu("reliable.pair_sort Gpu", s, device); !ok) return ok;
    if (s.reliable.responses == ResponseSource::Gpu) {
        if (auto ok = checkSortedOnGpu("reliable.responses Gpu", s, device); !ok) return ok;
        if (s.reliable.pair_sort == PairSort::Cpu)
            return invalid("reliable.responses Gpu needs the pairs sorted on the GPU (pair_sort Auto or Gpu, not Cpu)");
        if (s.reliable.device_pairs)
            return invalid("reliable.responses Gpu with reliable.device_pairs: that host result is built on the host "
                           "(the GPU's responses are in DevicePairs::responses with reliable.device_responses)");
    }
    if (s.reliable.device_responses && !s.reliable.device_pairs)
        return invalid("reliable.device_responses needs reliable.device_pairs = true: the responses are built from the device pairs");
    if (!s.reliable.device_pairs) return {};
    if (auto ok = checkSortedOnGpu("reliable.device_pairs", s, device); !ok) return ok;
    if (s.reliable.device_pair_capacity > kMaxDevicePairCapacity)
        return invalid("reliable.device_pair_capacity " + std::to_string(s.reliable.device_pair_capacity) +
                       " is more than kMaxDevicePairCapacity (" + std::to_string(kMaxDevicePairCapacity) + ")");
    return {};
}

Result<void> checkProximity(const DetectSettings& s, const vk::Device& device) {
    const ProximitySettings& p = s.proximity;
    if (!(p.distance >= 0) || !(p.distance <= 0x1p60))
        return invalid("proximity.distance " + std::to_string(p.distance) + " must be finite, at least 0 and at most 2^60 (world units)");
    if (p.distance == 0) return {};
    if (s.method != DetectMethod::Reliable)
        return invalid("proximity belongs to the reliable method (--method reliable): the peeling method samples no distances");
    if (!device.shader_float64)
        return Error(ErrorCode::UnsupportedFeature,
                     "proximity computes distances in double on the GPU and needs shaderFloat64, which " + device.info.name +
                         " lacks (or the adopted device did not enable)");
    if (p.capacity > kMaxProximityCapacity)
        return invalid("proximity.capacity " + std::to_string(p.capacity) + " is more than kMaxProximityCapacity (" +
                       std::to_string(kMaxProximityCapacity) + ")");
    return {};
}

Result<void> checkSortedOnGpuFilter(const std::string& what, bool on, bool filter_on_host_only, std::size_t live_objects) {
    if (on && filter_on_host_only)
        return invalid(what + " with a pair filter over " + std::to_string(live_objects) +
                       " live objects (more than kMaxFilterMaskObjects, " + std::to_string(gpu::kMaxFilterMaskObjects) +
                       "): the world applies that filter on the host only, so the GPU's pairs would differ");
    return {};
}

Result<void> checkSettings(const DetectSettings& s, const vk::Device& device) {
    // Every enum first, whatever the method uses: a value outside the enum would select no
    // branch below it (Coverage 77 sampled nothing and returned no pairs).
    const auto outside = [](const char* field, int value, const char* type, const char* values) {
        return invalid(std::string(field) + " " + std::to_string(value) + " is not a " + type + " (" + values + ")");
    };
    if (s.method != DetectMethod::Reliable && s.method != DetectMethod::Peeling)
        return outside("method", int(s.method), "DetectMethod", "Reliable or Peeling");
    if (s.peeling.packing != PackingMethod::Scan && s.peeling.packing != PackingMethod::Paper)
        return outside("peeling.packing", int(s.peeling.packing), "PackingMethod", "Scan or Paper");
    if (s.peeling.backend != SamplingBackend::Auto && s.peeling.backend != SamplingBackend::Raster &&
        s.peeling.backend != SamplingBackend::Compute)
        return outside("peeling.backend", int(s.peeling.backend), "SamplingBackend", "Auto, Raster or Compute");
    if (s.peeling.coverage != Coverage::Centre && s.peeling.coverage != Coverage::Dilate && s.peeling.coverage != Coverage::Conservative &&
        s.peeling.coverage != Coverage::Best)
        return outside("peeling.coverage", int(s.peeling.coverage), "Coverage", "Centre, Dilate, Conservative or Best");
    if (s.bad_objects != BadObjectPolicy::Exclude && s.bad_objects != BadObjectPolicy::Fail)
        return outside("bad_objects", int(s.bad_objects), "BadObjectPolicy", "Exclude or Fail");
    if (s.reliable.exact != ExactDecision::Auto && s.reliable.exact != ExactDecision::Gpu && s.reliable.exact != ExactDecision::Cpu)
        return outside("reliable.exact", int(s.reliable.exact), "ExactDecision", "Auto, Gpu or Cpu");
    if (s.reliable.exact_pass != ExactPass::Auto && s.reliable.exact_pass != ExactPass::Inline &&
        s.reliable.exact_pass != ExactPass::Queued)
        return outside("reliable.exact_pass", int(s.reliable.exact_pass), "ExactPass", "Auto, Inline or Queued");
    if (s.reliable.pair_sort != PairSort::Auto && s.reliable.pair_sort != PairSort::Gpu && s.reliable.pair_sort != PairSort::Cpu)
        return outside("reliable.pair_sort", int(s.reliable.pair_sort), "PairSort", "Auto, Gpu or Cpu");
    if (s.reliable.responses != ResponseSource::Auto && s.reliable.responses != ResponseSource::Gpu &&
        s.reliable.responses != ResponseSource::Cpu)
        return outside("reliable.responses", int(s.reliable.responses), "ResponseSource", "Auto, Gpu or Cpu");
    if (s.reliable.pair_naming != PairNaming::Auto && s.reliable.pair_naming != PairNaming::AfterFence)
        return outside("reliable.pair_naming", int(s.reliable.pair_naming), "PairNaming", "Auto or AfterFence");
    if (s.reliable.grid_tuning != GridTuning::Auto && s.reliable.grid_tuning != GridTuning::On && s.reliable.grid_tuning != GridTuning::Off)
        return outside("reliable.grid_tuning", int(s.reliable.grid_tuning), "GridTuning", "Auto, On or Off");
    const bool reliable = s.method == DetectMethod::Reliable;
    if (s.reliable.exact == ExactDecision::Gpu && !reliable)
        return invalid("exact decision on the GPU belongs to the reliable method (the peeling method decides on the CPU)");
    if (s.reliable.exact == ExactDecision::Gpu && !device.shader_float64)
        return Error(ErrorCode::UnsupportedFeature, "exact decision on the GPU needs shaderFloat64, which " + device.info.name +
                                                        " lacks (or the adopted device did not enable): use ExactDecision::Auto or Cpu");
    if (auto ok = checkDevicePairs(s, device); !ok) return ok;
    if (auto ok = checkProximity(s, device); !ok) return ok;
    if (s.peeling.axes != 1 && s.peeling.axes != 3) return invalid("peeling.axes must be 1 or 3, not " + std::to_string(s.peeling.axes));
    if (reliable && s.peeling.collision_rays)
        return invalid("peeling.collision_rays belongs to the peeling method (--method peeling): the reliable method samples no rays");
    if (reliable && s.peeling.axes != 1)
        return invalid("the reliable method runs along one direction (peeling.axes 1; resolveSettings sets it)");
    const std::uint32_t n = s.resolution.value_or(0);
    if (reliable) {
        if (n < 1 || n > gpu::kCellsMaxResolution)
            return invalid("resolution " + std::to_string(n) + " is not in [1, " + std::to_string(gpu::kCellsMaxResolution) +
                           "] (cells per side of the reliable method)");
    } else if (n < gpu::kMinResolution || n > gpu::kMaxResolution || (n & (n - 1)) != 0) {
        return invalid("resolution " + std::to_string(n) + " is not a power of two in [" + std::to_string(gpu::kMinResolution) + ", " +
                       std::to_string(gpu::kMaxResolution) + "]");
    }
    if (!s.direction) return invalid("projection direction must be finite and non-zero");
    const auto& d = *s.direction;
    const float dl = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(dl > 0) || !std::isfinite(dl)) return invalid("projection direction must be finite and non-zero");
    if (!finiteNonNegative(s.peeling.open_epsilon.value_or(0))) return invalid("peeling.open_epsilon must be finite and >= 0");
    if (!finiteNonNegative(s.peeling.closed_epsilon)) return invalid("peeling.closed_epsilon must be finite and >= 0");
    if (s.region) {
        const auto& r = *s.region;
        float widest = 0;
        for (int a = 0; a < 3; ++a) {
            if (!std::isfinite(r[a]) || !std::isfinite(r[a + 3]) || !(r[a] <= r[a + 3]))
                return invalid("sampling region must be finite with min <= max on every axis");
            if (std::fabs(r[a]) > gpu::kMaxWorldCoordinate || std::fabs(r[a + 3]) > gpu::kMaxWorldCoordinate)
                return Error(ErrorCode::LimitExceeded, "sampling region reaches beyond the sampling range of +-1e30 world units");
            widest = std::max(widest, r[a + 3] - r[a]);
        }
        if (!(widest >= gpu::kMinSamplingExtent))
            return Error(ErrorCode::LimitExceeded, "sampling region is narrower than the smallest extent vkcollide can sample (1e-30 world units)");
    }
    if (s.contacts.resolution &&
        (*s.contacts.resolution < gpu::kMinContactResolution || *s.contacts.resolution > gpu::kMaxContactResolution))
        return invalid("contacts.resolution " + std::to_string(*s.contacts.resolution) + " is not in [" +
                       std::to_string(gpu::kMinContactResolution) + ", " + std::to_string(gpu::kMaxContactResolution) + "]");
    if (reliable) return {};  // coverage and backend shape ray sampling, which it does not do
    if (s.peeling.coverage == Coverage::Conservative && !device.conservative_rasterization)
        return Error(ErrorCode::UnsupportedFeature, "conservative coverage needs VK_EXT_conservative_rasterization, which " +
                                                        device.info.name + " lacks (or the adopted device did not enable): use dilation");
    // Thin-triangle coverage is drawn by sample.vert (or a conservative pipeline): raster
    // only. Auto falls back to raster; an explicit Compute is refused.
    if (s.peeling.coverage != Coverage::Centre && s.peeling.backend == SamplingBackend::Compute)
        return Error(ErrorCode::UnsupportedFeature, "thin-triangle coverage (dilate or conservative) needs the raster sampling backend");
    return {};
}

Result<void> checkReliableObject(const Transform3x4& transform, float max_abs_position) {
    // The cell stage's bounds hold below 2^62 (docs/reliable.md, "Assumptions").
    constexpr float kLimit = 4.611686018427388e18f;
    for (float t : transform)
        if (!(std::fabs(t) < kLimit)) return invalid("transform entry " + std::to_string(t) + " is 2^62 or more in magnitude (the reliable method's limit)");
    if (!(max_abs_position < kLimit))
        return Error(ErrorCode::InvalidMesh, "has a vertex coordinate of magnitude 2^62 or more (the reliable method's limit)");
    return {};
}

Result<void> checkScene(std::span<const passes::GpuMesh> meshes) {
    if (meshes.empty()) return invalid("the world has no objects to test");
    std::uint64_t total = 0;
    for (const passes::GpuMesh& m : meshes) total += m.triangle_count;
    if (total >= gpu::kMaxTriangles) return invalid("scene has more than 2^30 triangles");
    return {};
}

}  // namespace vkcollide::validation
