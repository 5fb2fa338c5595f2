// libFuzzer target: the input is a program of CollisionWorld calls (world_program.hpp):
// host and engine meshes added, re-pointed, rewritten and removed, transforms, vertex
// updates, self-collision, pair filters (one of them throws), detections with any
// settings (bad ones included), submit / collect / tryCollect / ready, and the world
// destroyed with detections in flight. Tiny meshes: on lavapipe a detection costs
// milliseconds.
//
// What must hold, or the target aborts (a finding):
// - no crash, hang, sanitizer report or validation-layer message (the Context has the
//   Khronos validation layer on; VKCOLLIDE_FUZZ_VALIDATION=0 turns it off for speed);
// - every failure is a Result error with a message and a code the call may give
//   (VulkanError, DeviceLost, GraphError, OutOfMemory never: the meshes are tiny);
// - calls the documentation refuses are refused: ids that are not live, edits while a
//   detection is in flight, meshes that validateMesh rejects, collect() with nothing in
//   flight;
// - a result keeps its promises: pairs sorted, each of live objects and triangles, none
//   the pair filter forbids, none inside an object without self-collision, at most
//   max_pairs (and then `incomplete` says so), responses one per colliding triangle with
//   its partner count, contacts sorted;
// - with host meshes only, the reliable method's complete result equals the exact
//   reference (tests/support/exact_reference.hpp) and the peeling method's is a subset.
//
// The engine's side of the contract is kept: engine buffers stay alive until the world
// is gone and are rewritten only while no detection is in flight and the world is Ready,
// and their declared sizes are the real ones (a lie there is the engine's bug, not ours).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "fuzz/world_checks.hpp"
#include "fuzz/world_context.hpp"
#include "fuzz/world_engine.hpp"
#include "fuzz/world_program.hpp"
#include "fuzz/world_values.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::fuzz {
namespace {

std::string callName(Op op) {
    constexpr std::array<const char*, kOpCount> kNames = {
        "addMesh",          "addGpuMesh",     "setGpuMeshBuffers", "(engine write)", "removeObject", "setTransform",
        "setSelfCollision", "updateVertices", "setPairFilter",     "detect",         "submit",       "collect",
        "tryCollect",       "ready",          "resolveSettings",   "(new world)"};
    return kNames[static_cast<std::size_t>(op)];
}

void requireNamed(const Error& e, Op op, std::initializer_list<ErrorCode> codes) {
    trace(callName(op) + ": " + toString(e.code()) + ": " + e.message());
    if (e.message().empty()) fail(callName(op) + " failed with an empty message (" + toString(e.code()) + ")");
    if (std::find(codes.begin(), codes.end(), e.code()) == codes.end())
        fail(callName(op) + " failed with an unexpected " + toString(e.code()) + ": " + e.message());
}

constexpr std::initializer_list<ErrorCode> kEditErrors = {ErrorCode::InvalidArgument, ErrorCode::InvalidMesh, ErrorCode::BufferTooSmall,
                                                          ErrorCode::Timeout, ErrorCode::LimitExceeded};
constexpr std::initializer_list<ErrorCode> kDetectErrors = {ErrorCode::InvalidArgument, ErrorCode::InvalidMesh,
                                                            ErrorCode::BufferTooSmall,  ErrorCode::UnsupportedFeature,
                                                            ErrorCode::Timeout,         ErrorCode::LimitExceeded};

class Session {
public:
    explicit Session(ProgramReader& in) : in_(in) { newWorld(); }
    ~Session() {
        world_.reset();  // before the engine buffers it may still read
        engine_.clear();
        requireNoValidationMessages("destroying the world");
        // Everything the world allocated on the device is freed with it.
        if (const std::uint64_t left = fuzzContext().deviceMemoryInUse(); left != 0)
            fail(std::to_string(left) + " bytes of device memory still held after the world and its engine buffers are gone");
    }

