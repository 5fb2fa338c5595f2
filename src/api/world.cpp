// CollisionWorld: the registry of objects and the public methods that change it. Engine
// meshes are in engine_mesh.cpp, automatic settings in settings.cpp, one detection in
// detect.cpp, detections in flight in engine_sync.cpp, every input rule in validation.cpp.
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
std::string CollisionWorld::Impl::who(ObjectId id, const std::string& name) {
    return "object " + std::to_string(id) + " ('" + name + "')";
}

Result<CollisionWorld::Impl::Object*> CollisionWorld::Impl::find(ObjectId id, const char* what) {
    if (id >= objects.size() || !objects[id].alive)
        return Error(ErrorCode::InvalidArgument, std::string(what) + ": no object with id " + std::to_string(id));
    return &objects[id];
}

Result<void> CollisionWorld::Impl::notPending(const char* what) const {
    if (pending())
        return Error(ErrorCode::InvalidArgument, std::string(what) + " while a detection is in flight (it reads what " + what +
                                                     " changes): collect() it first");
    return {};
}

Result<void> CollisionWorld::Impl::notBusy(const char* what) const {
    if (settling())
        return Error(ErrorCode::Timeout, std::string(what) + " while the GPU work of a detection that timed out still runs " +
                                             "(state() is Busy until it ends): try again later");
    return {};
}

bool CollisionWorld::Impl::readInFlight(ObjectId id, VkDeviceAddress upload, const Float3* positions) const {
    for (const Run& r : runs) {
        if (!r.in_flight) continue;
        const auto it = std::lower_bound(r.ids.begin(), r.ids.end(), id);  // ids ascend (liveMeshes)
        if (it == r.ids.end() || *it != id) continue;
        const auto k = static_cast<std::size_t>(it - r.ids.begin());
        if (r.meshes[k].vertices == upload || r.positions[k].data() == positions) return true;
    }
    return false;
}

Result<CollisionWorld::Impl::Object::VertexCopy*> CollisionWorld::Impl::freeCopy(ObjectId id, Object& o) {
    for (Object::VertexCopy& c : o.copies)
        if (!readInFlight(id, c.upload.address(), c.positions.data())) return &c;
    // At most kMaxInFlight detections read at most that many copies, one of them the
    // current one: with kMaxInFlight copies beside it one is always free.
    if (o.copies.size() >= CollisionWorld::kMaxInFlight)
        return Error(ErrorCode::InvalidArgument, "updateVertices: every copy of the vertices is read by a detection in flight");
    auto upload = vk::Buffer::create(device(), std::size_t{o.gpu.vertex_count} * sizeof(Float3), 0, vk::MemoryKind::Upload,
                                     o.name + "-vertices-copy");
    if (!upload) return upload.error();
    o.copies.reserve(CollisionWorld::kMaxInFlight);  // moves keep each copy's positions where a run's span points
    o.copies.push_back({std::move(*upload), {}});
    return &o.copies.back();
}

Error CollisionWorld::Impl::noted(Error e) {
    if (e.code() == ErrorCode::DeviceLost) device_lost = true;
    return e;
}

ObjectId CollisionWorld::Impl::newId(const ObjectOptions& options, Object& out) const {
    out.alive = true;
    out.options = options;
    const auto id = static_cast<ObjectId>(objects.size());
    out.name = options.name.empty() ? "object " + std::to_string(id) : options.name;
    return id;
}

