// Engine meshes: addGpuMesh and setGpuMeshBuffers, and the one path that checks an
// engine's buffers (the layout in validation.cpp, each buffer by vk::checkEngineBuffer,
// which also gives its device address).
#include "api/validation.hpp"
#include "api/world_impl.hpp"
#include "mesh/engine_mesh.hpp"
#include "vk/engine_buffer.hpp"

namespace vkcollide {

Result<passes::GpuMesh> CollisionWorld::Impl::describeEngineMesh(ObjectId id, const std::string& name, const GpuMeshDesc& d,
                                                                 bool open) const {
    if (auto ok = validation::checkGpuMeshDesc(d); !ok) return registry.named(id, name, ok.error());
    const std::string prefix = registry.who(id, name) + ": ";
    auto vertices = vk::checkEngineBuffer(
        device(), {d.vertex_buffer, d.vertex_usage, d.vertex_buffer_size, d.vertex_offset, validation::vertexBytes(d)},
        prefix + "vertex buffer");
    if (!vertices) return vertices.error();
    auto indices = vk::checkEngineBuffer(
        device(), {d.index_buffer, d.index_usage, d.index_buffer_size, d.index_offset, validation::indexBytes(d)}, prefix + "index buffer");
    if (!indices) return indices.error();
    return passes::describeEngineMesh(d, *vertices, *indices, open);
}

Result<ObjectId> CollisionWorld::addGpuMesh(const GpuMeshDesc& d, const ObjectOptions& options) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::addGpuMesh");
    if (!scope) return scope.error();
    if (auto ok = w.detections.notPending("addGpuMesh"); !ok) return ok.error();
    Impl::Object o;
    const ObjectId id = w.registry.newId(options, o);
    for (auto ok : {validation::checkTransform(options.transform), validation::checkTypicalEdge(options.typical_edge_length)})
        if (!ok) return ObjectRegistry::named(id, o.name, ok.error());
    auto mesh = w.describeEngineMesh(id, o.name, d, options.open);
    if (!mesh) return mesh.error();
    o.gpu = *mesh;
    o.engine_desc = d;
    o.shape.edge_length = options.typical_edge_length;
    w.registry.objects.push_back(std::move(o));
    w.objectsChanged();
    return id;
}

// Why no objectsChanged(): the topology is the same, so the measured depth complexity
// (peeling's prediction), the narrow phase's source and the pair mask all stay valid;
// only the addresses the next detection reads change. Detections in flight keep the
// addresses they were submitted with (Run::meshes).
Result<void> CollisionWorld::setGpuMeshBuffers(ObjectId id, const GpuMeshDesc& d) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::setGpuMeshBuffers");
    if (!scope) return scope.error();
    auto found = w.registry.find(id, "setGpuMeshBuffers");
    if (!found) return found.error();
    Impl::Object& o = **found;
    if (o.host)
        return w.registry.named(
            id, Error(ErrorCode::InvalidArgument, "setGpuMeshBuffers: is a host mesh (added by addMesh): use updateVertices"));
    if (auto ok = validation::checkSameTopology(o.engine_desc, d); !ok) return w.registry.named(id, ok.error());
    auto mesh = w.describeEngineMesh(id, o.name, d, o.options.open);
    if (!mesh) return mesh.error();
    o.gpu = *mesh;
    o.engine_desc = d;
    return {};
}

}  // namespace vkcollide
