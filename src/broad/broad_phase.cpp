#include "broad/broad_phase.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "broad/peeling/peeling_method.hpp"  // broadPhaseMemory plans its rows
#include "broad/projection.hpp"
#include "common/broadphase.h"

namespace vkcollide::passes {
namespace {

// The rows every method shares.
CoreBuffers addCoreRows(BufferTable& t) {
    using vk::MemoryKind;
    using F = gpu::Frame;
    CoreBuffers c;
    c.frame = t.add({"frame", MemoryKind::Upload, [](const RunShape&) { return VkDeviceSize(sizeof(gpu::Frame)); }});
    c.objects = t.add({"objects", MemoryKind::Upload,
                       [](const RunShape& s) { return VkDeviceSize(sizeof(gpu::ObjectGpu)) * std::max<std::uint32_t>(s.objects, 1); },
                       &F::objects});
    // Host-readable after a run (gpuProjection): the fit writes it on the GPU.
    c.projection = t.add({"projection", MemoryKind::Upload, [](const RunShape&) { return VkDeviceSize(sizeof(gpu::Projection)); },
                          &F::projection, true});
    c.header = t.add({"header", MemoryKind::DeviceLocal, [](const RunShape&) { return VkDeviceSize(sizeof(gpu::Header)); }, &F::header});
    c.header_readback = t.add({"header-readback", MemoryKind::Readback,
                               [](const RunShape&) { return VkDeviceSize(sizeof(gpu::Header)); }, nullptr, true});
    return c;
}

// The rules validation.cpp checks at the API, asserted here.
[[maybe_unused]] bool meetsPreconditions(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s, bool conservative,
                                         const MethodTraits& traits) {
    const std::uint32_t n = s.resolution;
    const float dl = s.direction[0] * s.direction[0] + s.direction[1] * s.direction[1] + s.direction[2] * s.direction[2];
    const bool resolution_ok = traits.power_of_two_resolution
                                   ? n >= gpu::kMinResolution && n <= gpu::kMaxResolution && (n & (n - 1)) == 0
                                   : n >= 1 && n <= gpu::kMaxResolution;
    bool ok = resolution_ok && dl > 0 && std::isfinite(dl) &&
              !meshes.empty() && s.open_epsilon >= 0 && std::isfinite(s.open_epsilon) && s.closed_epsilon >= 0 &&
              std::isfinite(s.closed_epsilon) && s.coverage != Coverage::Best && (s.coverage != Coverage::Conservative || conservative);
    if (s.region)
        for (int a = 0; a < 3; ++a) ok = ok && std::isfinite((*s.region)[a]) && std::isfinite((*s.region)[a + 3]) && (*s.region)[a] <= (*s.region)[a + 3];
    std::uint64_t total = 0;
    for (const GpuMesh& m : meshes) {
        ok = ok && m.triangle_count > 0 && m.vertex_count > 0 && m.vertices && m.indices && m.vertex_stride >= 12 &&
             m.vertex_stride % 4 == 0 && m.vertices % 4 == 0 && m.indices % 4 == 0;
        for (float t : m.transform) ok = ok && std::isfinite(t);
        total += m.triangle_count;
    }
    if (s.pair_mask) ok = ok && s.pair_mask->objects == meshes.size();
    return ok && total < gpu::kMaxTriangles;
}

// The world AABB of a box in basis coordinates (the bounds pass's measure): each basis
// axis contributes its interval along its unit vector.
std::optional<std::array<float, 6>> worldBox(const ProjectionBasis& basis, const BasisBounds& b) {
    const std::array<float, 3>* axes[3] = {&basis.u, &basis.v, &basis.d};
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        if (!(b.lo[k] <= b.hi[k]) || !std::isfinite(b.lo[k]) || !std::isfinite(b.hi[k])) return std::nullopt;
        for (int w = 0; w < 3; ++w) {
            const double x0 = double((*axes[k])[w]) * b.lo[k], x1 = double((*axes[k])[w]) * b.hi[k];
            lo[w] += std::min(x0, x1), hi[w] += std::max(x0, x1);
        }
    }
    return std::array<float, 6>{float(lo[0]), float(lo[1]), float(lo[2]), float(hi[0]), float(hi[1]), float(hi[2])};
}

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

gpu::ObjectGpu objectGpu(const GpuMesh& m, std::uint32_t triangle_base) {
    gpu::ObjectGpu o{};
    o.vertices = m.vertices;
    o.indices = m.indices;
    o.vertex_stride = m.vertex_stride;
    o.vertex_count = m.vertex_count;
    o.triangle_count = m.triangle_count;
    o.triangle_base = triangle_base;
    o.flags = (m.open ? gpu::kObjectOpen : 0u) | (m.index16 ? gpu::kObjectIndex16 : 0u) |
              (m.check_on_gpu ? gpu::kObjectCheckOnGpu : 0u) | (m.self_collision ? gpu::kObjectSelfCollide : 0u);
    for (int r = 0; r < 3; ++r) o.model[r] = {m.transform[r * 4], m.transform[r * 4 + 1], m.transform[r * 4 + 2], m.transform[r * 4 + 3]};
    return o;
}

std::uint64_t waitNs(const BroadPhaseSettings& s) { return graph::waitNs(s.timeout_ns, s.deadline); }

Error timeoutOfRun(const BroadPhaseSettings& s, Error e) { return graph::timeoutOfDetection(s.timeout_ns, s.deadline.has_value(), std::move(e)); }

std::string describe(const ObjectFault& f) {
    const std::string affected = " (" + std::to_string(f.triangles_affected) + " triangles affected)";
    switch (f.kind) {
        case ObjectFault::Kind::IndexOutOfRange:
            return "triangle " + std::to_string(f.triangle) + " has an index >= the vertex count " + std::to_string(f.vertex_count) + affected;
        case ObjectFault::Kind::NonFinitePosition:
            return "triangle " + std::to_string(f.triangle) +
                   " has a vertex position that is NaN or infinite, or beyond +-1e30 after the object's transform (the sampling range)" +
                   affected;
        case ObjectFault::Kind::OutOfRange:
            return "triangle " + std::to_string(f.triangle) +
                   " has a position, transform entry or world coordinate of magnitude 2^62 or more (the reliable method's limit)";
    }
    return "triangle " + std::to_string(f.triangle) + ": unknown problem";
}

VkDeviceSize broadPhaseMemory(std::uint32_t resolution, std::uint32_t triangles, std::uint32_t objects, bool depth_aware) {
    BufferTable table;
    addCoreRows(table);
    PeelingMethod::addRows(table);
    return table.planBytes({resolution, triangles, objects, false, depth_aware});
}

Result<std::unique_ptr<BroadPhase>> BroadPhase::create(vk::Device& device, MethodFactory method) {
    std::unique_ptr<BroadPhase> bp(new BroadPhase(device));
    bp->core_ = addCoreRows(bp->table_);
    auto common = CommonStages::create(device);
    if (!common) return common.error();
    bp->common_ = std::move(*common);
    auto m = method(device, bp->table_, bp->core_);
    if (!m) return m.error();
    bp->method_ = std::move(*m);
    return bp;
}

BroadPhase::~BroadPhase() {
    // The executor is destroyed after the buffers (declared first): wait here.
    (void)executor_.settle(~std::uint64_t(0));
}

Result<void> BroadPhase::prepare(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
    const Clock::time_point t0 = Clock::now();
    auto ok = prepareRun(meshes, s);
    run_.host = graph::HostTimes{};
    run_.host.upload_ms = msSince(t0);
    return ok;
}

Result<void> BroadPhase::prepareRun(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s) {
    assert(meetsPreconditions(meshes, s, device_->conservative_rasterization, method_->traits()));
    // Work an earlier run gave up on (Timeout) may still read these buffers.
    if (auto ok = settle(waitNs(s)); !ok) {
        if (ok.error().code() != ErrorCode::Timeout) return ok.error();
        return Error(ErrorCode::Timeout, "the GPU work of an earlier detection that timed out is still running (" +
                                             ok.error().message() + " more)", ok.error().vkResult());
    }
    executor_.setWaitPolling(s.poll_ns);
    executor_.setPollHook(s.poll_hook);
    std::uint64_t total = 0;
    for (const GpuMesh& m : meshes) total += m.triangle_count;
    const RunShape shape{s.resolution, static_cast<std::uint32_t>(total), static_cast<std::uint32_t>(meshes.size()), s.keep_ray_image,
                         s.depth_aware};
    if (auto ok = table_.reserve(*device_, shape); !ok) return ok.error();
    gpu::Frame fr{};
    if (auto ok = method_->prepare(s, shape, fr); !ok) return ok.error();

    // Objects and the frame description (vectors reused run to run: no allocation in a
    // steady scene).
    std::vector<gpu::ObjectGpu>& objs = run_.objects;
    objs.resize(shape.objects);
    std::uint32_t base = 0;
    std::uint64_t vertex_base = 0;  // within the bounds pass's batch (CommonStages::recordFront)
    for (std::uint32_t i = 0; i < shape.objects; ++i) {
        const GpuMesh& m = meshes[i];
        gpu::ObjectGpu o = objectGpu(m, base);
        if (vertex_base + m.vertex_count > kBoundsBatchVertices) vertex_base = 0;  // a new batch
        o.vertex_base = static_cast<std::uint32_t>(vertex_base);
        vertex_base += m.vertex_count;
        objs[i] = o;
        base += m.triangle_count;
    }
    std::memcpy(table_.buffer(core_.objects).mapped(), objs.data(), objs.size() * sizeof(gpu::ObjectGpu));
    table_.buffer(core_.objects).flush();
    table_.fillFrame(fr);
    fr.resolution = s.resolution;
    fr.object_count = shape.objects;
    fr.triangle_count = shape.triangles;
    const ProjectionBasis basis = projectionBasis(s.direction);
    for (int k = 0; k < 3; ++k)
        fr.direction_basis[k] = basis.u[k], fr.direction_basis[3 + k] = basis.v[k], fr.direction_basis[6 + k] = basis.d[k];
    fr.open_epsilon_world = s.open_epsilon;
    fr.fit_margin = s.fit_margin;
    fr.closed_epsilon_world = s.closed_epsilon;
    if (s.region) {
        // The caller's box: the same mapping the fit shader computes, done here.
        const gpu::Projection pr = regionProjection(basis, *s.region, s.open_epsilon, s.closed_epsilon);
        std::memcpy(table_.buffer(core_.projection).mapped(), &pr, sizeof(pr));
        table_.buffer(core_.projection).flush();
    }
    std::memcpy(table_.buffer(core_.frame).mapped(), &fr, sizeof(fr));
    table_.buffer(core_.frame).flush();

    run_.frame = fr;
    run_.settings = s;
    run_.meshes.assign(meshes.begin(), meshes.end());
    run_.any_gpu_check = std::any_of(meshes.begin(), meshes.end(), [](const GpuMesh& m) { return m.check_on_gpu; });
    run_.first = BroadPhaseResult{};
    return {};
}

RunView BroadPhase::view() const {
    return {run_.settings, run_.meshes, run_.frame, table_.buffer(core_.frame).address(), run_.any_gpu_check, run_.objects,
            table_.buffer(core_.objects).address()};
}

void BroadPhase::record(graph::Graph& g, Recording what, FollowUpStage* follow_up) {
    const Clock::time_point t0 = Clock::now();
    const RunView run = view();
    if (what == Recording::FollowUp) {
        // Its own rows only: what the run wrote stays, and the stage reads none of it but
        // the objects (uploaded by the host).
        follow_up->record(g, run);
        executor_.setMilestone({});
        run_.host.declare_ms += msSince(t0);
        return;
    }
    const GraphBuffers buffers = table_.import(g);
    method_->import(g);
    if (what == Recording::Again) {
        // The method's passes alone: the front's outputs (projection, header) stay.
        method_->record(Phase::Again, g, run, buffers);
    } else {
        if (what != Recording::Main) {
            common_->recordFront(g, run, buffers, core_, table_.cleared());
            method_->record(Phase::Measure, g, run, buffers);
        }
        if (what != Recording::Measure) method_->record(Phase::Main, g, run, buffers);
    }
    common_->recordReadback(g, buffers, core_);
    // The method's milestone in this recording, if any: collect() calls it mid-submission.
    executor_.setMilestone(method_->milestone());
    run_.host.declare_ms += msSince(t0);
}

gpu::Header BroadPhase::readHeader() const {
    const vk::Buffer& rb = table_.buffer(core_.header_readback);
    rb.invalidate();
    gpu::Header h;
    std::memcpy(&h, rb.mapped(), sizeof(h));
    return h;
}

gpu::Projection BroadPhase::gpuProjection() const {
    const vk::Buffer& b = table_.buffer(core_.projection);
    b.invalidate();
    gpu::Projection p;
    std::memcpy(&p, b.mapped(), sizeof(p));
    return p;
}

// The GPU input checks' verdict as data; the error names the object by its run index.
Result<void> BroadPhase::checkInputs(const gpu::Header& h) {
    faults_.clear();
    if (h.bad_index_count)
        faults_.push_back({h.bad_index_object, ObjectFault::Kind::IndexOutOfRange, h.bad_index_triangle, h.bad_index_count,
                           run_.meshes.at(h.bad_index_object).vertex_count});
    if (h.bad_vertex_count && !(h.bad_index_count && h.bad_vertex_object == h.bad_index_object))
        faults_.push_back({h.bad_vertex_object, ObjectFault::Kind::NonFinitePosition, h.bad_vertex_triangle, h.bad_vertex_count,
                           run_.meshes.at(h.bad_vertex_object).vertex_count});
    if (faults_.empty()) return {};
    return Error(ErrorCode::InvalidMesh, "object " + std::to_string(faults_.front().object) + ": " + describe(faults_.front()));
}

// The fitted image must be at least kMinSamplingExtent wide (config.h): narrower, and the
// projection and pixels would need subnormal floats, which GPUs flush to zero. A scene of
// subnormal coordinates is flushed to a point before it is measured: the bounds pass
// counts those vertices. (A scene that is a point in float for other reasons, e.g. tiny
// features far from the origin, keeps the fit's extent of 1: dilation still marks its
// rays, docs/stability.md case 9.) A caller's region is checked by the API instead.
Result<void> BroadPhase::checkExtent(const gpu::Header& h) const {
    if (run_.settings.region) return {};
    const BasisBounds b = boundsFromHeader(h);
    const float size = std::max(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]);
    if (size >= gpu::kMinSamplingExtent || (size == 0 && h.subnormal_vertices == 0)) return {};
    char text[160];
    if (size == 0)
        std::snprintf(text, sizeof text, "the scene's coordinates are subnormal floats (%u vertices), which the GPU flushes to zero",
                      h.subnormal_vertices);
    else
        std::snprintf(text, sizeof text, "the scene is %g world units wide across the projection direction", double(size));
    return Error(ErrorCode::LimitExceeded, std::string(text) + ", narrower than the smallest extent vkcollide can sample "
                                                               "(1e-30 world units): scale the scene up");
}

