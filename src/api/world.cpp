// CollisionWorld: creation and the public methods that change its objects (the registry
// itself is object_registry.cpp). Engine meshes are in engine_mesh.cpp, automatic settings
// in auto_settings.cpp, one detection in detect.cpp, the calls that start and collect
// detections in engine_sync.cpp, every input rule in validation.cpp.
#include "vkcollide/world.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <stdexcept>

#include "api/context_access.hpp"
#include "api/vertex_scans.hpp"
#include "api/mesh_checks.hpp"
#include "api/validation.hpp"
#include "api/world_impl.hpp"
#include "common/config.h"
#include "core/host_memory.hpp"
#include "mesh/mesh_upload.hpp"
#include "vk/device.hpp"

namespace vkcollide {
Error CollisionWorld::Impl::noted(Error e) {
    if (e.code() == ErrorCode::DeviceLost) device_lost = true;
    return e;
}

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::~CollisionWorld() {
    impl_->guard.requireIdle("CollisionWorld destroyed");
    // Impl's runs are destroyed first: they wait for work in flight.
}

Result<std::unique_ptr<CollisionWorld>> CollisionWorld::create(Context& context, const WorldOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->device_ref = ContextAccess::deviceRef(context);
    // The default method's stages now (they check the device); every pipeline when a
    // detection first needs it (a world that only peels compiles none of the cell stage).
    auto detection = passes::Detection::create(ContextAccess::device(context), DetectionsInFlight::methodFactory(DetectSettings{}.method));
    if (!detection) return detection.error();
    impl->detections.runs[0].detection = std::move(*detection);
    if (options.executor) {
        impl->executor = options.executor;  // the engine's job system: no thread of our own
    } else {
        impl->own_pool = std::make_unique<ThreadPool>(options.threads);
        impl->executor = impl->own_pool.get();
    }
    return std::unique_ptr<CollisionWorld>(new CollisionWorld(std::move(impl)));
}

Result<ObjectId> CollisionWorld::addMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::addMesh");
    if (!scope) return scope.error();
    if (auto ok = w.detections.notPending("addMesh"); !ok) return ok.error();
    return hostMemoryGuarded("addMesh", [&]() -> Result<ObjectId> { return w.addHostMesh(mesh, options); });
}

Result<ObjectId> CollisionWorld::Impl::addHostMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Object o;
    const ObjectId id = registry.newId(options, o);
    // Every rule before anything is uploaded.
    for (auto ok : {validation::checkTransform(options.transform), validation::checkHostMesh(mesh)})
        if (!ok) return ObjectRegistry::named(id, o.name, ok.error());
    if (auto ok = validation::checkWorldRange(validation::boxOf(mesh.positions), options.transform); !ok)
        return ObjectRegistry::named(id, o.name, ok.error());
    auto uploaded = passes::uploadMeshes(device(), {&mesh}, {.open = {options.open}});
    if (!uploaded) return ObjectRegistry::named(id, o.name, uploaded.error());
    o.host = true;
    o.gpu = uploaded->meshes[0];
    o.vertices = std::move(uploaded->buffers[0]);
    o.indices = std::move(uploaded->buffers[1]);
    AutoSettings::measureHost(o, mesh.positions);
    o.host_positions = mesh.positions;
    o.host_indices = mesh.indices;
    if (!options.open) {
        o.boundary_edges = mesh_checks::boundaryEdges(mesh.indices);
        o.volume6 = mesh_checks::signedVolume6(*executor, mesh.positions, mesh.indices);
    }
    registry.objects.push_back(std::move(o));
    objectsChanged();
    return id;
}

Result<void> CollisionWorld::removeObject(ObjectId id) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::removeObject");
    if (!scope) return scope.error();
    for (auto ok : {w.detections.notPending("removeObject"), w.detections.notBusy("removeObject")})
        if (!ok) return ok.error();
    auto o = w.registry.find(id, "removeObject");
    if (!o) return o.error();
    **o = Impl::Object{};
    w.objectsChanged();
    return {};
}

// Allowed while detections are in flight: each keeps the transforms of its submit() (the
// GPU's copy is made then, the narrow phase takes Run::meshes' at finish()).
Result<void> CollisionWorld::setTransform(ObjectId id, const Transform3x4& t) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::setTransform");
    if (!scope) return scope.error();
    auto o = w.registry.find(id, "setTransform");
    if (!o) return o.error();
    if (auto ok = validation::checkTransform(t); !ok) return w.registry.named(id, ok.error());
    // Host meshes: the sampling range now (engine meshes: by the GPU check of each run).
    if ((*o)->host)
        if (auto ok = validation::checkWorldRange((*o)->box, t); !ok) return w.registry.named(id, ok.error());
    (*o)->options.transform = t;
    if (!w.registry.source_dirty && (*o)->source_index != Impl::kNoSource)
        if (auto ok = w.registry.source.setTransform((*o)->source_index, t); !ok) return w.registry.named(id, ok.error());
    return {};
}

