// CollisionWorld: objects, automatic settings, and one detection = GPU broad phase +
// CPU narrow phase.
#include "vkcollide/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "passes/broad_phase.hpp"
#include "passes/mesh_upload.hpp"
#include "passes/projection.hpp"
#include "vk/device.hpp"
#include "vk/resources.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Largest factor by which the transform stretches a length (row norms bound it).
float maxScale(const Transform3x4& t) {
    float s = 0;
    for (int r = 0; r < 3; ++r) s = std::max(s, std::sqrt(t[r * 4] * t[r * 4] + t[r * 4 + 1] * t[r * 4 + 1] + t[r * 4 + 2] * t[r * 4 + 2]));
    return s;
}

std::uint32_t nextPowerOfTwo(double x) {
    std::uint32_t p = 1;
    while (p < x && p < (1u << 30)) p *= 2;
    return p;
}

using gpu::kFallbackResolution;
using gpu::kMaxAutoResolution;
using gpu::kMinAutoResolution;
using gpu::kOpenEpsilonPerEdge;
using gpu::kPixelsPerEdge;

}  // namespace

struct CollisionWorld::Impl {
    struct Object {
        bool alive = false;
        std::string name;
        ObjectOptions options;
        bool host = false;
        vk::Buffer vertices, indices;  // host meshes: uploaded copies
        // Host meshes: the indices again, for measuring after updateVertices (reading the
        // upload buffer back would cross the bus: it may be write-combined device memory).
        std::vector<std::uint32_t> host_indices;
        passes::GpuMesh gpu;           // addresses, counts, flags (transform set per run)
        // Host meshes: object-space box and mean edge length (object units).
        std::array<float, 6> box{};
        float edge_length = 0;
    };

    Context* context = nullptr;
    // One broad phase per sampling direction (the second and third only for axes = 3).
    std::array<std::unique_ptr<passes::BroadPhase>, 3> broads;
    std::unique_ptr<ThreadPool> pool;
    std::vector<Object> objects;
    std::function<bool(ObjectId, ObjectId)> pair_filter;
    std::array<std::uint32_t, 3> last_depth_complexity{};
    std::array<bool, 3> depth_complexity_known{};

    // The detection in flight.
    bool pending = false;
    std::vector<ObjectId> run_ids;  // broad-phase object index -> ObjectId
    std::vector<passes::GpuMesh> run_meshes;
    std::vector<ExcludedObject> run_excluded;
    DetectSettings run_settings;
    std::string run_note;
    Clock::time_point run_start;
    std::uint32_t run_axes = 1;
    std::array<std::array<float, 3>, 3> run_directions{};
    std::array<bool, 3> axis_pending{};                               // submitted, to collect
    std::array<std::optional<passes::BroadPhaseResult>, 3> run_ready;  // measured runs, already complete
    std::uint32_t failed_axis = 0;                                    // the axis whose error the last call returned

    vk::Device& device() { return context->device(); }

    Result<Object*> find(ObjectId id, const char* what) {
        if (id >= objects.size() || !objects[id].alive)
            return Error(ErrorCode::InvalidArgument, std::string(what) + ": no object with id " + std::to_string(id));
        return &objects[id];
    }
    Result<void> notPending(const char* what) const {
        if (pending) return Error(ErrorCode::InvalidArgument, std::string(what) + " while a detection is in flight: collect() it first");
        return {};
    }
    ObjectId newId(const ObjectOptions& options, Object& out) {
        out.alive = true;
        out.options = options;
        const auto id = static_cast<ObjectId>(objects.size());
        out.name = options.name.empty() ? "object " + std::to_string(id) : options.name;
        return id;
    }
    void objectsChanged() { depth_complexity_known.fill(false); }

    static void measureHost(Object& o, std::span<const Float3> positions, std::span<const std::uint32_t> indices) {
        float lo[3] = {positions[0].x, positions[0].y, positions[0].z}, hi[3] = {lo[0], lo[1], lo[2]};
        for (const Float3& p : positions) {
            const float c[3] = {p.x, p.y, p.z};
            for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
        }
        o.box = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
        double sum = 0;
        auto dist = [&](std::uint32_t a, std::uint32_t b) {
            const Float3 &p = positions[a], &q = positions[b];
            return std::sqrt(double(p.x - q.x) * (p.x - q.x) + double(p.y - q.y) * (p.y - q.y) + double(p.z - q.z) * (p.z - q.z));
        };
        for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
            sum += dist(indices[t], indices[t + 1]) + dist(indices[t + 1], indices[t + 2]) + dist(indices[t + 2], indices[t]);
        o.edge_length = indices.empty() ? 0.0f : static_cast<float>(sum / double(indices.size()));
    }