void BroadPhase::addTimings(BroadPhaseResult& result, const graph::ExecutionReport& report) {
    for (const auto& p : report.passes) {
        addStageTime(result, p);
        result.passes.push_back(p);
    }
    result.host += report.host;
}

Result<BroadPhaseResult> BroadPhase::run(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s, graph::SubmitTarget* target,
                                         bool signal) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "a broad phase is in flight: collect() it first");
    if (!method_->traits().measures) {
        // Nothing to measure: one submission.
        if (auto ok = submit(meshes, s, 0, target, signal); !ok) return ok.error();
        return collect();
    }
    if (target && target->engine)
        return Error(ErrorCode::InvalidArgument, "the peeling method measures the depth complexity in a submission of its own and "
                                                 "waits for it on the host: it cannot be recorded into an engine's command buffer");
    if (auto ok = prepare(meshes, s); !ok) return ok.error();

    // Submission 1: front and measurement; the method reads the header.
    graph::Graph g1;
    record(g1, Recording::Measure);
    if (auto ok = executor_.submit(g1, waitNs(s), target, false); !ok) return timeoutOfRun(s, ok.error());
    auto report1 = executor_.collect(waitNs(s));
    if (!report1) return timeoutOfRun(s, report1.error());
    const gpu::Header h1 = readHeader();
    if (auto ok = checkInputs(h1); !ok) return ok.error();
    if (auto ok = checkExtent(h1); !ok) return ok.error();
    if (auto ok = method_->begin(view(), &h1, report1->passes, 0); !ok) return ok.error();
    run_.first = BroadPhaseResult{};
    addTimings(run_.first, *report1);

    // Submission 2: the method's main passes.
    graph::Graph g2;
    record(g2, Recording::Main);
    if (s.deadline && waitNs(s) == 0) return timeoutOfRun(s, Error(ErrorCode::Timeout, "deadline passed"));
    if (auto ok = executor_.submit(g2, waitNs(s), target, signal); !ok) return timeoutOfRun(s, ok.error());
    pending_ = true;
    return collect();
}

