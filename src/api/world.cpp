// CollisionWorld: the registry of objects and the public methods. Automatic settings are
// in settings.cpp, one detection in detect.cpp, every input rule in validation.cpp.
#include "vkcollide/world.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <stdexcept>

#include "api/validation.hpp"
#include "api/world_impl.hpp"
#include "config.h"
#include "passes/engine_mesh.hpp"
#include "passes/mesh_upload.hpp"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

// No exception crosses the API: host memory running out anywhere in a detection (the
// records read back, the union of three axes, the narrow phase's arrays, the result)
// becomes OutOfMemory, and the detection in flight is forgotten (its GPU work is waited
// for like a timed-out one's).
template <typename F>
auto hostGuarded(passes::Detection& detection, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        detection.abandon();
        return Error(ErrorCode::OutOfMemory, "host memory ran out during the detection");
    } catch (const std::length_error&) {
        detection.abandon();
        return Error(ErrorCode::OutOfMemory, "an array of the detection would exceed its largest size");
    }
}

}  // namespace

std::string CollisionWorld::Impl::who(ObjectId id, const std::string& name) {
    return "object " + std::to_string(id) + " ('" + name + "')";
}

Result<CollisionWorld::Impl::Object*> CollisionWorld::Impl::find(ObjectId id, const char* what) {
    if (id >= objects.size() || !objects[id].alive)
        return Error(ErrorCode::InvalidArgument, std::string(what) + ": no object with id " + std::to_string(id));
    return &objects[id];
}

Result<void> CollisionWorld::Impl::notPending(const char* what) const {
    if (pending()) return Error(ErrorCode::InvalidArgument, std::string(what) + " while a detection is in flight: collect() it first");
    return {};
}

Result<void> CollisionWorld::Impl::notBusy(const char* what) const {
    if (detection->busy())
        return Error(ErrorCode::Timeout, std::string(what) + " while the GPU work of a detection that timed out still runs " +
                                             "(state() is Busy until it ends): try again later");
    return {};
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
CollisionWorld::~CollisionWorld() = default;  // Impl's detection waits for work in flight first

Result<std::unique_ptr<CollisionWorld>> CollisionWorld::create(Context& context, const WorldOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->context = &context;
    // The default method's pipelines now; the other's when a detection first asks for it.
    auto detection = passes::Detection::create(context.device(), Impl::methodFactory(DetectSettings{}.method));
    if (!detection) return detection.error();
    impl->detection = std::move(*detection);
    impl->pool = std::make_unique<ThreadPool>(options.threads);
    return std::unique_ptr<CollisionWorld>(new CollisionWorld(std::move(impl)));
}

Result<ObjectId> CollisionWorld::addMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("addMesh"); !ok) return ok.error();
    Impl::Object o;
    const ObjectId id = w.newId(options, o);
    // Every rule before anything is uploaded.
    for (auto ok : {validation::checkTransform(options.transform), validation::checkHostMesh(mesh)})
        if (!ok) return Impl::named(id, o.name, ok.error());
    if (auto ok = validation::checkWorldRange(validation::boxOf(mesh.positions), options.transform); !ok)
        return Impl::named(id, o.name, ok.error());
    auto uploaded = passes::uploadMeshes(w.device(), {&mesh}, {.open = {options.open}});
    if (!uploaded) return Impl::named(id, o.name, uploaded.error());
    o.host = true;
    o.gpu = uploaded->meshes[0];
    o.vertices = std::move(uploaded->buffers[0]);
    o.indices = std::move(uploaded->buffers[1]);
    Impl::measureHost(o, mesh.positions, mesh.indices);
    o.host_positions = mesh.positions;
    o.host_indices = mesh.indices;
    w.objects.push_back(std::move(o));
    w.objectsChanged();
    return id;
}

Result<ObjectId> CollisionWorld::addGpuMesh(const GpuMeshDesc& d, const ObjectOptions& options) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("addGpuMesh"); !ok) return ok.error();
    Impl::Object o;
    const ObjectId id = w.newId(options, o);
    if (auto ok = validation::checkGpuMeshDesc(d); !ok) return Impl::named(id, o.name, ok.error());
    // The declared sizes cannot exceed what the buffers were created with.
    const VkDeviceSize vertex_capacity = passes::engineBufferCapacity(w.device(), d.vertex_buffer);
    const VkDeviceSize index_capacity = passes::engineBufferCapacity(w.device(), d.index_buffer);
    for (auto ok : {validation::checkDeclaredSizes(d, vertex_capacity, index_capacity), validation::checkTransform(options.transform),
                    validation::checkTypicalEdge(options.typical_edge_length)})
        if (!ok) return Impl::named(id, o.name, ok.error());
    o.gpu = passes::describeEngineMesh(w.device(), d, options.open);
    if (auto ok = validation::checkEngineAddresses(o.gpu, d); !ok) return Impl::named(id, o.name, ok.error());
    o.edge_length = options.typical_edge_length;
    w.objects.push_back(std::move(o));
    w.objectsChanged();
    return id;
}