    Result<DetectSettings> resolve(const DetectSettings& in, std::string* note) const;
    Error named(const Error& e) const;
    void collectRunObjects();
    passes::BroadPhaseSettings broadSettings(std::uint32_t axis) const;
    Result<void> submitAxes(bool measure);
    Result<std::vector<passes::BroadPhaseResult>> gather();
    bool excludable(const Error& e) const;
    Result<void> excludeBad();
    Result<std::vector<passes::BroadPhaseResult>> runExcluding();
    Result<DetectResult> finish(std::vector<passes::BroadPhaseResult> broad);
    Result<void> start(const DetectSettings& settings, bool measure);
};

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::~CollisionWorld() {
    // Never free buffers the GPU may still read.
    if (impl_ && impl_->pending) (void)impl_->gather();
}

Result<std::unique_ptr<CollisionWorld>> CollisionWorld::create(Context& context, const WorldOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->context = &context;
    auto bp = passes::BroadPhase::create(context.device());
    if (!bp) return bp.error();
    impl->broads[0] = std::move(*bp);
    impl->pool = std::make_unique<ThreadPool>(options.threads);
    return std::unique_ptr<CollisionWorld>(new CollisionWorld(std::move(impl)));
}

Result<ObjectId> CollisionWorld::addMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("addMesh"); !ok) return ok.error();
    Impl::Object o;
    const ObjectId id = w.newId(options, o);
    const std::string who = "object " + std::to_string(id) + " ('" + o.name + "'): ";
    // The same checked upload the broad-phase tests use (validateMesh, then the copies).
    auto uploaded = passes::uploadMeshes(w.device(), {&mesh}, {.open = {options.open}});
    if (!uploaded) return Error(uploaded.error().code(), who + uploaded.error().message(), uploaded.error().vkResult());
    for (float t : options.transform)
        if (!std::isfinite(t)) return Error(ErrorCode::InvalidArgument, who + "transform is not finite");
    if (mesh.triangleCount() >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidMesh, who + "has 2^30 triangles or more");
    o.host = true;
    o.gpu = uploaded->meshes[0];
    o.vertices = std::move(uploaded->buffers[0]);
    o.indices = std::move(uploaded->buffers[1]);
    Impl::measureHost(o, mesh.positions, mesh.indices);
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
    const std::string who = "object " + std::to_string(id) + " ('" + o.name + "'): ";
    auto bad = [&](ErrorCode code, const std::string& what) { return Error(code, who + what); };
    if (d.vertex_buffer == VK_NULL_HANDLE || d.index_buffer == VK_NULL_HANDLE)
        return bad(ErrorCode::InvalidArgument, "vertex or index buffer is VK_NULL_HANDLE");
    if (d.index_count == 0 || d.vertex_count == 0) return bad(ErrorCode::InvalidMesh, "empty mesh (no indices or no vertices)");
    if (d.index_count % 3 != 0)
        return bad(ErrorCode::InvalidMesh, "index count " + std::to_string(d.index_count) + " is not a multiple of 3");
    if (d.index_count / 3 >= gpu::kMaxTriangles) return bad(ErrorCode::InvalidMesh, "has 2^30 triangles or more");
    std::uint32_t position_bytes = 0;
    if (d.position_format == VK_FORMAT_R32G32B32_SFLOAT) position_bytes = 12;
    else if (d.position_format == VK_FORMAT_R32G32B32A32_SFLOAT) position_bytes = 16;
    else
        return bad(ErrorCode::UnsupportedFeature, "position format " + std::to_string(int(d.position_format)) +
                                                      " is not supported (use VK_FORMAT_R32G32B32_SFLOAT or R32G32B32A32_SFLOAT)");
    if (d.vertex_stride < position_bytes || d.vertex_stride % 4 != 0 || d.vertex_offset % 4 != 0 || d.index_offset % 4 != 0)
        return bad(ErrorCode::InvalidArgument, "vertex stride " + std::to_string(d.vertex_stride) +
                                                   " must hold a position and be a multiple of 4; offsets must be multiples of 4");
    if (d.index_type != VK_INDEX_TYPE_UINT32 && d.index_type != VK_INDEX_TYPE_UINT16)
        return bad(ErrorCode::UnsupportedFeature, "index type must be VK_INDEX_TYPE_UINT16 or VK_INDEX_TYPE_UINT32");
    const bool index16 = d.index_type == VK_INDEX_TYPE_UINT16;
    if (index16 && d.vertex_count > 65536)
        return bad(ErrorCode::InvalidMesh, std::to_string(d.vertex_count) + " vertices cannot be reached by 16-bit indices");
    const VkDeviceSize vertex_end = d.vertex_offset + VkDeviceSize(d.vertex_count - 1) * d.vertex_stride + position_bytes;
    // 16-bit indices are read in whole 4-byte words.
    const VkDeviceSize index_end = d.index_offset + (index16 ? (VkDeviceSize(d.index_count) * 2 + 3) / 4 * 4 : VkDeviceSize(d.index_count) * 4);
    if (vertex_end > d.vertex_buffer_size)
        return bad(ErrorCode::BufferTooSmall, "vertex buffer of " + std::to_string(d.vertex_buffer_size) + " bytes is smaller than the " +
                                                  std::to_string(vertex_end) + " bytes its " + std::to_string(d.vertex_count) + " vertices need");
    if (index_end > d.index_buffer_size)
        return bad(ErrorCode::BufferTooSmall, "index buffer of " + std::to_string(d.index_buffer_size) + " bytes is smaller than the " +
                                                  std::to_string(index_end) + " bytes its " + std::to_string(d.index_count) + " indices need" +
                                                  (index16 ? " (16-bit indices are read in whole 4-byte words: pad by 2 bytes)" : ""));
    // The declared sizes cannot exceed what the buffers were created with.
    const auto& fns = w.device().fns;
    for (auto [buffer, declared, what] : {std::tuple{d.vertex_buffer, d.vertex_buffer_size, "vertex"},
                                          std::tuple{d.index_buffer, d.index_buffer_size, "index"}}) {
        VkMemoryRequirements req{};
        fns.vkGetBufferMemoryRequirements(w.device().device, buffer, &req);
        if (req.size < declared)
            return bad(ErrorCode::BufferTooSmall, std::string(what) + " buffer is declared as " + std::to_string(declared) +
                                                      " bytes but holds at most " + std::to_string(req.size));
    }
    for (float t : options.transform)
        if (!std::isfinite(t)) return bad(ErrorCode::InvalidArgument, "transform is not finite");
    if (!(options.typical_edge_length >= 0) || !std::isfinite(options.typical_edge_length))
        return bad(ErrorCode::InvalidArgument, "typical_edge_length must be finite and >= 0");
    VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    ai.buffer = d.vertex_buffer;
    o.gpu.vertices = fns.vkGetBufferDeviceAddress(w.device().device, &ai) + d.vertex_offset;
    ai.buffer = d.index_buffer;
    o.gpu.indices = fns.vkGetBufferDeviceAddress(w.device().device, &ai) + d.index_offset;
    if (o.gpu.vertices == d.vertex_offset || o.gpu.indices == d.index_offset)
        return bad(ErrorCode::InvalidArgument, "a buffer has no device address (create it with SHADER_DEVICE_ADDRESS usage)");
    o.gpu.vertex_stride = d.vertex_stride;
    o.gpu.vertex_count = d.vertex_count;
    o.gpu.index16 = index16;
    o.gpu.triangle_count = d.index_count / 3;
    o.gpu.open = options.open;
    o.gpu.check_on_gpu = true;
    o.edge_length = options.typical_edge_length;
    w.objects.push_back(std::move(o));
    w.objectsChanged();
    return id;
}

