// vkcollide: proximity queries (DetectSettings::proximity, docs/proximity.md). With a
// distance d, a detection of the reliable method also reports every vertex-triangle and
// edge-edge pair whose distance is at most d: across objects that may collide, and within
// an object whose self-collision is on (primitives that share a vertex index or a
// bit-identical world vertex left out, as for intersecting pairs). Computed on the GPU in
// double on the world vertices the CPU's narrow phase uses; none within d is ever left
// out; a pair whose computed distance is within its error bound of d is reported with
// kProximityInBand (it may lie slightly beyond d).
#pragma once

#include <cstdint>

#include <vulkan/vulkan_core.h>

namespace vkcollide {

enum class ProximityKind : std::uint32_t {
    VertexTriangle = 0,  // a vertex of object_a and a triangle of object_b
    EdgeEdge = 1,        // an edge of object_a and an edge of object_b
};

inline constexpr std::uint32_t kProximityInBand = 1;   // ProximityPair::flags: maybe beyond d, within the error bound
inline constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;  // unused a1 / b1 of a vertex-triangle pair

// One pair within the distance (64 bytes; the GPU's record, spirv/proximity.h).
// Vertex-triangle: a0 the vertex of object_a, b0 the triangle of object_b (a1 = b1 =
// kNoPrimitive). Edge-edge: (a0, a1) and (b0, b1) the edges' vertex indices, each lower
// first, and (object_a, a0, a1) < (object_b, b0, b1). Both within one object when its
// self-collision is on. DetectResult::proximity is sorted by (kind, object_a, a0, a1,
// object_b, b0, b1) and holds each pair once.
struct ProximityPair {
    ProximityKind kind = ProximityKind::VertexTriangle;
    std::uint32_t flags = 0;  // kProximityInBand
    std::uint32_t object_a = 0, object_b = 0;
    std::uint32_t a0 = 0, a1 = kNoPrimitive;
    std::uint32_t b0 = 0, b1 = kNoPrimitive;
    float distance = 0;  // world units, computed in double (rounded)
    // Closest points: on a, the vertex itself, or (1 - weight_a) * v[a0] + weight_a * v[a1];
    // on b, weights_b over the triangle's three vertices in its index order, or
    // weights_b[0] * v[b0] + weights_b[1] * v[b1] (weights_b[2] = 0).
    float weight_a = 0;
    float weights_b[3] = {0, 0, 0};
    // Unit vector from b's closest point towards a's (distance 0: the triangle's normal,
    // or the two edges' common normal).
    float normal[3] = {0, 0, 1};
};

// Where DetectResult::proximity also lies on the GPU (DetectResult::device_proximity), for a
// GPU solver's next command buffer. `pairs`: ProximityPair records (64 bytes, the layout
// above) at offset 0, `capacity` of them; the first `count` are the result's pairs in its
// order, except that a pair the host dropped as found twice is there twice, side by side
// (rare: a triangle pair whose canonical-cell scan ran out of budget, docs/reliable.md).
// The buffer is host-visible memory the GPU wrote (read it by address or as a storage
// buffer). `header`: one DeviceProximityHeader at offset 0 (device-local). Both have usage
// STORAGE, SHADER_DEVICE_ADDRESS, TRANSFER_SRC and TRANSFER_DST on the Context's queue
// family; the engine reads them, never writes them.
// Synchronisation as for DevicePairs (detect_result.hpp): complete and visible at the world's
// signal (submit) or after the recorded commands (record), finished when detect()/collect()
// return. Lifetime: until the next detection in the same slot starts (DevicePairs::slot's
// rule); a detection that needs more capacity re-creates them: take them afresh from each
// DetectResult.
struct DeviceProximityHeader {
    std::uint32_t count = 0, needed = 0, flags = 0, capacity = 0;  // flags: kDeviceProximity*
    std::uint32_t triangle_pairs = 0, distances = 0, neighbours = 0, in_band = 0;
};
inline constexpr std::uint32_t kDeviceProximityOverflow = 1;    // needed > capacity (collect() grew it and ran again)
inline constexpr std::uint32_t kDeviceProximityIncomplete = 2;  // the cell stage runs again or on: count 0 until collect() repeats it
struct DeviceProximity {
    VkBuffer pairs = VK_NULL_HANDLE;
    VkDeviceAddress pairs_address = 0;
    VkBuffer header = VK_NULL_HANDLE;
    VkDeviceAddress header_address = 0;
    std::uint32_t capacity = 0;
};

struct ProximitySettings {
    // d in world units; 0: off. Finite, at most 2^60. Needs the reliable method, host
    // meshes (their indices tell which primitives neighbour each other) and a device with
    // shaderFloat64; otherwise the detection is refused naming why.
    double distance = 0;
    // Records the GPU buffer holds. 0: automatic (grows to what a detection needed, the
    // proximity pass alone run again). Else a fixed capacity: a detection that finds more
    // fails with LimitExceeded naming the count it found (nothing is dropped silently).
    std::uint32_t capacity = 0;
};
inline constexpr std::uint32_t kMaxProximityCapacity = 1u << 26;

struct ProximityStats {
    bool ran = false;
    double distance = 0;
    std::uint64_t pairs = 0;            // in DetectResult::proximity
    std::uint64_t vertex_triangle = 0;  // of them, vertex-triangle
    std::uint64_t edge_edge = 0;        // of them, edge-edge
    std::uint64_t in_band = 0;          // of them, flagged kProximityInBand
    std::uint64_t triangle_pairs = 0;   // candidate triangle pairs examined on the GPU
    std::uint64_t distances = 0;        // primitive pairs whose distance was computed
    std::uint64_t neighbours = 0;       // primitive pairs left out as neighbours
    std::uint64_t duplicates = 0;       // records the host removed (a pair found twice)
    std::uint32_t capacity = 0;         // records the GPU buffer held in the last run
    std::uint32_t runs = 0;             // proximity passes (more after the buffer grew)
    double gpu_ms = 0;                  // the proximity pass on the GPU
    double host_ms = 0;                 // reading, sorting and mapping the records
};

}  // namespace vkcollide
