// The world's objects: each one's meshes (uploaded copies, host copies, engine buffers), its
// id and name, and the views of the live set that detections read (the narrow phase's
// TriangleSource, the pair filter's mask). world.cpp adds and changes objects through it.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "api/vertex_scans.hpp"
#include "broad/broad_phase_types.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

struct DetectionsInFlight;

struct ObjectRegistry {
    struct Object {
        bool alive = false;
        std::string name;
        ObjectOptions options;
        bool host = false;
        vk::Buffer vertices, indices;  // host meshes: uploaded copies
        // Host meshes: positions and indices again, for the narrow phase's TriangleSource
        // (reliable method) and for measuring the shape (reading the upload buffer back
        // would cross the bus: it may be write-combined device memory).
        std::vector<Float3> host_positions;
        // updateVertices writes here, then swaps: a refused update leaves host_positions
        // as they were.
        std::vector<Float3> spare_positions;
        // Pipelining host meshes: further copies of the vertices (upload buffer and host
        // positions). updateVertices writes one of them, and makes it current by swapping,
        // when a detection in flight reads the current ones; at most kMaxInFlight, made on
        // first need (a world that never updates in flight has none), reused once no
        // detection in flight reads them (freeCopy).
        struct VertexCopy {
            vk::Buffer upload;
            std::vector<Float3> positions;
        };
        std::vector<VertexCopy> copies;
        std::vector<std::uint32_t> host_indices;
        passes::GpuMesh gpu;           // addresses, counts, flags (transform set per run)
        GpuMeshDesc engine_desc;       // engine meshes: as given (setGpuMeshBuffers keeps its topology)
        // Object-space box (host meshes) and largest |coordinate| (the reliable method's
        // limit), measured when the geometry changes.
        std::array<float, 6> box{};
        float max_abs = 0;
        // Closed host meshes (mesh_checks): edges of one triangle (from addMesh), and six
        // times the object-space volume (both measured by addMesh; updateVertices leaves them).
        std::uint64_t boundary_edges = 0;
        double volume6 = 0;
        // For the automatic settings (vertex_scans::Shape): the typical edge length (object
        // units; given for GPU meshes) and, host meshes, the sum over triangles of
        // area * n n^T and the area facing each object axis (object space). A cache for host
        // meshes: after their geometry changes (shape_stale) they are measured by the next
        // resolve() that needs them (AutoSettings::measureShapes), not by addMesh; hence
        // mutable. updateVertices measures them on the way (in its own parallel loop) while
        // the last resolve() needed them.
        mutable vertex_scans::Shape shape;
        mutable bool shape_stale = false;
        // Proximity: the vertices and edges each triangle owns (host meshes, computed by the
        // first detection that asks; the indices never change).
        std::vector<std::uint8_t> proximity_owned;
        // Index of the object in `source` (kNoSource: not in it).
        std::uint32_t source_index = 0xFFFFFFFFu;
    };
    static constexpr std::uint32_t kNoSource = 0xFFFFFFFFu;

    std::function<bool(ObjectId, ObjectId)> pair_filter;
    std::vector<Object> objects;
    // The narrow phase's view of the live objects for the pair path (reliable method):
    // host meshes borrow host_positions and host_indices, GPU meshes are read from the
    // detection's downloaded triangles. Rebuilt (O(objects), no copies) when objects are
    // added or removed; transforms are set in place.
    TriangleSource source;
    std::vector<ObjectId> source_ids;
    bool source_dirty = true;
    // The pair filter's answers over the live objects in id order (setPairFilter's
    // contract): recomputed at the next detection after the filter or the objects change.
    passes::ObjectPairMask pair_mask;
    bool pair_mask_dirty = true;

    // "object 3 ('cloth')": how every error names an object, in one place.
    static std::string who(ObjectId id, const std::string& name);
    static Error named(ObjectId id, const std::string& name, const Error& e) {
        return Error(e.code(), who(id, name) + ": " + e.message(), e.vkResult());
    }
    Error named(ObjectId id, const Error& e) const { return named(id, objects.at(id).name, e); }
    Result<Object*> find(ObjectId id, const char* what);
    ObjectId newId(const ObjectOptions& options, Object& out) const;
    // Objects were added or removed: the source and the mask are rebuilt when next needed.
    void changed() { source_dirty = pair_mask_dirty = true; }
    // A copy of `o`'s vertices that no detection in `in_flight` reads, made when there is none.
    Result<Object::VertexCopy*> freeCopy(vk::Device& device, const DetectionsInFlight& in_flight, ObjectId id, Object& o);

    // The live objects as the broad phase reads them (transforms applied), and their ids.
    void liveMeshes(std::vector<passes::GpuMesh>& out_meshes, std::vector<ObjectId>& out_ids) const;
    // The source for the detection's objects (`ids`, in run order); rebuilt when needed.
    Result<void> syncSource(std::span<const ObjectId> ids);
    // The filter's mask over the live objects `ids` (id order), or null: no filter, or more
    // than kMaxFilterMaskObjects objects; the filter's exception as an error.
    Result<const passes::ObjectPairMask*> pairMask(std::span<const ObjectId> ids);
    // The pair filter's answer, or InvalidArgument naming the pair if it threw.
    Result<bool> callPairFilter(ObjectId a, ObjectId b) const;
};

}  // namespace vkcollide
