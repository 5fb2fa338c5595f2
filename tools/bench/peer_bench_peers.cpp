#include "peer_bench_peers.hpp"

#ifdef VKCOLLIDE_PEER_BENCH_GPU
#include <chrono>

#include "vkcollide/context.hpp"
#include "vkcollide/world.hpp"
#endif

namespace vkcollide::bench::peer_bench {
namespace {

// vkcollide as a peer: the same world-space meshes, a CollisionWorld on the device found
// (lavapipe without a GPU). Frame 0 builds (world, pipelines, uploads); every later frame
// uploads the frame's vertices (build_ms: what a changed scene costs it) and detects
// (query_ms: broad phase on the GPU, readback, exact narrow phase). Settings automatic,
// but for --resolution. The device is made once, outside the timings.

#ifdef VKCOLLIDE_PEER_BENCH_GPU
class VkcollidePeer final : public Peer {
public:
    VkcollidePeer(std::unique_ptr<Context> context, const PeerMode& mode, unsigned threads, std::uint32_t resolution)
        : context_(std::move(context)), mode_(mode), threads_(threads) {
        if (resolution) settings_.resolution = resolution;
    }
    std::string_view name() const noexcept override { return "vkcollide"; }

    Result<PeerFrame> frame(std::span<const HostMesh> meshes) override {
        using Clock = std::chrono::steady_clock;
        const auto ms = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
        PeerFrame out;
        const auto build = Clock::now();
        if (!world_) {
            auto w = CollisionWorld::create(*context_, {.threads = threads_});
            if (!w) return w.error();
            world_ = std::move(*w);
            for (const HostMesh& m : meshes) {
                auto id = world_->addMesh(m, {.name = m.name, .self_collision = mode_.self_collision});
                if (!id) return id.error();
                ids_.push_back(*id);
            }
        } else {
            if (meshes.size() != ids_.size()) return Error(ErrorCode::InvalidArgument, "vkcollide peer: the frame has another object count");
            for (std::size_t i = 0; i < meshes.size(); ++i)
                if (auto ok = world_->updateVertices(ids_[i], meshes[i].positions); !ok) return ok.error();
        }
        out.timings.build_ms = ms(build);
        const auto query = Clock::now();
        auto r = world_->detect(settings_);
        if (!r) return r.error();
        out.timings.query_ms = ms(query);
        out.timings.total_ms = out.timings.build_ms + out.timings.query_ms;
        out.timings.candidates = r->stats.narrow.sap_pairs;
        out.timings.memory_bytes = r->stats.gpu_memory_bytes;
        out.pairs = std::move(r->pairs);  // object ids are 0, 1, ... in the order added
        return out;
    }

private:
    std::unique_ptr<Context> context_;
    PeerMode mode_;
    unsigned threads_;
    DetectSettings settings_;
    std::unique_ptr<CollisionWorld> world_;
    std::vector<ObjectId> ids_;
};

Result<std::unique_ptr<Peer>> createVkcollidePeer(const PeerMode& mode, unsigned threads, std::uint32_t resolution) {
    auto context = Context::create();
    if (!context) return context.error();
    return std::unique_ptr<Peer>(new VkcollidePeer(std::move(*context), mode, threads, resolution));
}
#endif

}  // namespace

std::vector<PeerSpec> allPeers(std::uint32_t vkcollide_resolution) {
    std::vector<PeerSpec> peers = {
        {"fcl-aabb", false, false, [](const PeerMode& m, unsigned t) { return createFclPeer(FclVolume::Aabb, m, t); }},
        {"fcl-obbrss", false, false,
         [](const PeerMode& m, unsigned t) { return createFclPeer(FclVolume::Obbrss, m, t); }},
        {"embree", true, false,
         [](const PeerMode& m, unsigned t) { return createEmbreePeer(EmbreeUpdate::Rebuild, m, t); }},
        {"embree-refit", true, true,
         [](const PeerMode& m, unsigned t) { return createEmbreePeer(EmbreeUpdate::Refit, m, t); }},
        {"cgal", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Exact, true}, m, t);
         }},
        {"cgal-seqbox", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Exact, false}, m, t);
         }},
        {"cgal-epick", true, false,
         [](const PeerMode& m, unsigned t) {
             return createCgalPeer({CgalTest::Epick, true}, m, t);
         }},
    };
#ifdef VKCOLLIDE_PEER_BENCH_GPU
    peers.push_back({"vkcollide", true, false, [vkcollide_resolution](const PeerMode& m, unsigned t) {
                         return createVkcollidePeer(m, t, vkcollide_resolution);
                     }});
#else
    (void)vkcollide_resolution;
#endif
    return peers;
}

}  // namespace vkcollide::bench::peer_bench