Result<void> CollisionWorld::removeObject(ObjectId id) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("removeObject"); !ok) return ok.error();
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
    for (float x : t)
        if (!std::isfinite(x)) return Error(ErrorCode::InvalidArgument, "object " + std::to_string(id) + " ('" + (*o)->name + "'): transform is not finite");
    (*o)->options.transform = t;
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
    if (auto ok = w.notPending("updateVertices"); !ok) return ok.error();
    auto found = w.find(id, "updateVertices");
    if (!found) return found.error();
    Impl::Object& o = **found;
    const std::string who = "object " + std::to_string(id) + " ('" + o.name + "'): ";
    if (!o.host) return Error(ErrorCode::InvalidArgument, who + "is a GPU mesh: write its vertex buffer instead");
    if (positions.size() != o.gpu.vertex_count)
        return Error(ErrorCode::InvalidArgument, who + std::to_string(positions.size()) + " positions given for " +
                                                     std::to_string(o.gpu.vertex_count) + " vertices");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
            return Error(ErrorCode::InvalidMesh, who + "vertex " + std::to_string(i) + " is NaN or infinite");
    std::memcpy(o.vertices.mapped(), positions.data(), positions.size_bytes());
    o.vertices.flush();
    Impl::measureHost(o, positions, o.host_indices);
    return {};
}