    void run() {
        for (std::size_t n = 0; n < kMaxOps && !in_.done(); ++n) {
            const Op op = static_cast<Op>(in_.byte() % kOpCount);
            trace(callName(op));
            step(op);
            requireNoValidationMessages(callName(op).c_str());
            if (world_->inFlight() != in_flight_.size() || world_->pending() != pending())
                fail("after " + callName(op) + " the world has " + std::to_string(world_->inFlight()) +
                     " detections in flight, the program counted " + std::to_string(in_flight_.size()));
            if (world_->state() == WorldState::DeviceLost) fail("the device was lost after " + callName(op));
        }
    }

private:
    // Detections cost milliseconds each; this keeps an input under a second or so.
    static constexpr std::uint32_t kMaxDetections = 10;
    static constexpr std::uint32_t kMaxNewWorlds = 2;

    ProgramReader& in_;
    std::vector<std::unique_ptr<EngineBuffers>> engine_;  // declared first: destroyed last
    std::unique_ptr<CollisionWorld> world_;
    std::map<ObjectId, Object> objects_;
    std::set<ObjectId> removed_;
    PairFilterKind filter_ = PairFilterKind::None;
    bool filter_threw_ = false;
    std::deque<Snapshot> in_flight_;
    std::uint32_t detections_ = 0;
    std::uint32_t worlds_ = 0;

    void newWorld() {
        world_.reset();
        auto w = CollisionWorld::create(fuzzContext(), {.threads = 2});
        if (!w) fail("CollisionWorld::create failed: " + w.error().message());
        world_ = std::move(*w);
        objects_.clear();
        removed_.clear();  // ids are per world
        in_flight_.clear();
        filter_ = PairFilterKind::None;
        filter_threw_ = false;
    }

    // An object id from a pick byte, and whether it is live.
    ObjectId pick(std::uint8_t b) const {
        if (b < kBogusPick && !objects_.empty()) return std::next(objects_.begin(), b % objects_.size())->first;
        if (b % 2 == 0 && !removed_.empty()) return *removed_.begin();
        return 0xFFFFFFF0u - (b % 4);
    }
    bool live(ObjectId id) const { return objects_.count(id) != 0; }
    bool pending() const { return !in_flight_.empty(); }

    HostMesh meshOf(const Geometry& g) const {
        HostMesh m;
        if (!(g.flags & kNoName)) m.name = "fuzz mesh";
        for (std::size_t i = 0; i + 2 < g.coordinates.size(); i += 3)
            m.positions.push_back({coordinate(g.coordinates[i]), coordinate(g.coordinates[i + 1]), coordinate(g.coordinates[i + 2])});
        for (std::uint8_t i : g.indices) m.indices.push_back(i);
        if ((g.flags & kDropIndex) && !m.indices.empty()) m.indices.pop_back();
        return m;
    }

    ObjectOptions optionsOf(const Geometry& g, const TransformCode& t, std::uint8_t edge) const {
        ObjectOptions o;
        if (!(g.flags & kNoName)) o.name = "fuzz object";
        o.self_collision = (g.flags & kSelfCollision) != 0;
        o.open = (g.flags & kOpen) != 0;
        o.transform = transformOf(t);
        o.typical_edge_length = typicalEdge(edge);
        return o;
    }

    // Engine buffers holding `mesh` in `layout` (kept until the input ends), and their
    // description.
    std::pair<std::size_t, GpuMeshDesc> engineMesh(const HostMesh& mesh, std::uint8_t layout) {
        GpuMeshDesc desc;
        engine_.push_back(makeEngineBuffers(ContextAccess::device(fuzzContext()), mesh, layout, desc));
        return {engine_.size() - 1, desc};
    }