Result<void> CollisionWorld::setSelfCollision(ObjectId id, bool on) {
    auto scope = impl_->guard.enter("CollisionWorld::setSelfCollision");
    if (!scope) return scope.error();
    if (auto ok = impl_->detections.notPending("setSelfCollision"); !ok) return ok.error();
    auto o = impl_->registry.find(id, "setSelfCollision");
    if (!o) return o.error();
    (*o)->options.self_collision = on;
    return {};
}

Result<void> CollisionWorld::updateVertices(ObjectId id, std::span<const Float3> positions) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::updateVertices");
    if (!scope) return scope.error();
    if (auto ok = w.detections.notBusy("updateVertices"); !ok) return ok.error();
    return hostMemoryGuarded("updateVertices", [&] { return w.updateHostVertices(id, positions); });
}

Result<void> CollisionWorld::Impl::updateHostVertices(ObjectId id, std::span<const Float3> positions) {
    auto found = registry.find(id, "updateVertices");
    if (!found) return found.error();
    Object& o = **found;
    if (!o.host) return registry.named(id, Error(ErrorCode::InvalidArgument, "is a GPU mesh: write its vertex buffer instead"));
    if (positions.size() != o.gpu.vertex_count) return registry.named(id, validation::checkVertices(positions, o.gpu.vertex_count).error());
    // One pass over the caller's array, split over the executor's threads: copied into a
    // host copy and an upload buffer, checked and boxed on the way. No detection in flight
    // reads the current vertices: into the spare host copy and straight into the current
    // upload buffer (a refused update puts it back from the host copy). One does
    // (pipelining): into a copy no detection reads, which then becomes the current one.
    // Either way a refused update changes nothing. The shape (typical edge, area moment)
    // is measured in the same loop while the last settings needed it, else later, when
    // automatic settings need it (AutoSettings::measureShapes).
    Object::VertexCopy* copy = nullptr;
    if (detections.reads(id, o.gpu.vertices, o.host_positions.data())) {
        auto free = registry.freeCopy(device(), detections, id, o);
        if (!free) return registry.named(id, free.error());
        copy = *free;
    }
    std::vector<Float3>& host_copy = copy ? copy->positions : o.spare_positions;
    vk::Buffer& upload_buffer = copy ? copy->upload : o.vertices;
    host_copy.resize(positions.size());
    auto* upload = static_cast<Float3*>(upload_buffer.mapped());
    const bool measure = auto_settings.wantsShape(o);
    vertex_scans::Shape shape;
    const vertex_scans::VertexScan scan =
        measure ? vertex_scans::copyScanAndMeasure(*executor, positions, host_copy, upload, o.host_indices, shape)
                : vertex_scans::copyAndScan(*executor, positions, host_copy, upload);
    auto refused = [&](const Error& e) {
        if (!copy) std::memcpy(upload, o.host_positions.data(), positions.size_bytes());
        return registry.named(id, e);
    };
    if (!scan.finite) return refused(validation::nonFiniteVertex(scan.first_bad));
    if (auto ok = validation::checkWorldRange(scan.box, o.options.transform); !ok) return refused(ok.error());
    upload_buffer.flush();
    std::swap(o.host_positions, host_copy);  // (detections read their own spans: Run::positions)
    if (copy) {
        std::swap(o.vertices, copy->upload);
        o.gpu.vertices = o.vertices.address();
    }
    o.box = scan.box;
    o.max_abs = scan.max_abs;
    o.shape_stale = !measure;
    if (measure) o.shape = shape;
    return {};
}

Result<void> CollisionWorld::setPairFilter(std::function<bool(ObjectId, ObjectId)> may_collide) {
    auto scope = impl_->guard.enter("CollisionWorld::setPairFilter");
    if (!scope) return scope.error();
    if (auto ok = impl_->detections.notPending("setPairFilter"); !ok) return ok.error();
    impl_->registry.pair_filter = std::move(may_collide);
    impl_->registry.pair_mask_dirty = true;
    return {};
}

std::size_t CollisionWorld::objectCount() const noexcept {
    const auto& objects = impl_->registry.objects;
    return static_cast<std::size_t>(std::count_if(objects.begin(), objects.end(), [](const auto& o) { return o.alive; }));
}

std::size_t CollisionWorld::triangleCount() const noexcept {
    std::size_t n = 0;
    for (const auto& o : impl_->registry.objects) n += o.alive ? o.gpu.triangle_count : 0;
    return n;
}

Result<DetectSettings> CollisionWorld::resolveSettings(const DetectSettings& settings) const {
    auto scope = impl_->guard.enter("CollisionWorld::resolveSettings");
    if (!scope) return scope.error();
    std::vector<passes::GpuMesh> meshes;
    std::vector<ObjectId> ids;
    impl_->registry.liveMeshes(meshes, ids);
    std::string note;
    const DetectSettings s = impl_->resolve(settings, &note);
    for (auto ok : {validation::checkScene(meshes), validation::checkSettings(s, impl_->device())})
        if (!ok) return ok.error();
    return s;
}

}  // namespace vkcollide