void CollisionWorld::setPairFilter(std::function<bool(ObjectId, ObjectId)> may_collide) { impl_->pair_filter = std::move(may_collide); }

std::size_t CollisionWorld::objectCount() const noexcept {
    return static_cast<std::size_t>(std::count_if(impl_->objects.begin(), impl_->objects.end(), [](const auto& o) { return o.alive; }));
}

std::size_t CollisionWorld::triangleCount() const noexcept {
    std::size_t n = 0;
    for (const auto& o : impl_->objects) n += o.alive ? o.gpu.triangle_count : 0;
    return n;
}

bool CollisionWorld::pending() const noexcept { return impl_->pending; }

Result<DetectSettings> CollisionWorld::resolveSettings(const DetectSettings& settings) const {
    std::string note;
    return impl_->resolve(settings, &note);
}

// Fills every automatic field from the host's knowledge of the scene: the world box of
// the host meshes, the typical edge length of every object that has one.
Result<DetectSettings> CollisionWorld::Impl::resolve(const DetectSettings& in, std::string* note) const {
    DetectSettings s = in;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double edge_weighted = 0, edge_triangles = 0, open_edge = 0, open_triangles = 0;
    bool any = false, any_box = false;
    for (const Object& o : objects) {
        if (!o.alive) continue;
        any = true;
        const Transform3x4& t = o.options.transform;
        if (o.host) {
            for (int c = 0; c < 8; ++c) {
                const float p[3] = {o.box[(c & 1) ? 3 : 0], o.box[(c & 2) ? 4 : 1], o.box[(c & 4) ? 5 : 2]};
                for (int r = 0; r < 3; ++r) {
                    const float x = t[r * 4] * p[0] + t[r * 4 + 1] * p[1] + t[r * 4 + 2] * p[2] + t[r * 4 + 3];
                    lo[r] = std::min(lo[r], x), hi[r] = std::max(hi[r], x);
                }
            }
            any_box = true;
        }
        if (o.edge_length > 0) {
            const double e = double(o.edge_length) * maxScale(t), n = o.gpu.triangle_count;
            edge_weighted += e * n, edge_triangles += n;
            if (o.options.open) open_edge += e * n, open_triangles += n;
        }
    }
    if (!any) return Error(ErrorCode::InvalidArgument, "the world has no objects to test");
    if (s.axes != 1 && s.axes != 3) return Error(ErrorCode::InvalidArgument, "axes must be 1 or 3, not " + std::to_string(s.axes));
    std::string why;
    if (!s.direction) {
        if (any_box) {
            int thin = 0;
            for (int a = 1; a < 3; ++a)
                if (hi[a] - lo[a] < hi[thin] - lo[thin]) thin = a;
            std::array<float, 3> d{0, 0, 0};
            d[thin] = 1;
            s.direction = d;
            why += std::string("direction ") + "xyz"[thin] + " (the scene's thinnest axis)";
        } else {
            s.direction = std::array<float, 3>{0, 0, 1};
            why += "direction z (no host geometry to measure)";
        }
    }
    const double typical_edge = edge_triangles > 0 ? edge_weighted / edge_triangles : 0;
    if (!s.resolution) {
        // Extent across the image: the box's widest extent perpendicular to the direction.
        const auto& d = *s.direction;
        const double dl = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
        double extent = 0;
        if (any_box) {
            const double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
            for (int a = 0; a < 3; ++a) extent = std::max(extent, size[a] * std::sqrt(std::max(0.0, 1.0 - (d[a] / dl) * (d[a] / dl))));
            if (s.region) {
                const auto& r = *s.region;
                extent = std::max({double(r[3] - r[0]), double(r[4] - r[1]), double(r[5] - r[2])});
            }
        }
        if (extent > 0 && typical_edge > 0) {
            const double want = kPixelsPerEdge * extent / typical_edge;
            s.resolution = std::clamp(nextPowerOfTwo(want), kMinAutoResolution, kMaxAutoResolution);
            char buf[160];
            std::snprintf(buf, sizeof buf, "resolution %u (extent %.4g / typical edge %.4g x %.0f px per edge)", *s.resolution, extent,
                          typical_edge, kPixelsPerEdge);
            why += (why.empty() ? "" : "; ") + std::string(buf);
        } else {
            s.resolution = kFallbackResolution;
            why += std::string(why.empty() ? "" : "; ") + "resolution " + std::to_string(kFallbackResolution) +
                   " (no host geometry or edge length to measure)";
        }
    }
    if (!s.open_epsilon) {
        s.open_epsilon = open_triangles > 0 ? static_cast<float>(kOpenEpsilonPerEdge * open_edge / open_triangles) : 0.0f;
        if (open_triangles > 0) why += (why.empty() ? "" : "; ") + std::string("open epsilon half the open objects' typical edge");
    }
    if (s.coverage == Coverage::Best) {
        s.coverage = context->device().conservative_rasterization ? Coverage::Conservative : Coverage::Dilate;
        why += (why.empty() ? "" : "; ") + std::string(s.coverage == Coverage::Conservative
                                                           ? "coverage conservative (the device rasterises conservatively)"
                                                           : "coverage dilate (no conservative rasterisation on this device)");
    }
    if (note) *note = why;
    return s;
}

