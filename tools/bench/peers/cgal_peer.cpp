// CGAL's box_intersection_d over triangle boxes as the broad phase, an exact triangle
// test as the narrow phase: the exact CPU baseline.
//
// Boxes are closed (CGAL's default topology), so triangles that only touch are
// candidates. Coordinates stay float: the boxes of float triangles are exact in float.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/cache_aligned_allocator.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <utility>

#include "vkcollide/thread_pool.hpp"
#include "narrow/triangle_intersection.hpp"
#include "peer_common.hpp"
#include "peers.hpp"

namespace vkcollide::bench {
namespace {

using detail::Stopwatch;

// Which triangle a box bounds. Boxes hold a pointer into an array of these: the box id
// (the handle's address) is unique, and the callback needs no search to name the pair.
struct TriangleRef {
    std::uint32_t object, triangle;
};
using Box = CGAL::Box_intersection_d::Box_with_handle_d<float, 3, const TriangleRef*>;
// Per-thread candidate lists; a native TLS key per instance keeps local() cheap in a
// callback that runs once per overlapping box pair.
using PerThreadPairs =
    tbb::enumerable_thread_specific<std::vector<TrianglePair>, tbb::cache_aligned_allocator<std::vector<TrianglePair>>,
                                    tbb::ets_key_per_instance>;

#if !defined(CGAL_LINKED_WITH_TBB)
#error "the CGAL peer needs CGAL::TBB_support (CGAL_LINKED_WITH_TBB) for Parallel_tag"
#endif

// CGAL 5.5's parallel box intersection splits both ranges 4 ways and copies each range
// 4 times (box_intersection_d.h), so it holds 8 copies of the boxes while it runs; the
// sequential one copies the range once.
constexpr std::size_t kParallelBoxCopies = 1 + 8;
constexpr std::size_t kSequentialBoxCopies = 1 + 1;

bool epickTest(const Float3 (&a)[3], const Float3 (&b)[3]) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    const auto point = [](const Float3& p) { return K::Point_3(p.x, p.y, p.z); };
    const K::Triangle_3 ta(point(a[0]), point(a[1]), point(a[2]));
    const K::Triangle_3 tb(point(b[0]), point(b[1]), point(b[2]));
    // do_intersect requires non-degenerate triangles.
    if (ta.is_degenerate() || tb.is_degenerate()) return detail::exactTest(a, b);
    return CGAL::do_intersect(ta, tb);
}

class CgalPeer final : public Peer {
public:
    CgalPeer(const CgalOptions& options, const PeerMode& mode, unsigned threads)
        : options_(options),
          mode_(mode),
          pool_(threads),
          arena_(threads ? static_cast<int>(threads) : tbb::task_arena::automatic) {}

    std::string_view name() const noexcept override {
        if (options_.test == CgalTest::Epick) return options_.parallel_boxes ? "cgal-epick" : "cgal-epick-seqbox";
        return options_.parallel_boxes ? "cgal" : "cgal-seqbox";
    }

