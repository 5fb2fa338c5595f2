// The registry of objects: lookups, ids, vertex copies for pipelining, and the views of the
// live set that detections read (the narrow phase's source, the pair filter's mask).
#include "api/object_registry.hpp"

#include <algorithm>
#include <exception>

#include "api/in_flight.hpp"
#include "common/config.h"
#include "vk/device.hpp"

namespace vkcollide {

std::string ObjectRegistry::who(ObjectId id, const std::string& name) {
    return "object " + std::to_string(id) + " ('" + name + "')";
}

Result<ObjectRegistry::Object*> ObjectRegistry::find(ObjectId id, const char* what) {
    if (id >= objects.size() || !objects[id].alive)
        return Error(ErrorCode::InvalidArgument, std::string(what) + ": no object with id " + std::to_string(id));
    return &objects[id];
}

Result<ObjectRegistry::Object::VertexCopy*> ObjectRegistry::freeCopy(vk::Device& device, const DetectionsInFlight& in_flight, ObjectId id,
                                                                     Object& o) {
    for (Object::VertexCopy& c : o.copies)
        if (!in_flight.reads(id, c.upload.address(), c.positions.data())) return &c;
    // At most kMaxInFlight detections read at most that many copies, one of them the
    // current one: with kMaxInFlight copies beside it one is always free.
    if (o.copies.size() >= CollisionWorld::kMaxInFlight)
        return Error(ErrorCode::InvalidArgument, "updateVertices: every copy of the vertices is read by a detection in flight");
    auto upload = vk::Buffer::create(device, std::size_t{o.gpu.vertex_count} * sizeof(Float3), 0, vk::MemoryKind::Upload,
                                     o.name + "-vertices-copy");
    if (!upload) return upload.error();
    o.copies.reserve(CollisionWorld::kMaxInFlight);  // moves keep each copy's positions where a run's span points
    o.copies.push_back({std::move(*upload), {}});
    return &o.copies.back();
}

ObjectId ObjectRegistry::newId(const ObjectOptions& options, Object& out) const {
    out.alive = true;
    out.options = options;
    const auto id = static_cast<ObjectId>(objects.size());
    out.name = options.name.empty() ? "object " + std::to_string(id) : options.name;
    return id;
}

void ObjectRegistry::liveMeshes(std::vector<passes::GpuMesh>& meshes, std::vector<ObjectId>& ids) const {
    meshes.clear();
    ids.clear();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        if (!objects[i].alive) continue;
        passes::GpuMesh m = objects[i].gpu;
        m.transform = objects[i].options.transform;
        m.self_collision = objects[i].options.self_collision;
        meshes.push_back(m);
        ids.push_back(static_cast<ObjectId>(i));
    }
}

Result<void> ObjectRegistry::syncSource(std::span<const ObjectId> ids) {
    if (!source_dirty && std::equal(ids.begin(), ids.end(), source_ids.begin(), source_ids.end())) return {};
    for (ObjectId id : source_ids)
        if (id < objects.size()) objects[id].source_index = kNoSource;
    source.clear();
    source_ids.assign(ids.begin(), ids.end());
    for (ObjectId id : ids) {
        Object& o = objects[id];
        auto added = o.host ? source.addHostMesh(o.host_positions, o.host_indices, o.options.transform)
                            : source.addGpuMesh(o.gpu.triangle_count);
        if (!added) return named(id, added.error());
        o.source_index = *added;
    }
    source_dirty = false;
    return {};
}

Result<bool> ObjectRegistry::callPairFilter(ObjectId a, ObjectId b) const {
    std::string what;
    try {
        return pair_filter(a, b);
    } catch (const std::exception& e) {
        what = std::string(": ") + e.what();
    } catch (...) {
    }
    return Error(ErrorCode::InvalidArgument, "the pair filter threw for objects " + std::to_string(a) + " and " + std::to_string(b) +
                                                 what + " (it must not throw)");
}

Result<const passes::ObjectPairMask*> ObjectRegistry::pairMask(std::span<const ObjectId> ids) {
    if (!pair_filter || ids.size() > gpu::kMaxFilterMaskObjects) return nullptr;
    if (pair_mask_dirty || pair_mask.objects != ids.size()) {
        const auto n = static_cast<std::uint32_t>(ids.size());
        pair_mask.reset(n);
        pair_mask_dirty = true;  // until every answer is in
        for (std::uint32_t a = 0; a < n; ++a)
            for (std::uint32_t b = a + 1; b < n; ++b) {
                auto answer = callPairFilter(ids[a], ids[b]);
                if (!answer) return answer.error();
                if (*answer) pair_mask.allow(a, b);
            }
        pair_mask_dirty = false;
    }
    return &pair_mask;
}

}  // namespace vkcollide