// The broad phase names objects by their index in the run; name them by id.
Error CollisionWorld::Impl::named(const Error& e) const {
    std::string m = e.message();
    const std::size_t end = m.rfind("object ", 0) == 0 ? m.find_first_not_of("0123456789", 7) : std::string::npos;
    if (end != std::string::npos && end > 7) {
        const std::size_t idx = std::stoul(m.substr(7, end - 7));
        if (idx < run_ids.size()) {
            const Object& o = objects[run_ids[idx]];
            m = "object " + std::to_string(run_ids[idx]) + " ('" + o.name + "')" + m.substr(end);
        }
    }
    return Error(e.code(), m, e.vkResult());
}

// The objects of this run: every live one that this detection has not excluded.
void CollisionWorld::Impl::collectRunObjects() {
    run_meshes.clear();
    run_ids.clear();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const auto id = static_cast<ObjectId>(i);
        if (!objects[i].alive ||
            std::any_of(run_excluded.begin(), run_excluded.end(), [&](const ExcludedObject& e) { return e.object == id; }))
            continue;
        passes::GpuMesh m = objects[i].gpu;
        m.transform = objects[i].options.transform;
        run_meshes.push_back(m);
        run_ids.push_back(id);
    }
}

passes::BroadPhaseSettings CollisionWorld::Impl::broadSettings(std::uint32_t axis) const {
    const DetectSettings& s = run_settings;
    passes::BroadPhaseSettings b;
    b.resolution = *s.resolution;
    b.direction = run_directions[axis];
    b.layer_cap = s.layer_cap;
    b.dual = s.dual;
    b.packing = s.packing;
    b.backend = s.backend;
    b.open_epsilon = *s.open_epsilon;
    b.closed_epsilon = s.closed_epsilon;
    b.coverage = s.coverage;  // resolve() turned Best into Conservative or Dilate
    b.region = s.region;
    return b;
}