Result<void> BroadPhase::submit(std::span<const GpuMesh> meshes, const BroadPhaseSettings& s, std::uint32_t layers,
                                graph::SubmitTarget* target, bool signal) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "a broad phase is in flight: collect() it first");
    if (auto ok = prepare(meshes, s); !ok) return ok.error();
    const Clock::time_point t_predict = Clock::now();
    if (auto ok = method_->begin(view(), nullptr, {}, layers); !ok) return ok.error();
    run_.host.upload_ms += msSince(t_predict);
    graph::Graph g;
    record(g, Recording::Whole);
    if (auto ok = executor_.submit(g, waitNs(s), target, signal); !ok) return timeoutOfRun(s, ok.error());
    pending_ = true;
    return {};
}

Result<graph::ExecutionReport> BroadPhase::runMore(Recording what, FollowUpStage* follow_up, const char* what_runs) {
    const BroadPhaseSettings& s = run_.settings;
    // The detection's timeout, saying which part was left when it ran out.
    const auto timedOut = [&](Error e) {
        Error out = timeoutOfRun(s, std::move(e));
        if (out.code() != ErrorCode::Timeout) return out;
        return Error(ErrorCode::Timeout, out.message() + "; it ran out at " + what_runs, out.vkResult());
    };
    if (s.deadline && waitNs(s) == 0) return timedOut(Error(ErrorCode::Timeout, "deadline passed"));
    graph::Graph g;
    record(g, what, follow_up);
    auto report = executor_.run(g, waitNs(s));
    if (!report) return timedOut(report.error());
    return report;
}