Result<void> CollisionWorld::removeObject(ObjectId id) {
    Impl& w = *impl_;
    for (auto ok : {w.notPending("removeObject"), w.notBusy("removeObject")})
        if (!ok) return ok.error();
    auto o = w.find(id, "removeObject");
    if (!o) return o.error();
    **o = Impl::Object{};
    w.objectsChanged();
    return {};
}

Result<void> CollisionWorld::setTransform(ObjectId id, const Transform3x4& t) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("setTransform"); !ok) return ok.error();
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
    auto o = impl_->find(id, "setSelfCollision");
    if (!o) return o.error();
    (*o)->options.self_collision = on;
    return {};
}

Result<void> CollisionWorld::updateVertices(ObjectId id, std::span<const Float3> positions) {
    Impl& w = *impl_;
    for (auto ok : {w.notPending("updateVertices"), w.notBusy("updateVertices")})
        if (!ok) return ok.error();
    auto found = w.find(id, "updateVertices");
    if (!found) return found.error();
    Impl::Object& o = **found;
    if (!o.host) return w.named(id, Error(ErrorCode::InvalidArgument, "is a GPU mesh: write its vertex buffer instead"));
    if (auto ok = validation::checkVertices(positions, o.gpu.vertex_count); !ok) return w.named(id, ok.error());
    if (auto ok = validation::checkWorldRange(validation::boxOf(positions), o.options.transform); !ok) return w.named(id, ok.error());
    std::memcpy(o.vertices.mapped(), positions.data(), positions.size_bytes());
    o.vertices.flush();
    // Same count: the source's view of host_positions stays valid.
    std::memcpy(o.host_positions.data(), positions.data(), positions.size_bytes());
    Impl::measureHost(o, positions, o.host_indices);
    return {};
}

void CollisionWorld::setPairFilter(std::function<bool(ObjectId, ObjectId)> may_collide) {
    impl_->pair_filter = std::move(may_collide);
    impl_->pair_mask_dirty = true;
}

std::size_t CollisionWorld::objectCount() const noexcept {
    return static_cast<std::size_t>(std::count_if(impl_->objects.begin(), impl_->objects.end(), [](const auto& o) { return o.alive; }));
}

std::size_t CollisionWorld::triangleCount() const noexcept {
    std::size_t n = 0;
    for (const auto& o : impl_->objects) n += o.alive ? o.gpu.triangle_count : 0;
    return n;
}

bool CollisionWorld::pending() const noexcept { return impl_->pending(); }

WorldState CollisionWorld::state() const {
    if (impl_->device_lost) return WorldState::DeviceLost;
    return impl_->detection->busy() ? WorldState::Busy : WorldState::Ready;
}

Result<DetectSettings> CollisionWorld::resolveSettings(const DetectSettings& settings) const {
    std::vector<passes::GpuMesh> meshes;
    std::vector<ObjectId> ids;
    impl_->liveMeshes(meshes, ids);
    std::string note;
    const DetectSettings s = impl_->resolve(settings, &note);
    for (auto ok : {validation::checkScene(meshes), validation::checkSettings(s, impl_->context->device())})
        if (!ok) return ok.error();
    return s;
}

Result<DetectResult> CollisionWorld::detect(const DetectSettings& settings) {
    return hostGuarded(*impl_->detection, [&]() -> Result<DetectResult> {
        if (auto ok = impl_->start(settings, settings.measure_layers); !ok) return ok.error();
        return impl_->collect();
    });
}

Result<void> CollisionWorld::submit(const DetectSettings& settings) {
    return hostGuarded(*impl_->detection, [&] { return impl_->start(settings, false); });
}

Result<DetectResult> CollisionWorld::collect() {
    return hostGuarded(*impl_->detection, [&] { return impl_->collect(); });
}

}  // namespace vkcollide
