// CollisionWorld: objects, automatic settings, and one detection = GPU broad phase +
// CPU narrow phase.
#include "vkcollide/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "passes/broad_phase.hpp"
#include "passes/compute_sampling.hpp"
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

// Automatic resolution: about this many pixels along a typical triangle edge.
constexpr double kPixelsPerEdge = 4.0;
constexpr std::uint32_t kMinAutoResolution = 64, kMaxAutoResolution = 2048;

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
    std::unique_ptr<passes::BroadPhase> broad;
    std::unique_ptr<ThreadPool> pool;
    std::vector<Object> objects;
    std::function<bool(ObjectId, ObjectId)> pair_filter;
    std::uint32_t last_depth_complexity = 0;
    bool depth_complexity_known = false;

    // The detection in flight.
    bool pending = false;
    std::vector<ObjectId> run_ids;  // broad-phase object index -> ObjectId
    DetectSettings run_settings;
    std::string run_note;
    Clock::time_point run_start;
    std::optional<passes::BroadPhaseResult> run_ready;  // a measuring submit() finished at once

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
    void objectsChanged() { depth_complexity_known = false; }

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
    Result<passes::BroadPhaseResult> runBroad(const DetectSettings& s, bool measure, std::vector<passes::GpuMesh>& meshes);
    Result<DetectResult> finish(passes::BroadPhaseResult broad);
    Result<void> start(const DetectSettings& settings, bool measure);
};

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::~CollisionWorld() {
    // Never free buffers the GPU may still read.
    if (impl_ && impl_->pending) (void)impl_->broad->collect();
}

Result<std::unique_ptr<CollisionWorld>> CollisionWorld::create(Context& context, const WorldOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->context = &context;
    auto bp = passes::BroadPhase::create(context.device());
    if (!bp) return bp.error();
    impl->broad = std::move(*bp);
    impl->pool = std::make_unique<ThreadPool>(options.threads);
    return std::unique_ptr<CollisionWorld>(new CollisionWorld(std::move(impl)));
}

Result<ObjectId> CollisionWorld::addMesh(const HostMesh& mesh, const ObjectOptions& options) {
    Impl& w = *impl_;
    if (auto ok = w.notPending("addMesh"); !ok) return ok.error();
    Impl::Object o;
    const ObjectId id = w.newId(options, o);
    const std::string who = "object " + std::to_string(id) + " ('" + o.name + "'): ";
    if (auto ok = validateMesh(mesh); !ok) return Error(ok.error().code(), who + ok.error().message());
    for (float t : options.transform)
        if (!std::isfinite(t)) return Error(ErrorCode::InvalidArgument, who + "transform is not finite");
    if (mesh.triangleCount() >= gpu::kMaxTriangles) return Error(ErrorCode::InvalidMesh, who + "has 2^30 triangles or more");
    auto vb = vk::Buffer::create(w.device(), mesh.positions.size() * sizeof(Float3), 0, vk::MemoryKind::Upload, o.name + "-vertices");
    if (!vb) return Error(vb.error().code(), who + vb.error().message(), vb.error().vkResult());
    auto ib = vk::Buffer::create(w.device(), mesh.indices.size() * 4, 0, vk::MemoryKind::Upload, o.name + "-indices");
    if (!ib) return Error(ib.error().code(), who + ib.error().message(), ib.error().vkResult());
    std::memcpy(vb->mapped(), mesh.positions.data(), mesh.positions.size() * sizeof(Float3));
    std::memcpy(ib->mapped(), mesh.indices.data(), mesh.indices.size() * 4);
    vb->flush();
    ib->flush();
    o.host = true;
    o.gpu.vertices = vb->address();
    o.gpu.vertex_stride = sizeof(Float3);
    o.gpu.vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
    o.gpu.indices = ib->address();
    o.gpu.triangle_count = static_cast<std::uint32_t>(mesh.triangleCount());
    o.gpu.open = options.open;
    o.vertices = std::move(*vb);
    o.indices = std::move(*ib);
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
            s.resolution = 512;
            why += (why.empty() ? "" : "; ") + std::string("resolution 512 (no host geometry or edge length to measure)");
        }
    }
    if (!s.open_epsilon) {
        s.open_epsilon = open_triangles > 0 ? static_cast<float>(0.5 * open_edge / open_triangles) : 0.0f;
        if (open_triangles > 0) why += (why.empty() ? "" : "; ") + std::string("open epsilon half the open objects' typical edge");
    }
    if (note) *note = why;
    return s;
}