    void step(Op op) {
        switch (op) {
            case Op::AddMesh: return addMesh();
            case Op::AddGpuMesh: return addGpuMesh();
            case Op::SetGpuMeshBuffers: return setGpuMeshBuffers();
            case Op::WriteGpuMesh: return writeGpuMesh();
            case Op::RemoveObject: return removeObject();
            case Op::SetTransform: return setTransform();
            case Op::SetSelfCollision: return setSelfCollision();
            case Op::UpdateVertices: return updateVertices();
            case Op::SetPairFilter: return setPairFilter();
            case Op::Detect: return detect();
            case Op::Submit: return submit();
            case Op::Collect: return collect(false);
            case Op::TryCollect: return collect(true);
            case Op::Ready: return ready();
            case Op::ResolveSettings: return resolveSettings();
            case Op::RecreateWorld:
                // Each world compiles its pipelines (a tenth of a second on lavapipe).
                if (worlds_++ < kMaxNewWorlds) newWorld();
                return;
            case Op::Count: break;
        }
    }

    // An edit the world must refuse while a detection is in flight.
    void requireRefusedWhilePending(const char* call, bool ok) const {
        if (ok && pending()) fail(std::string(call) + " succeeded while a detection was in flight");
    }

    void addMesh() {
        const Geometry g = readGeometry(in_);
        const TransformCode t = readTransform(in_);
        const std::uint8_t edge = in_.byte();
        const HostMesh mesh = meshOf(g);
        const ObjectOptions options = optionsOf(g, t, edge);
        auto id = world_->addMesh(mesh, options);
        if (!id) return requireNamed(id.error(), Op::AddMesh, kEditErrors);
        requireRefusedWhilePending("addMesh", true);
        if (!validateMesh(mesh)) fail("addMesh accepted a mesh validateMesh refuses");
        if (live(*id) || removed_.count(*id)) fail("addMesh gave an id in use or used before");
        objects_[*id] = Object{false, mesh, options.transform, options.self_collision, 0};
    }

    void addGpuMesh() {
        const Geometry g = readGeometry(in_);
        const TransformCode t = readTransform(in_);
        const std::uint8_t edge = in_.byte();
        const std::uint8_t layout = in_.byte();
        const HostMesh mesh = meshOf(g);
        if (mesh.positions.empty()) return;
        auto [engine, desc] = engineMesh(mesh, layout);
        const ObjectOptions options = optionsOf(g, t, edge);
        auto id = world_->addGpuMesh(desc, options);
        if (!id) return requireNamed(id.error(), Op::AddGpuMesh, kEditErrors);
        requireRefusedWhilePending("addGpuMesh", true);
        if (layout & (kDeclareExtraVertex | kNoAddressUsage | kNullIndexBuffer))
            fail("addGpuMesh accepted a description that breaks a rule (layout " + std::to_string(layout) + ")");
        objects_[*id] = Object{true, mesh, options.transform, options.self_collision, engine};
    }

    void setGpuMeshBuffers() {
        const ObjectId id = pick(in_.byte());
        const std::uint8_t layout = in_.byte();
        const Geometry g = readGeometry(in_);
        const HostMesh mesh = meshOf(g);
        if (mesh.positions.empty()) return;
        auto [engine, desc] = engineMesh(mesh, layout);
        auto ok = world_->setGpuMeshBuffers(id, desc);
        if (!ok) return requireNamed(ok.error(), Op::SetGpuMeshBuffers, kEditErrors);
        if (!live(id) || !objects_[id].gpu) fail("setGpuMeshBuffers accepted an object that is not a live engine mesh");
        Object& o = objects_[id];
        if (o.mesh.positions.size() != mesh.positions.size() || o.mesh.indices.size() != mesh.indices.size())
            fail("setGpuMeshBuffers accepted another topology");
        o.mesh = mesh;
        o.engine = engine;
    }

