// vkcollide: what a detection returns (DetectResult) and the results it can leave on the
// GPU for the engine (DevicePairs: layout, synchronisation and lifetime).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vkcollide/contacts.hpp"
#include "vkcollide/detect_stats.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/proximity.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide {

// An object a detection left out (BadObjectPolicy::Exclude), and why.
struct ExcludedObject {
    ObjectId object = 0;
    Error error{ErrorCode::InvalidMesh, {}};  // names the object, a bad triangle and the problem
};

// ---- Results on the GPU (DetectSettings::reliable.device_pairs; docs/api.md) ------------
//
// Layout. `pairs`: TrianglePair records (four uint32: object_a, triangle_a, object_b,
// triangle_b; 16 bytes, tightly packed) at offset 0, `capacity` of them; the first
// `count` are the detection's pairs in DetectResult::pairs' order (object ids as the API
// returns them, triangles within the object). `header`: one DevicePairsHeader at offset 0.
// Both are storage buffers with device addresses in device-local memory (usage STORAGE,
// SHADER_DEVICE_ADDRESS, TRANSFER_SRC, TRANSFER_DST; EXCLUSIVE on the Context's queue
// family), written by compute shaders; the engine reads them, never writes them.
//
// Synchronisation: the writes are complete and visible at the world's signal. submit():
// wait for sync.signal with the stage mask of your reads (e.g. COMPUTE_SHADER); record():
// after the recorded commands in your command buffer, a memory (or buffer memory) barrier
// from COMPUTE_SHADER / SHADER_WRITE to your stage and access; detect() and collect(): the
// work is finished (on another queue, order after the world's work as for submit()).
// Before collect() returns, check the header: kDevicePairsIncomplete means this GPU run must
// be repeated or finished (a reliable-method buffer overflowed, DetectStats::cells.runs > 1;
// an engine mesh failed the GPU input check; or the sweep or the pair pass goes on in later
// submissions, cells.sweep_chunks or pair_chunks > 1) and count is 0; collect() does it,
// after which the buffers hold the final pairs (as DetectResult::pairs) for reads ordered
// after collect().
//
// Lifetime: each of the world's two detection slots (kMaxInFlight) has its own buffers
// (DevicePairs::slot). A detection's pairs stay there until the GPU work of the next
// detection in the same slot: the next detect()/submit()/record() when none is in flight
// when it starts (slot 0), else the other slot (pipelining: frame N + 1 writes slot 1 while
// frame N's pairs stay in slot 0). Your GPU reads must be ordered before that detection's
// GPU work: on the Context's queue, submitted before its submit() (each detection begins
// with a full memory barrier); on another queue, by a semaphore in its SubmitSync::wait.
// The buffers may be re-created (larger) for a later detection: take DevicePairs afresh
// for every detection (devicePairs() or DetectResult::device). Replaced buffers stay
// alive until the start of the second detection after in that slot, so reads ordered as
// above never meet a freed buffer. All of them are freed with the world.
struct DevicePairsHeader {
    std::uint32_t count = 0;  // pairs written: min(needed, capacity)
    std::uint32_t needed = 0;  // distinct intersecting pairs the detection found
    std::uint32_t flags = 0;  // kDevicePairs* below
    std::uint32_t capacity = 0;  // pairs the buffer holds
    // With device_responses: the responses written (one per triangle in any of the `needed`
    // pairs, even where the pairs overflowed) and the buffer's capacity (the detection's
    // triangles: it never overflows); 0 and 0 without.
    std::uint32_t responses = 0;
    std::uint32_t response_capacity = 0;
    std::uint32_t reserved[2] = {};
};
inline constexpr std::uint32_t kDevicePairsOverflow = 1;  // needed > capacity: the first `capacity` pairs written
inline constexpr std::uint32_t kDevicePairsIncomplete = 2;  // repeated by collect(): count 0 until then
struct DevicePairs {
    VkBuffer pairs = VK_NULL_HANDLE;  // TrianglePair[capacity] at offset 0
    VkDeviceAddress pairs_address = 0;
    VkBuffer header = VK_NULL_HANDLE;  // DevicePairsHeader at offset 0
    VkDeviceAddress header_address = 0;
    std::uint32_t capacity = 0;  // pairs (the header says it too)
    std::uint32_t slot = 0;  // the detection slot (0 or 1) whose buffers these are
    // With DetectSettings::reliable.device_responses: TriangleResponse[response_capacity] at
    // offset 0 (24 bytes each, tightly packed: object, triangle, direction x y z as floats,
    // partner_count), the first header.responses of them DetectResult::responses' records in
    // its order; same usage, memory, synchronisation and lifetime as `pairs`. Else null.
    VkBuffer responses = VK_NULL_HANDLE;
    VkDeviceAddress responses_address = 0;
    std::uint32_t response_capacity = 0;
};

// The collision rays of a peeling detection (DetectSettings::peeling.collision_rays): each ray from
// where the sampled box begins along its direction to where it ends, in world space.
struct CollisionRays {
    std::vector<std::array<Float3, 2>> segments;  // every direction's rays, the first direction's first
    std::array<std::uint32_t, 3> per_axis{};  // how many of `segments` each direction gave
    float pixel_size = 0;  // world width of one ray's pixel (first direction)
};

struct DetectResult {
    std::vector<TrianglePair> pairs;
    // With DetectSettings::reliable.device_pairs: where the same pairs are on the GPU (above).
    std::optional<DevicePairs> device;
    std::vector<TriangleResponse> responses;  // one per colliding triangle, world space
    std::vector<ExcludedObject> excluded;  // engine meshes that failed the GPU check this time
    // With DetectSettings::contacts.objects: one per pair of closed objects whose volumes overlap
    // or whose triangles intersect (filtered pairs and excluded objects have none), sorted
    // by (object_a, object_b). Empty otherwise.
    std::vector<ObjectContact> contacts;
    // With DetectSettings::contacts.geometry: one per `pairs` entry, same index; and per pair
    // of objects with intersecting triangles, their sums, sorted by (object_a, object_b).
    std::vector<PairContact> pair_contacts;
    std::vector<ObjectPairContact> pair_contact_totals;
    // With DetectSettings::proximity: every vertex-triangle and edge-edge pair within the
    // distance, each once, sorted (ProximityPair). Empty otherwise.
    std::vector<ProximityPair> proximity;
    // With DetectSettings::proximity: the same pairs on the GPU (vkcollide/proximity.hpp).
    std::optional<DeviceProximity> device_proximity;
    // With DetectSettings::peeling.collision_rays: where the collision rays were.
    std::optional<CollisionRays> collision_rays;
    DetectStats stats;
    // DetectSettings::limits.max_pairs was reached: the intersecting pairs found beyond it (not in
    // `pairs`, not in `responses`), and an error (LimitExceeded) that says so. Empty and 0
    // when the result is complete.
    std::uint64_t pairs_left_out = 0;
    std::optional<Error> incomplete;
};

}  // namespace vkcollide