// Starts every axis: measured (two submissions, waited for) or with the layers predicted
// by the last detection (one submission, left in flight). Stops at the first error; the
// axes already started stay for gather() to drain.
Result<void> CollisionWorld::Impl::submitAxes(bool measure) {
    for (std::uint32_t k = 0; k < run_axes; ++k) {
        failed_axis = k;
        if (!broads[k]) {
            auto bp = passes::BroadPhase::create(device());
            if (!bp) return bp.error();
            broads[k] = std::move(*bp);
        }
        const passes::BroadPhaseSettings b = broadSettings(k);
        if (measure || !depth_complexity_known[k]) {
            auto r = broads[k]->run(run_meshes, b);
            if (!r) return r.error();
            run_ready[k] = std::move(*r);
        } else {
            if (auto ok = broads[k]->submit(run_meshes, b, std::max(last_depth_complexity[k], 1u)); !ok) return ok.error();
            axis_pending[k] = true;
        }
    }
    return {};
}

// Waits for every axis started; always drains all of them and returns the first error.
Result<std::vector<passes::BroadPhaseResult>> CollisionWorld::Impl::gather() {
    std::vector<passes::BroadPhaseResult> out;
    std::optional<Error> first;
    for (std::uint32_t k = 0; k < broads.size(); ++k) {
        if (run_ready[k]) {
            out.push_back(std::move(*run_ready[k]));
            run_ready[k].reset();
        } else if (axis_pending[k]) {
            axis_pending[k] = false;
            auto r = broads[k]->collect();
            if (r) {
                out.push_back(std::move(*r));
            } else if (!first) {
                first = r.error();
                failed_axis = k;
            }
        }
    }
    pending = false;
    if (first) return *first;
    return out;
}

bool CollisionWorld::Impl::excludable(const Error& e) const {
    return run_settings.bad_objects == BadObjectPolicy::Exclude && e.code() == ErrorCode::InvalidMesh && broads[failed_axis] &&
           !broads[failed_axis]->faults().empty();
}

// Leaves out the objects the GPU check named, each with its own error. Why exclude and
// go on rather than fail: a bad engine buffer (a simulation that produced NaN) should not
// blind collision detection for every other object; re-running without it gives the
// others exactly the pairs they would have alone (tests/stability/faults_tests.cpp).
Result<void> CollisionWorld::Impl::excludeBad() {
    const std::size_t before = run_excluded.size();
    for (const passes::ObjectFault& f : broads[failed_axis]->faults())
        if (f.object < run_ids.size()) run_excluded.push_back({run_ids[f.object], named(Error(ErrorCode::InvalidMesh, "object " + std::to_string(f.object) + ": " + passes::describe(f)))});
    if (run_excluded.size() == before) return Error(ErrorCode::InvalidMesh, "the GPU input check failed without naming an object");
    collectRunObjects();
    if (run_meshes.empty()) return Error(ErrorCode::InvalidMesh, "no object left to test: " + run_excluded.front().error.message());
    return {};
}

// Measured runs of every axis, leaving out bad engine meshes until the check passes: one
// more run per bad object (two when two are named at once), only in frames that have one.
Result<std::vector<passes::BroadPhaseResult>> CollisionWorld::Impl::runExcluding() {
    for (;;) {
        const Result<void> ok = submitAxes(true);
        const std::uint32_t failed = failed_axis;
        auto r = gather();  // drains what submitAxes started, even after an error
        if (!ok) {
            failed_axis = failed;
            r = ok.error();
        }
        if (r || !excludable(r.error())) return r;
        if (auto ex = excludeBad(); !ex) return ex.error();
    }
}

