#include "bench_world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "api/context_access.hpp"

namespace vkcollide::bench {
namespace {

void writeVertices(EngineMesh& e, const BenchObject& o) {
    auto* dst = static_cast<std::uint8_t*>(e.vertices.mapped());
    for (std::size_t i = 0; i < o.mesh.positions.size(); ++i) std::memcpy(dst + i * o.gpu_stride, &o.mesh.positions[i], 12);
    e.vertices.flush();
}

Result<EngineMesh> makeEngineMesh(vk::Device& device, const BenchObject& o) {
    if (o.gpu_stride != 12 && o.gpu_stride != 16) return Error(ErrorCode::InvalidArgument, o.mesh.name + ": gpu_stride must be 12 or 16");
    if (o.gpu_index16 && o.mesh.positions.size() > 65536)
        return Error(ErrorCode::InvalidArgument, o.mesh.name + ": 16-bit indices need at most 65,536 vertices");
    EngineMesh e;
    auto vb = vk::Buffer::create(device, o.mesh.positions.size() * o.gpu_stride, 0, vk::MemoryKind::Upload, "bench-engine-vertices");
    if (!vb) return vb.error();
    e.vertices = std::move(*vb);
    std::memset(e.vertices.mapped(), 0, e.vertices.size());
    writeVertices(e, o);
    const std::size_t index_bytes = o.gpu_index16 ? (o.mesh.indices.size() * 2 + 3) / 4 * 4 : o.mesh.indices.size() * 4;
    auto ib = vk::Buffer::create(device, index_bytes, 0, vk::MemoryKind::Upload, "bench-engine-indices");
    if (!ib) return ib.error();
    e.indices = std::move(*ib);
    std::memset(e.indices.mapped(), 0, e.indices.size());
    if (o.gpu_index16) {
        auto* idx = static_cast<std::uint16_t*>(e.indices.mapped());
        for (std::size_t k = 0; k < o.mesh.indices.size(); ++k) idx[k] = static_cast<std::uint16_t>(o.mesh.indices[k]);
    } else {
        std::memcpy(e.indices.mapped(), o.mesh.indices.data(), o.mesh.indices.size() * 4);
    }
    e.indices.flush();
    e.desc.vertex_buffer = e.vertices.handle();
    e.desc.vertex_buffer_size = e.vertices.size();
    e.desc.vertex_stride = o.gpu_stride;
    e.desc.vertex_count = static_cast<std::uint32_t>(o.mesh.positions.size());
    e.desc.position_format = o.gpu_stride == 16 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32G32B32_SFLOAT;
    e.desc.index_buffer = e.indices.handle();
    e.desc.index_buffer_size = e.indices.size();
    e.desc.index_type = o.gpu_index16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;
    e.desc.index_count = static_cast<std::uint32_t>(o.mesh.indices.size());
    return e;
}

}  // namespace

Result<void> bakeTransforms(std::vector<BenchObject>& objects) {
    for (BenchObject& o : objects) {
        double stretch = 0;
        for (int r = 0; r < 3; ++r) {
            const double x = o.transform[4 * r], y = o.transform[4 * r + 1], z = o.transform[4 * r + 2];
            stretch = std::max(stretch, std::sqrt(x * x + y * y + z * z));
        }
        if (Result<void> ok = transformMesh(o.mesh, o.transform); !ok) return ok;
        o.typical_edge_length *= static_cast<float>(stretch);
        o.transform = kIdentity3x4;
    }
    return {};
}

Result<std::vector<BenchObject>> buildFrame(const SceneSpec& scene, int frame, bool bake_moving) {
    Result<std::vector<BenchObject>> objects = scene.build(frame);
    if (objects && (scene.motion != Motion::Moving || bake_moving))
        if (Result<void> ok = bakeTransforms(*objects); !ok) return ok.error();
    return objects;
}

Result<SceneInWorld> addToWorld(CollisionWorld& world, Context& context, const std::vector<BenchObject>& objects, bool all_open) {
    SceneInWorld s;
    s.engine.resize(objects.size());
    for (std::size_t k = 0; k < objects.size(); ++k) {
        const BenchObject& o = objects[k];
        ObjectOptions oo;
        oo.name = o.mesh.name;
        oo.self_collision = o.self_collision;
        oo.open = o.open || all_open;
        oo.transform = o.transform;
        oo.typical_edge_length = o.typical_edge_length;
        Result<ObjectId> id = Error(ErrorCode::InvalidArgument, "");
        if (o.gpu) {
            auto e = makeEngineMesh(ContextAccess::device(context), o);
            if (!e) return e.error();
            s.engine[k] = std::move(*e);
            id = world.addGpuMesh(s.engine[k].desc, oo);
        } else {
            id = world.addMesh(o.mesh, oo);
        }
        if (!id) return id.error();
        s.ids.push_back(*id);
    }
    return s;
}

Result<void> applyFrame(CollisionWorld& world, SceneInWorld& scene, Motion motion, const std::vector<BenchObject>& frame) {
    if (frame.size() != scene.ids.size()) return Error(ErrorCode::InvalidArgument, "applyFrame: the frame has another object count");
    for (std::size_t k = 0; k < frame.size() && motion != Motion::Rigid; ++k) {
        const BenchObject& o = frame[k];
        if (motion == Motion::Moving) {
            if (Result<void> ok = world.setTransform(scene.ids[k], o.transform); !ok) return ok;
        } else if (o.gpu) {
            if (o.mesh.positions.size() != scene.engine[k].desc.vertex_count)
                return Error(ErrorCode::InvalidArgument, o.mesh.name + ": the frame has another vertex count");
            writeVertices(scene.engine[k], o);
        } else if (Result<void> ok = world.updateVertices(scene.ids[k], o.mesh.positions); !ok) {
            return ok;
        }
    }
    return {};
}

}  // namespace vkcollide::bench
