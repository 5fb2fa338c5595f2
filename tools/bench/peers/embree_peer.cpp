// Embree 3 rtcCollide as a broad phase, our exact triangle test as the narrow phase.
//
// rtcCollide only takes user geometries (rtcCollide.md), so each object is a user
// geometry whose primitives are its triangles, bounded by a callback. Colliding the scene
// with itself reports leaf pairs whose boxes overlap (closed boxes: touching counts),
// including (t, t) and both orders of a pair; we keep one order.
#include <embree3/rtcore.h>
#include <tbb/cache_aligned_allocator.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <utility>

#include "vkcollide/thread_pool.hpp"
#include "peer_common.hpp"
#include "peers.hpp"

namespace vkcollide::bench {
namespace {

using detail::Stopwatch;

struct ObjectData {
    const HostMesh* mesh = nullptr;  // the current frame's mesh; updated before each commit
};

void boundsOfTriangle(const RTCBoundsFunctionArguments* args) {
    const HostMesh& m = *static_cast<const ObjectData*>(args->geometryUserPtr)->mesh;
    Float3 v[3];
    detail::triangleVertices(m, args->primID, v);
    RTCBounds* b = args->bounds_o;
    b->lower_x = std::min({v[0].x, v[1].x, v[2].x});
    b->lower_y = std::min({v[0].y, v[1].y, v[2].y});
    b->lower_z = std::min({v[0].z, v[1].z, v[2].z});
    b->upper_x = std::max({v[0].x, v[1].x, v[2].x});
    b->upper_y = std::max({v[0].y, v[1].y, v[2].y});
    b->upper_z = std::max({v[0].z, v[1].z, v[2].z});
}

struct CollideContext {
    bool self_collision = true;
    // A native TLS key per instance keeps local() cheap; the callback runs per leaf pair.
    tbb::enumerable_thread_specific<std::vector<TrianglePair>, tbb::cache_aligned_allocator<std::vector<TrianglePair>>,
                                    tbb::ets_key_per_instance>
        found;
};

// Called concurrently from Embree's (TBB) workers.
void collectCandidates(void* user, RTCCollision* collisions, unsigned int count) {
    auto* context = static_cast<CollideContext*>(user);
    std::vector<TrianglePair>& out = context->found.local();
    for (unsigned int i = 0; i < count; ++i) {
        const RTCCollision& c = collisions[i];
        const std::pair a(c.geomID0, c.primID0), b(c.geomID1, c.primID1);
        // Both orders of a pair come back from a scene collided with itself (and never
        // (t, t)); keep a < b. Pairs within one object are dropped here when they cannot count.
        if (!(a < b)) continue;
        if (a.first == b.first && !context->self_collision) continue;
        out.push_back({a.first, a.second, b.first, b.second});
    }
}

class EmbreePeer final : public Peer {
public:
    EmbreePeer(EmbreeUpdate update, const PeerMode& mode, unsigned threads)
        : update_(update), mode_(mode), pool_(threads) {}

    ~EmbreePeer() override {
        releaseScene();
        if (device_) rtcReleaseDevice(device_);
    }

    Result<void> init(unsigned threads) {
        const std::string config = threads ? "threads=" + std::to_string(threads) : std::string();
        device_ = rtcNewDevice(config.c_str());
        if (!device_) return Error(ErrorCode::InvalidArgument, "embree: rtcNewDevice failed");
        rtcSetDeviceErrorFunction(
            device_,
            [](void* self, RTCError code, const char* what) {
                auto* peer = static_cast<EmbreePeer*>(self);
                if (peer->error_.empty())
                    peer->error_ = "embree error " + std::to_string(code) + ": " + (what ? what : "");
            },
            this);
        rtcSetDeviceMemoryMonitorFunction(
            device_,
            [](void* bytes, ssize_t delta, bool) {
                static_cast<std::atomic<std::int64_t>*>(bytes)->fetch_add(delta, std::memory_order_relaxed);
                return true;
            },
            &memory_bytes_);
        return {};
    }

    std::string_view name() const noexcept override {
        return update_ == EmbreeUpdate::Refit ? "embree-refit" : "embree";
    }

