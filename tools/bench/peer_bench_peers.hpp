// The peers vkcollide_peer_bench can run (--peers, --list): FCL, Embree and CGAL in their
// variants (peers/peers.hpp), and vkcollide itself where the GPU library was built
// (VKCOLLIDE_PEER_BENCH_GPU).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "peers.hpp"

namespace vkcollide::bench::peer_bench {

struct PeerSpec {
    std::string name;
    bool self_collision_capable;
    bool deforming_only;  // a variant that only differs from another one when deforming
    std::function<Result<std::unique_ptr<Peer>>(const PeerMode&, unsigned threads)> create;
};

// Every peer, in --list order; vkcollide_resolution: the vkcollide peer's (0: automatic).
std::vector<PeerSpec> allPeers(std::uint32_t vkcollide_resolution);

}  // namespace vkcollide::bench::peer_bench