namespace {

// A kept region mapped back to world space. A record's kept box and depth extent are a
// box in its direction's sampling space; the projection rows are orthogonal, so the
// region's world points are sum over a of unit_a * (s_a - offset_a) / scale_a, and the
// world AABB of that sum is the sum of the AABBs of its three segments. Cut to the
// triangle's own AABB; padded by 1e-4 of the image width against rounding.
std::array<double, 6> keptWorldBox(const CandidateTriangle& c, const gpu::Projection& projection) {
    const std::array<double, 6> kept = passes::samplingBoxToWorld(projection, {c.box[0], c.box[1], c.zmin}, {c.box[2], c.box[3], c.zmax});
    const double lo[3] = {kept[0], kept[1], kept[2]}, hi[3] = {kept[3], kept[4], kept[5]};
    const double image_width = passes::imageWidth(projection);
    const double pad = gpu::kKeptBoxPad * image_width;
    std::array<double, 6> out;
    for (int w = 0; w < 3; ++w) {
        double t_lo = INFINITY, t_hi = -INFINITY;
        for (const Float3& v : c.v) {
            const double x = w == 0 ? v.x : (w == 1 ? v.y : v.z);
            t_lo = std::min(t_lo, x), t_hi = std::max(t_hi, x);
        }
        out[w] = std::max(lo[w] - pad, t_lo);
        out[w + 3] = std::min(hi[w] + pad, t_hi);
        if (!(out[w] <= out[w + 3])) out[w] = t_lo, out[w + 3] = t_hi;  // rounding only: keep the triangle's box
    }
    return out;
}

// The candidates of several sampling directions, one record per triangle, with world
// boxes (keptWorldBox; the union over the directions that kept it). A pair that any one
// direction would test has overlapping boxes here too, so the exact narrow phase sees at
// least the union of the directions' tests, each once; boxes in one direction's image
// space would mean nothing next to another's.
std::vector<CandidateTriangle> uniteAxes(const std::vector<passes::BroadPhaseResult>& runs) {
    struct Entry {
        const CandidateTriangle* record;
        std::array<double, 6> box;
    };
    std::vector<Entry> all;
    for (const auto& run : runs)
        for (const CandidateTriangle& c : run.records) all.push_back({&c, keptWorldBox(c, run.projection)});
    std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) {
        return a.record->object != b.record->object ? a.record->object < b.record->object : a.record->triangle < b.record->triangle;
    });
    std::vector<CandidateTriangle> out;
    for (std::size_t i = 0; i < all.size();) {
        std::array<double, 6> box = all[i].box;
        std::size_t j = i + 1;
        for (; j < all.size() && all[j].record->object == all[i].record->object && all[j].record->triangle == all[i].record->triangle; ++j)
            for (int w = 0; w < 3; ++w) box[w] = std::min(box[w], all[j].box[w]), box[w + 3] = std::max(box[w + 3], all[j].box[w + 3]);
        CandidateTriangle c = *all[i].record;
        // Outward to float: boxes that touch in double still touch.
        auto down = [](double x) { const float f = static_cast<float>(x); return double(f) > x ? std::nextafter(f, -INFINITY) : f; };
        auto up = [](double x) { const float f = static_cast<float>(x); return double(f) < x ? std::nextafter(f, INFINITY) : f; };
        c.box[0] = down(box[0]), c.box[1] = down(box[1]), c.box[2] = up(box[3]), c.box[3] = up(box[4]);
        c.zmin = down(box[2]), c.zmax = up(box[5]);
        out.push_back(c);
        i = j;
    }
    return out;
}

}  // namespace