    Result<PeerFrame> frame(std::span<const HostMesh> meshes) override {
        if (Result<void> ok = detail::validateScene(meshes); !ok) return ok.error();
        const bool update = mode_.motion == Motion::Deforming && scene_;
        if (update) {
            if (Result<void> ok = topology_.check(meshes); !ok) return ok.error();
        } else if (mode_.motion == Motion::Deforming) {
            topology_.remember(meshes);
        }

        PeerFrame out;
        const Stopwatch build_clock;
        if (update) {
            // Same geometries, moved vertices: mark each modified and commit again, which
            // rebuilds (LOW) or refits (REFIT) what changed.
            for (std::size_t o = 0; o < meshes.size(); ++o) {
                objects_[o].mesh = &meshes[o];
                rtcCommitGeometry(geometries_[o]);
            }
            rtcCommitScene(scene_);
        } else {
            buildScene(meshes);
        }
        out.timings.build_ms = build_clock.ms();
        if (!error_.empty()) return Error(ErrorCode::InvalidArgument, error_);

        const Stopwatch query_clock;
        CollideContext context;
        context.self_collision = mode_.self_collision;
        rtcCollide(scene_, scene_, collectCandidates, &context);
        std::vector<TrianglePair> candidates;
        {
            std::size_t total = 0;
            for (const auto& part : context.found) total += part.size();
            candidates.reserve(total);
            for (const auto& part : context.found) candidates.insert(candidates.end(), part.begin(), part.end());
        }
        out.pairs = detail::exactPairs(meshes, candidates, mode_.self_collision, detail::exactTest, pool_);
        out.timings.query_ms = query_clock.ms();
        if (!error_.empty()) return Error(ErrorCode::InvalidArgument, error_);

        out.timings.total_ms = out.timings.build_ms + out.timings.query_ms;
        out.timings.candidates = candidates.size();
        out.timings.memory_bytes = static_cast<std::size_t>(std::max<std::int64_t>(0, memory_bytes_.load())) +
                                   candidates.capacity() * sizeof(TrianglePair);
        return out;
    }

private:
    void buildScene(std::span<const HostMesh> meshes) {
        releaseScene();
        const bool dynamic = mode_.motion == Motion::Deforming;
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, dynamic ? RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_NONE);
        rtcSetSceneBuildQuality(scene_, dynamic ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
        RTCBuildQuality geometry_quality = RTC_BUILD_QUALITY_MEDIUM;
        if (dynamic)
            geometry_quality = update_ == EmbreeUpdate::Refit ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_LOW;
        objects_.assign(meshes.size(), ObjectData{});
        for (std::size_t o = 0; o < meshes.size(); ++o) {
            objects_[o].mesh = &meshes[o];
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(meshes[o].triangleCount()));
            rtcSetGeometryUserData(g, &objects_[o]);
            rtcSetGeometryBoundsFunction(g, boundsOfTriangle, nullptr);
            rtcSetGeometryBuildQuality(g, geometry_quality);
            rtcCommitGeometry(g);
            rtcAttachGeometryByID(scene_, g, static_cast<unsigned>(o));
            geometries_.push_back(g);  // the scene holds a reference too; ours is for updates
        }
        rtcCommitScene(scene_);
    }

    void releaseScene() {
        for (RTCGeometry g : geometries_) rtcReleaseGeometry(g);
        geometries_.clear();
        if (scene_) rtcReleaseScene(scene_);
        scene_ = nullptr;
    }

    EmbreeUpdate update_;
    PeerMode mode_;
    ThreadPool pool_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<RTCGeometry> geometries_;
    std::vector<ObjectData> objects_;
    detail::TopologyCheck topology_;
    std::atomic<std::int64_t> memory_bytes_{0};
    std::string error_;  // first error Embree reported
};

}  // namespace

Result<std::unique_ptr<Peer>> createEmbreePeer(EmbreeUpdate update, const PeerMode& mode, unsigned threads) {
    auto peer = std::make_unique<EmbreePeer>(update, mode, threads);
    if (Result<void> ok = peer->init(threads); !ok) return ok.error();
    return std::unique_ptr<Peer>(std::move(peer));
}

}  // namespace vkcollide::bench