Result<FollowUpStage*> BroadPhase::followUp(FollowUpFactory factory) {
    for (auto& [made_by, stage] : follow_ups_)
        if (made_by == factory) return stage.get();
    auto stage = factory(*device_, table_);
    if (!stage) return stage.error();
    follow_ups_.emplace_back(factory, std::move(*stage));
    return follow_ups_.back().second.get();
}

Result<void> BroadPhase::runFollowUp(FollowUpStage& stage) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "a broad phase is in flight: collect() it before a follow-up stage");
    const RunView run = view();
    auto step = stage.begin(run);
    for (std::uint32_t submissions = 0; step && *step == Collected::Again; ++submissions) {
        if (submissions > kMaxMethodAgains)
            return Error(ErrorCode::VulkanError, std::string(stage.name()) + " asked for more than " + std::to_string(kMaxMethodAgains) +
                                                     " submissions (internal error)");
        auto report = runMore(Recording::FollowUp, &stage, stage.name());
        if (!report) return report.error();
        step = stage.collect(run, *report);
    }
    if (!step) return step.error();
    return {};
}

Result<BroadPhaseResult> BroadPhase::collect() {
    if (!pending_) return Error(ErrorCode::InvalidArgument, "no broad phase in flight: submit() first");
    pending_ = false;
    auto report = executor_.collect(waitNs(run_.settings));
    if (!report) return timeoutOfRun(run_.settings, report.error());

    const auto t0 = std::chrono::steady_clock::now();
    gpu::Header h = readHeader();
    if (auto ok = checkInputs(h); !ok) return ok.error();
    if (auto ok = checkExtent(h); !ok) return ok.error();
    BroadPhaseResult result = std::move(run_.first);
    addTimings(result, *report);
    result.host += run_.host;
    // A single submission measures the depth complexity in the same run; with a
    // separate measuring submission, the second header keeps the first's value.
    result.depth_complexity = h.depth_complexity;
    result.triangles = run_.frame.triangle_count;
    const ProjectionBasis basis = projectionBasis(run_.settings.direction);
    const BroadPhaseSettings& s = run_.settings;
    result.projection = s.region ? regionProjection(basis, *s.region, s.open_epsilon, s.closed_epsilon)
                                 : fitProjection(basis, boundsFromHeader(h), s.fit_margin, s.open_epsilon, s.closed_epsilon);
    if (!s.region) result.scene_box = worldBox(basis, boundsFromHeader(h));
    for (std::uint32_t agains = 0;; ++agains) {
        auto collected = method_->collect(view(), h, result);
        if (!collected) {
            if (collected.error().code() == ErrorCode::InvalidMesh)
                if (const std::optional<ObjectFault> f = method_->fault(); f && f->object < run_.meshes.size()) {
                    faults_.push_back(*f);
                    return Error(ErrorCode::InvalidMesh, "object " + std::to_string(f->object) + ": " + describe(*f));
                }
            return collected.error();
        }
        if (*collected == Collected::Done) break;
        if (agains == kMaxMethodAgains)
            return Error(ErrorCode::VulkanError, "the broad phase's method asked for more than " + std::to_string(kMaxMethodAgains) +
                                                     " submissions after the first (internal error)");
        // Its times join the run's.
        auto more = runMore(Recording::Again, nullptr, "the method's passes");
        if (!more) return more.error();
        addTimings(result, *more);
        h = readHeader();  // what the method's passes counted in it since
    }
    result.readback_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace vkcollide::passes