Result<passes::BroadPhaseResult> CollisionWorld::Impl::runBroad(const DetectSettings& s, bool measure,
                                                              std::vector<passes::GpuMesh>& meshes) {
    meshes.clear();
    run_ids.clear();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        if (!objects[i].alive) continue;
        passes::GpuMesh m = objects[i].gpu;
        m.transform = objects[i].options.transform;
        meshes.push_back(m);
        run_ids.push_back(static_cast<ObjectId>(i));
    }
    passes::BroadPhaseSettings b;
    b.resolution = *s.resolution;
    b.direction = *s.direction;
    b.layer_cap = s.layer_cap;
    b.dual = s.dual;
    b.packing = s.packing;
    b.backend = s.backend;
    b.open_epsilon = *s.open_epsilon;
    b.region = s.region;
    auto named = [&](Error e) {
        // The broad phase names objects by their index in the run; name them by id.
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
    };
    if (measure || !depth_complexity_known) {
        auto r = broad->run(meshes, b);
        if (!r) return named(r.error());
        return r;
    }
    if (auto ok = broad->submit(meshes, b, std::max(last_depth_complexity, 1u)); !ok) return named(ok.error());
    pending = true;
    return passes::BroadPhaseResult{};
}

Result<DetectResult> CollisionWorld::Impl::finish(passes::BroadPhaseResult broad_result) {
    DetectResult out;
    DetectStats& st = out.stats;
    st.triangles = broad_result.triangles;
    st.collision_rays = broad_result.collision_rays;
    st.triangles_downloaded = broad_result.records.size();
    st.objects = static_cast<std::uint32_t>(run_ids.size());
    st.resolution = *run_settings.resolution;
    st.direction = *run_settings.direction;
    st.depth_complexity = broad_result.depth_complexity;
    st.layers = broad_result.layers;
    st.peel_passes = broad_result.peel_steps;
    st.dual = run_settings.dual;
    const std::uint32_t cap = run_settings.layer_cap;
    st.layers_short = broad_result.depth_complexity > broad_result.layers && (cap == 0 || broad_result.layers < cap);
    st.settings_note = run_note;
    st.backend = passes::toString(broad_result.backend);
    st.backend_reason = broad_result.backend_reason;
    for (const auto& p : broad_result.passes) st.gpu_passes.push_back({p.name, p.gpu_ms});
    st.sampling_ms = broad_result.sampling_ms;
    st.merging_ms = broad_result.merging_ms;
    st.separation_ms = broad_result.separation_ms;
    st.packing_ms = broad_result.packing_ms;
    st.readback_ms = broad_result.readback_ms;
    last_depth_complexity = broad_result.depth_complexity;
    depth_complexity_known = true;

    NarrowOptions options;
    for (ObjectId id : run_ids) options.self_collision.push_back(objects[id].options.self_collision);
    if (pair_filter) {
        options.may_collide = [this](std::uint32_t a, std::uint32_t b) { return pair_filter(run_ids[a], run_ids[b]); };
    }
    const auto t0 = Clock::now();
    auto narrow = runNarrowPhase(broad_result.records, options, *pool);
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
    st.gpu_memory_bytes = broad->memoryBytes();
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
    std::vector<passes::GpuMesh> meshes;
    auto r = runBroad(*s, measure, meshes);
    if (!r) return r.error();
    if (!pending) run_ready = std::move(*r);  // measured: already complete
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
    passes::BroadPhaseResult broad;
    if (w.run_ready) {
        broad = std::move(*w.run_ready);
        w.run_ready.reset();
    } else {
        auto r = w.broad->collect();
        w.pending = false;
        if (!r) return r.error();
        broad = std::move(*r);
    }
    w.pending = false;
    return w.finish(std::move(broad));
}

}  // namespace vkcollide