Result<DetectResult> CollisionWorld::Impl::finish(std::vector<passes::BroadPhaseResult> broad) {
    DetectResult out;
    out.excluded = std::move(run_excluded);
    run_excluded.clear();
    DetectStats& st = out.stats;
    st.objects = static_cast<std::uint32_t>(run_ids.size());
    st.resolution = *run_settings.resolution;
    st.direction = run_directions[0];
    st.dual = run_settings.dual;
    st.axes = run_axes;
    st.coverage = run_settings.coverage;
    st.settings_note = run_note;
    st.backend = broad[0].backend;
    st.backend_reason = broad[0].backend_reason;
    for (std::uint32_t k = 1; k < broad.size(); ++k)
        if (broad[k].backend != broad[0].backend) st.backend_reason += "; axis " + std::to_string(k) + ": " + toString(broad[k].backend) + " (" + broad[k].backend_reason + ")";
    const std::uint32_t cap = run_settings.layer_cap;
    for (std::uint32_t k = 0; k < broad.size(); ++k) {
        const passes::BroadPhaseResult& b = broad[k];
        st.triangles = b.triangles;
        st.collision_rays += b.collision_rays;
        st.triangles_downloaded += b.records.size();
        st.depth_complexity = std::max(st.depth_complexity, b.depth_complexity);
        st.layers = std::max(st.layers, b.layers);
        st.peel_passes += b.peel_steps;
        st.layers_short = st.layers_short || (b.depth_complexity > b.layers && (cap == 0 || b.layers < cap));
        const std::string prefix = broad.size() > 1 ? "axis " + std::to_string(k) + ": " : "";
        for (const auto& p : b.passes) st.gpu_passes.push_back({prefix + p.name, p.gpu_ms});
        st.sampling_ms += b.sampling_ms;
        st.merging_ms += b.merging_ms;
        st.separation_ms += b.separation_ms;
        st.packing_ms += b.packing_ms;
        st.readback_ms += b.readback_ms;
        last_depth_complexity[k] = b.depth_complexity;
        depth_complexity_known[k] = true;
    }

    NarrowOptions options;
    for (ObjectId id : run_ids) options.self_collision.push_back(objects[id].options.self_collision);
    if (pair_filter) {
        options.may_collide = [this](std::uint32_t a, std::uint32_t b) { return pair_filter(run_ids[a], run_ids[b]); };
    }
    const auto t0 = Clock::now();
    std::vector<CandidateTriangle> united;
    if (broad.size() > 1) united = uniteAxes(broad);
    auto narrow = runNarrowPhase(broad.size() > 1 ? std::span<const CandidateTriangle>(united) : broad[0].records, options, *pool);
    st.narrow_ms = msSince(t0);
    if (!narrow) return narrow.error();
    st.narrow_threads = pool->threadCount();
    st.narrow = narrow->stats;
    st.potentially_colliding_triangles = narrow->stats.potentially_colliding_triangles;
    st.triangle_tests = narrow->stats.triangle_tests;
    st.positive_tests = narrow->stats.positive_tests;
    // Run indices grow with ids, so the sorted order survives the mapping.
    out.pairs = std::move(narrow->pairs);
    for (TrianglePair& p : out.pairs) p.object_a = run_ids[p.object_a], p.object_b = run_ids[p.object_b];
    out.responses = std::move(narrow->responses);
    for (TriangleResponse& r : out.responses) r.object = run_ids[r.object];
    for (const auto& bp : broads)
        if (bp) st.gpu_memory_bytes += bp->memoryBytes();
    for (const Object& o : objects) st.gpu_memory_bytes += (o.vertices.valid() ? o.vertices.size() : 0) + (o.indices.valid() ? o.indices.size() : 0);
    st.total_ms = msSince(run_start);
    return out;
}

Result<void> CollisionWorld::Impl::start(const DetectSettings& settings, bool measure) {
    if (pending) return Error(ErrorCode::InvalidArgument, "submit while a detection is in flight: collect() it first");
    run_start = Clock::now();
    auto s = resolve(settings, &run_note);
    if (!s) return s.error();
    run_settings = *s;
    run_axes = s->axes;
    run_directions[0] = *s->direction;
    if (run_axes == 3) {
        // The other two: the image axes of the first direction (world axes when it is one).
        const passes::ProjectionBasis basis = passes::projectionBasis(*s->direction);
        run_directions[1] = basis.u;
        run_directions[2] = basis.v;
    }
    run_excluded.clear();
    collectRunObjects();
    if (measure) {
        auto r = runExcluding();
        if (!r) return named(r.error());
        for (std::uint32_t k = 0; k < r->size(); ++k) run_ready[k] = std::move((*r)[k]);
        pending = true;
        return {};
    }
    if (auto ok = submitAxes(false); !ok) {
        (void)gather();
        return named(ok.error());
    }
    pending = true;
    return {};
}

Result<DetectResult> CollisionWorld::detect(const DetectSettings& settings) {
    if (auto ok = impl_->start(settings, settings.measure_layers); !ok) return ok.error();
    return collect();
}

Result<void> CollisionWorld::submit(const DetectSettings& settings) { return impl_->start(settings, false); }

Result<DetectResult> CollisionWorld::collect() {
    Impl& w = *impl_;
    if (!w.pending) return Error(ErrorCode::InvalidArgument, "collect without a detection in flight: submit() first");
    auto r = w.gather();
    if (!r && w.excludable(r.error())) {
        // Found by the check of this submission: leave the object out and run again now.
        if (auto ex = w.excludeBad(); !ex) return ex.error();
        r = w.runExcluding();
    }
    if (!r) return w.named(r.error());
    return w.finish(std::move(*r));
}

}  // namespace vkcollide