    void writeGpuMesh() {
        const ObjectId id = pick(in_.byte());
        const std::uint8_t slot = in_.byte();
        const std::uint8_t value = in_.byte();
        // The engine's contract: no write while a detection may read the buffers.
        if (!live(id) || !objects_[id].gpu || pending() || world_->state() != WorldState::Ready) return;
        Object& o = objects_[id];
        EngineBuffers& e = *engine_[o.engine];
        if (slot & 128) {
            if (e.index_count == 0) return;
            const std::uint32_t k = (slot & 127u) % e.index_count;
            writeIndex(e, k, value);
            o.mesh.indices[k] = value;
        } else {
            const std::uint32_t v = ((slot & 127u) / 3) % e.vertex_count;
            Float3& p = o.mesh.positions[v];
            (slot % 3 == 0 ? p.x : slot % 3 == 1 ? p.y : p.z) = coordinate(value);
            writeVertex(e, v, p);
        }
    }

    void removeObject() {
        const ObjectId id = pick(in_.byte());
        auto ok = world_->removeObject(id);
        if (!ok) {
            requireNamed(ok.error(), Op::RemoveObject, kEditErrors);
            if (live(id) && !pending() && world_->state() == WorldState::Ready && ok.error().code() != ErrorCode::Timeout)
                fail("removeObject refused a live object of a Ready world: " + ok.error().message());
            return;
        }
        requireRefusedWhilePending("removeObject", true);
        if (!live(id)) fail("removeObject accepted an id that is not live");
        objects_.erase(id);
        removed_.insert(id);
    }

    void setTransform() {
        const ObjectId id = pick(in_.byte());
        const Transform3x4 m = transformOf(readTransform(in_));
        auto ok = world_->setTransform(id, m);
        if (!ok) return requireNamed(ok.error(), Op::SetTransform, kEditErrors);
        if (!live(id)) fail("setTransform accepted an id that is not live");
        if (!std::all_of(m.begin(), m.end(), [](float x) { return std::isfinite(x); }))
            fail("setTransform accepted a transform that is not finite");
        objects_[id].transform = m;
    }

    void setSelfCollision() {
        const ObjectId id = pick(in_.byte());
        const bool on = (in_.byte() & 1) != 0;
        auto ok = world_->setSelfCollision(id, on);
        if (!ok) return requireNamed(ok.error(), Op::SetSelfCollision, kEditErrors);
        requireRefusedWhilePending("setSelfCollision", true);
        if (!live(id)) fail("setSelfCollision accepted an id that is not live");
        objects_[id].self_collision = on;
    }