    Result<PeerFrame> frame(std::span<const HostMesh> meshes) override {
        if (Result<void> ok = detail::validateScene(meshes); !ok) return ok.error();
        if (mode_.motion == Motion::Deforming) {
            if (first_frame_done_) {
                if (Result<void> ok = topology_.check(meshes); !ok) return ok.error();
            } else {
                topology_.remember(meshes);
            }
        }
        first_frame_done_ = true;

        PeerFrame out;
        // Build: one box per triangle. CGAL keeps no structure between calls, so this is
        // all a deforming frame redoes.
        const Stopwatch build_clock;
        std::vector<std::size_t> first_triangle(meshes.size() + 1, 0);
        for (std::size_t o = 0; o < meshes.size(); ++o)
            first_triangle[o + 1] = first_triangle[o] + meshes[o].triangleCount();
        const std::size_t triangle_count = first_triangle.back();
        if (refs_.size() != triangle_count) {
            refs_.resize(triangle_count);
            for (std::size_t o = 0; o < meshes.size(); ++o) {
                for (std::uint32_t t = 0; t < meshes[o].triangleCount(); ++t) {
                    refs_[first_triangle[o] + t] = {static_cast<std::uint32_t>(o), t};
                }
            }
        }
        boxes_.resize(triangle_count);
        pool_.parallelFor(meshes.size(), 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t o = begin; o < end; ++o) {
                const HostMesh& m = meshes[o];
                for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
                    Float3 v[3];
                    detail::triangleVertices(m, t, v);
                    float lo[3] = {std::min({v[0].x, v[1].x, v[2].x}), std::min({v[0].y, v[1].y, v[2].y}),
                                   std::min({v[0].z, v[1].z, v[2].z})};
                    float hi[3] = {std::max({v[0].x, v[1].x, v[2].x}), std::max({v[0].y, v[1].y, v[2].y}),
                                   std::max({v[0].z, v[1].z, v[2].z})};
                    const std::size_t g = first_triangle[o] + t;
                    boxes_[g] = Box(lo, hi, &refs_[g]);
                }
            }
        });
        out.timings.build_ms = build_clock.ms();

        const Stopwatch query_clock;
        std::vector<TrianglePair> candidates = findCandidates();
        const detail::TriangleTest& test = options_.test == CgalTest::Epick ? detail::TriangleTest(epickTest)
                                                                            : detail::TriangleTest(detail::exactTest);
        out.pairs = detail::exactPairs(meshes, candidates, mode_.self_collision, test, pool_);
        out.timings.query_ms = query_clock.ms();
        out.timings.total_ms = out.timings.build_ms + out.timings.query_ms;
        out.timings.candidates = candidates.size();
        const std::size_t copies = options_.parallel_boxes ? kParallelBoxCopies : kSequentialBoxCopies;
        out.timings.memory_bytes = copies * boxes_.size() * sizeof(Box) + refs_.size() * sizeof(TriangleRef) +
                                   candidates.capacity() * sizeof(TrianglePair);
        return out;
    }

private:
    std::vector<TrianglePair> findCandidates() {
        const bool self = mode_.self_collision;
        // Each unordered pair comes once; order it. Without self-collision, pairs within
        // one object would only be thrown away later.
        const auto candidate = [self](const Box& box_a, const Box& box_b, TrianglePair& out) {
            const TriangleRef a = *box_a.handle(), b = *box_b.handle();
            if (a.object == b.object && !self) return false;
            out = std::pair(a.object, a.triangle) < std::pair(b.object, b.triangle)
                      ? TrianglePair{a.object, a.triangle, b.object, b.triangle}
                      : TrianglePair{b.object, b.triangle, a.object, a.triangle};
            return true;
        };
        std::vector<TrianglePair> out;
        if (!options_.parallel_boxes) {
            CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes_.begin(), boxes_.end(),
                                                                [&](const Box& a, const Box& b) {
                                                                    TrianglePair p;
                                                                    if (candidate(a, b, p)) out.push_back(p);
                                                                });
            return out;
        }
        PerThreadPairs found;
        // The arena caps CGAL's TBB tasks at the session's thread count.
        arena_.execute([&] {
            CGAL::box_self_intersection_d<CGAL::Parallel_tag>(boxes_.begin(), boxes_.end(),
                                                              [&](const Box& a, const Box& b) {
                                                                  TrianglePair p;
                                                                  if (candidate(a, b, p)) found.local().push_back(p);
                                                              });
        });
        std::size_t total = 0;
        for (const auto& part : found) total += part.size();
        out.reserve(total);
        for (const auto& part : found) out.insert(out.end(), part.begin(), part.end());
        return out;
    }

    CgalOptions options_;
    PeerMode mode_;
    ThreadPool pool_;
    bool first_frame_done_ = false;
    detail::TopologyCheck topology_;
    std::vector<TriangleRef> refs_;  // one per triangle of the scene: what box handles point to
    std::vector<Box> boxes_;
    tbb::task_arena arena_;
};

}  // namespace

Result<std::unique_ptr<Peer>> createCgalPeer(const CgalOptions& options, const PeerMode& mode, unsigned threads) {
    return std::unique_ptr<Peer>(std::make_unique<CgalPeer>(options, mode, threads));
}

}  // namespace vkcollide::bench