void CollisionWorld::Impl::liveMeshes(std::vector<passes::GpuMesh>& meshes, std::vector<ObjectId>& ids) const {
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

Result<void> CollisionWorld::Impl::syncSource(std::span<const ObjectId> ids) {
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

Result<bool> CollisionWorld::Impl::callPairFilter(ObjectId a, ObjectId b) const {
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

Result<const passes::ObjectPairMask*> CollisionWorld::Impl::pairMask(std::span<const ObjectId> ids) {
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

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::~CollisionWorld() {
    impl_->guard.requireIdle("CollisionWorld destroyed");
    // Impl's runs are destroyed first: they wait for work in flight.
}

Result<std::unique_ptr<CollisionWorld>> CollisionWorld::create(Context& context, const WorldOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->device_ref = ContextAccess::deviceRef(context);
    // The default method's pipelines now; the other's when a detection first asks for it.
    auto detection = passes::Detection::create(ContextAccess::device(context), Impl::methodFactory(DetectSettings{}.method));
    if (!detection) return detection.error();
    impl->runs[0].detection = std::move(*detection);
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
    if (auto ok = w.notPending("addMesh"); !ok) return ok.error();
    return hostMemoryGuarded("addMesh", [&]() -> Result<ObjectId> { return w.addHostMesh(mesh, options); });
}

Result<ObjectId> CollisionWorld::Impl::addHostMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Object o;
    const ObjectId id = newId(options, o);
    // Every rule before anything is uploaded.
    for (auto ok : {validation::checkTransform(options.transform), validation::checkHostMesh(mesh)})
        if (!ok) return named(id, o.name, ok.error());
    if (auto ok = validation::checkWorldRange(validation::boxOf(mesh.positions), options.transform); !ok)
        return named(id, o.name, ok.error());
    auto uploaded = passes::uploadMeshes(device(), {&mesh}, {.open = {options.open}});
    if (!uploaded) return named(id, o.name, uploaded.error());
    o.host = true;
    o.gpu = uploaded->meshes[0];
    o.vertices = std::move(uploaded->buffers[0]);
    o.indices = std::move(uploaded->buffers[1]);
    measureHost(o, mesh.positions);
    o.host_positions = mesh.positions;
    o.host_indices = mesh.indices;
    if (!options.open) {
        o.boundary_edges = mesh_checks::boundaryEdges(mesh.indices);
        o.volume6 = mesh_checks::signedVolume6(*executor, mesh.positions, mesh.indices);
    }
    objects.push_back(std::move(o));
    objectsChanged();
    return id;
}

Result<void> CollisionWorld::removeObject(ObjectId id) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::removeObject");
    if (!scope) return scope.error();
    for (auto ok : {w.notPending("removeObject"), w.notBusy("removeObject")})
        if (!ok) return ok.error();
    auto o = w.find(id, "removeObject");
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
    auto o = w.find(id, "setTransform");
    if (!o) return o.error();
    if (auto ok = validation::checkTransform(t); !ok) return w.named(id, ok.error());
    // Host meshes: the sampling range now (engine meshes: by the GPU check of each run).
    if ((*o)->host)
        if (auto ok = validation::checkWorldRange((*o)->box, t); !ok) return w.named(id, ok.error());
    (*o)->options.transform = t;
    if (!w.source_dirty && (*o)->source_index != Impl::kNoSource)
        if (auto ok = w.source.setTransform((*o)->source_index, t); !ok) return w.named(id, ok.error());
    return {};
}

Result<void> CollisionWorld::setSelfCollision(ObjectId id, bool on) {
    auto scope = impl_->guard.enter("CollisionWorld::setSelfCollision");
    if (!scope) return scope.error();
    if (auto ok = impl_->notPending("setSelfCollision"); !ok) return ok.error();
    auto o = impl_->find(id, "setSelfCollision");
    if (!o) return o.error();
    (*o)->options.self_collision = on;
    return {};
}

Result<void> CollisionWorld::updateVertices(ObjectId id, std::span<const Float3> positions) {
    Impl& w = *impl_;
    auto scope = w.guard.enter("CollisionWorld::updateVertices");
    if (!scope) return scope.error();
    if (auto ok = w.notBusy("updateVertices"); !ok) return ok.error();
    return hostMemoryGuarded("updateVertices", [&] { return w.updateHostVertices(id, positions); });
}

Result<void> CollisionWorld::Impl::updateHostVertices(ObjectId id, std::span<const Float3> positions) {
    auto found = find(id, "updateVertices");
    if (!found) return found.error();
    Object& o = **found;
    if (!o.host) return named(id, Error(ErrorCode::InvalidArgument, "is a GPU mesh: write its vertex buffer instead"));
    if (positions.size() != o.gpu.vertex_count) return named(id, validation::checkVertices(positions, o.gpu.vertex_count).error());
    // One pass over the caller's array, split over the executor's threads: copied into a
    // host copy and an upload buffer, checked and boxed on the way. No detection in flight
    // reads the current vertices: into the spare host copy and straight into the current
    // upload buffer (a refused update puts it back from the host copy). One does
    // (pipelining): into a copy no detection reads, which then becomes the current one.
    // Either way a refused update changes nothing. The shape (typical edge, area moment)
    // is measured in the same loop while the last settings needed it, else later, when
    // automatic settings need it (measureShapes).
    Object::VertexCopy* copy = nullptr;
    if (readInFlight(id, o.gpu.vertices, o.host_positions.data())) {
        auto free = freeCopy(id, o);
        if (!free) return named(id, free.error());
        copy = *free;
    }
    std::vector<Float3>& host_copy = copy ? copy->positions : o.spare_positions;
    vk::Buffer& upload_buffer = copy ? copy->upload : o.vertices;
    host_copy.resize(positions.size());
    auto* upload = static_cast<Float3*>(upload_buffer.mapped());
    const bool measure = wantsShape(o);
    vertex_scans::Shape shape;
    const vertex_scans::VertexScan scan =
        measure ? vertex_scans::copyScanAndMeasure(*executor, positions, host_copy, upload, o.host_indices, shape)
                : vertex_scans::copyAndScan(*executor, positions, host_copy, upload);
    auto refused = [&](const Error& e) {
        if (!copy) std::memcpy(upload, o.host_positions.data(), positions.size_bytes());
        return named(id, e);
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
    if (measure) o.edge_length = shape.edge_length, o.area_moment = shape.area_moment;
    return {};
}

Result<void> CollisionWorld::setPairFilter(std::function<bool(ObjectId, ObjectId)> may_collide) {
    auto scope = impl_->guard.enter("CollisionWorld::setPairFilter");
    if (!scope) return scope.error();
    if (auto ok = impl_->notPending("setPairFilter"); !ok) return ok.error();
    impl_->pair_filter = std::move(may_collide);
    impl_->pair_mask_dirty = true;
    return {};
}

std::size_t CollisionWorld::objectCount() const noexcept {
    return static_cast<std::size_t>(std::count_if(impl_->objects.begin(), impl_->objects.end(), [](const auto& o) { return o.alive; }));
}

std::size_t CollisionWorld::triangleCount() const noexcept {
    std::size_t n = 0;
    for (const auto& o : impl_->objects) n += o.alive ? o.gpu.triangle_count : 0;
    return n;
}

Result<DetectSettings> CollisionWorld::resolveSettings(const DetectSettings& settings) const {
    auto scope = impl_->guard.enter("CollisionWorld::resolveSettings");
    if (!scope) return scope.error();
    std::vector<passes::GpuMesh> meshes;
    std::vector<ObjectId> ids;
    impl_->liveMeshes(meshes, ids);
    std::string note;
    const DetectSettings s = impl_->resolve(settings, &note);
    for (auto ok : {validation::checkScene(meshes), validation::checkSettings(s, impl_->device())})
        if (!ok) return ok.error();
    return s;
}

}  // namespace vkcollide