    void updateVertices() {
        const ObjectId id = pick(in_.byte());
        const std::uint8_t count_code = in_.byte();
        std::size_t count = live(id) ? objects_[id].mesh.positions.size() : 3;
        switch (count_code % 8) {
            case 5: count = count > 0 ? count - 1 : 0; break;
            case 6: ++count; break;
            case 7: count = 0; break;
            default: break;
        }
        count = std::min<std::size_t>(count, kMaxVertices + 1);
        std::vector<Float3> positions(count);
        for (Float3& p : positions) p = {coordinate(in_.byte()), coordinate(in_.byte()), coordinate(in_.byte())};
        auto ok = world_->updateVertices(id, positions);
        if (!ok) return requireNamed(ok.error(), Op::UpdateVertices, kEditErrors);
        // Allowed in flight: the detections in flight keep their snapshots' vertices, which
        // checkResult compares them with.
        if (!live(id) || objects_[id].gpu) fail("updateVertices accepted an id that is not a live host mesh");
        if (positions.size() != objects_[id].mesh.positions.size()) fail("updateVertices accepted another vertex count");
        for (const Float3& p : positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                fail("updateVertices accepted a position that is not finite");
        objects_[id].mesh.positions = positions;
    }

    void setPairFilter() {
        const auto kind = static_cast<PairFilterKind>(in_.byte() % static_cast<std::uint8_t>(PairFilterKind::Count));
        std::function<bool(ObjectId, ObjectId)> filter;
        if (kind != PairFilterKind::None) {
            filter = [kind](ObjectId a, ObjectId b) {
                if (a >= b) fail("the pair filter was called with a >= b");
                if (kind == PairFilterKind::Throws) throw std::runtime_error("fuzz filter refuses to answer");
                return allowed(kind, a, b);
            };
        }
        auto ok = world_->setPairFilter(std::move(filter));
        if (!ok) return requireNamed(ok.error(), Op::SetPairFilter, kEditErrors);
        requireRefusedWhilePending("setPairFilter", true);
        filter_ = kind;
        filter_threw_ = kind == PairFilterKind::Throws;
    }

    Snapshot snapshot(const DetectSettings& s) const { return Snapshot{objects_, filter_, filter_threw_, s}; }

    void detect() {
        const DetectSettings s = decodeSettings(readSettings(in_));
        trace("  settings: " + describe(s));
        if (detections_++ >= kMaxDetections) return;
        const Snapshot snap = snapshot(s);
        auto r = world_->detect(s);
        if (!r) {
            requireNamed(r.error(), Op::Detect, kDetectErrors);
            if (pending() && r.error().code() != ErrorCode::InvalidArgument)
                fail("detect() with detections in flight failed with " + std::string(toString(r.error().code())));
            return;
        }
        if (pending()) fail("detect() succeeded while detections were in flight");
        checkResult(*r, snap, "detect");
    }

    void submit() {
        const DetectSettings s = decodeSettings(readSettings(in_));
        trace("  settings: " + describe(s));
        if (detections_++ >= kMaxDetections) return;
        auto ok = world_->submit(s);
        if (!ok) return requireNamed(ok.error(), Op::Submit, kDetectErrors);
        if (in_flight_.size() >= CollisionWorld::kMaxInFlight) fail("submit() accepted more than kMaxInFlight");
        in_flight_.push_back(snapshot(s));
        if (world_->inFlight() != in_flight_.size()) fail("inFlight() disagrees with the submissions");
    }

    void collect(bool try_only) {
        const Op op = try_only ? Op::TryCollect : Op::Collect;
        std::optional<DetectResult> result;
        if (try_only) {
            auto r = world_->tryCollect();
            if (!r) return collectFailed(r.error(), op);
            if (!*r) {
                if (!pending()) fail("tryCollect() said 'still running' with nothing in flight");
                return;
            }
            result = std::move(**r);
        } else {
            auto r = world_->collect();
            if (!r) return collectFailed(r.error(), op);
            result = std::move(*r);
        }
        if (!pending()) fail(callName(op) + " returned a result with nothing in flight");
        const Snapshot snap = std::move(in_flight_.front());
        in_flight_.pop_front();
        checkResult(*result, snap, callName(op).c_str());
    }

    void collectFailed(const Error& e, Op op) {
        requireNamed(e, op, kDetectErrors);
        if (!pending()) {
            if (e.code() != ErrorCode::InvalidArgument) fail(callName(op) + " with nothing in flight: not InvalidArgument");
            return;
        }
        // A failed collect ends that detection (the oldest).
        in_flight_.pop_front();
    }

    void ready() {
        auto r = world_->ready();
        if (!r) {
            requireNamed(r.error(), Op::Ready, kDetectErrors);
            if (pending()) fail("ready() failed with a detection in flight: " + r.error().message());
            return;
        }
        if (!pending()) fail("ready() answered with nothing in flight");
    }

    void resolveSettings() {
        const DetectSettings s = decodeSettings(readSettings(in_));
        trace("  settings: " + describe(s));
        auto r = world_->resolveSettings(s);
        if (!r) return requireNamed(r.error(), Op::ResolveSettings, kDetectErrors);
        if (!r->resolution || !r->direction) fail("resolveSettings left an automatic field empty");
    }
};

}  // namespace
}  // namespace vkcollide::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    vkcollide::fuzz::nextInput();
    vkcollide::fuzz::ProgramReader in(data, size);
    vkcollide::fuzz::Session session(in);
    session.run();
    return 0;
}
