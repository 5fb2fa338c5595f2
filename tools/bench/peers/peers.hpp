// vkcollide bench: the libraries users pick instead of vkcollide ("peers"), behind one
// interface, so that the benchmark times them on the same scenes and frames.
//
// Each peer takes the scene as world-space meshes (object id = index in the span) and
// returns every intersecting triangle pair in vkcollide's convention: TrianglePair
// ordered (object_a, triangle_a) < (object_b, triangle_b), the list sorted and free of
// duplicates. Triangles of one object that are neighbours (a shared vertex index or a
// bit-identical vertex position, narrow/neighbours.hpp) are never a pair.
//
//   FCL (libfcl 0.7)         BVHModel<AABB> or BVHModel<OBBRSS> per object, a
//                            DynamicAABBTree broad phase over the objects, collide() with
//                            a request for all contacts. FCL's own triangle test decides
//                            (double precision, not exact). FCL finds no pairs within one
//                            object (fcl#333), so it only runs with self_collision off.
//   Embree 3 (rtcCollide)    one user geometry per object, a bounds callback per
//                            triangle; rtcCollide(scene, scene) hands out candidate pairs,
//                            our exact test (narrow/triangle_intersection.hpp) decides.
//   CGAL (box_intersection_d) box_self_intersection_d over all triangle boxes, closed
//                            boxes, Parallel_tag (TBB) or Sequential_tag; our exact
//                            test (or, as a cross-check, CGAL's do_intersect with the
//                            Epick kernel) decides. The exact CPU baseline.
//
// Frames. A peer is a session: frame() is called once per simulation frame.
//   Motion::Rigid      every frame builds from scratch and queries, what a one-shot query
//                      of a changed scene costs (Embree and CGAL must rebuild when objects
//                      move; FCL could keep its BVHs and move objects by transform, so for
//                      FCL build_ms is the part a rigid-body engine would not pay).
//   Motion::Deforming  the first frame builds; every later frame gets the same meshes
//                      with moved vertices (same vertex and index counts, same indices)
//                      and does what the library must do per frame, counted in build_ms:
//                      FCL: beginUpdateModel/updateSubModel/endUpdateModel(refit, bottom-up)
//                           plus the object AABBs and the broad-phase manager update;
//                      Embree: rebuild with RTC_BUILD_QUALITY_LOW, or (EmbreeRefit) a
//                           dynamic scene whose geometries are refitted (RTC_BUILD_QUALITY_REFIT);
//                      CGAL: recompute the boxes (it keeps no structure between calls).
//
// Timings are wall-clock milliseconds on the calling thread (steady_clock); query_ms is
// the broad phase plus the exact tests, total_ms = build_ms + query_ms.
//
// Thread safety: a session is used by one thread at a time; sessions are independent.
// Each session owns its worker threads (`threads`; 0 = all hardware threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/result.hpp"
#include "../bench_scenes.hpp"  // Motion

namespace vkcollide::bench {


struct PeerMode {
    // Pairs of triangles within one object (non-neighbours) are reported too. Applies to
    // every object; FCL refuses true.
    bool self_collision = true;
    Motion motion = Motion::Rigid;
};

struct PeerTimings {
    double build_ms = 0;  // build (first frame, every rigid frame) or per-frame refit/rebuild
    double query_ms = 0;  // broad phase + narrow phase
    double total_ms = 0;  // build_ms + query_ms
    // Candidate triangle pairs the library's broad phase handed to the exact test (Embree,
    // CGAL: after removing (t, t) and duplicates, before the neighbour filter). FCL tests
    // inside its traversal and does not say: 0.
    std::size_t candidates = 0;
    // Bytes the library's structures hold after the frame: FCL BVHModel::memUsage, Embree's
    // device memory monitor, CGAL's box arrays (with the copies Parallel_tag makes) and the
    // candidate list. An estimate, not a peak; 0 when unknown.
    std::size_t memory_bytes = 0;
};

struct PeerFrame {
    std::vector<TrianglePair> pairs;  // sorted, unique, each ordered a < b
    PeerTimings timings;
};

class Peer {
public:
    virtual ~Peer() = default;
    // Runs one frame on `in_meshes` (world space; read during the call only).
    // Errors: InvalidMesh (validateMesh's rules), InvalidArgument when a deforming frame
    // changes a mesh's vertex count, triangle count or indices, or the object count.
    virtual Result<PeerFrame> frame(std::span<const HostMesh> in_meshes) = 0;
    // Short name for tables and CSV: "fcl-aabb", "embree", "cgal", "cgal-seqbox", ...
    virtual std::string_view name() const noexcept = 0;
};

enum class FclVolume { Aabb, Obbrss };
enum class EmbreeUpdate {
    Rebuild,  // rigid: RTC_BUILD_QUALITY_MEDIUM; deforming: rebuild each frame with RTC_BUILD_QUALITY_LOW
    Refit,    // deforming: RTC_SCENE_FLAG_DYNAMIC, geometries RTC_BUILD_QUALITY_REFIT (rigid: as Rebuild)
};
enum class CgalTest {
    Exact,  // narrow::trianglesIntersect (ours, exact, touching counts)
    Epick,  // CGAL::do_intersect on Exact_predicates_inexact_constructions_kernel triangles;
            // a degenerate (collinear) triangle falls back to ours (CGAL's precondition)
};
struct CgalOptions {
    CgalTest test = CgalTest::Exact;
    // box_self_intersection_d<Parallel_tag> (CGAL 5.5: a fixed 4 x 4 split over TBB) or
    // <Sequential_tag>. The exact tests run on all threads either way.
    bool parallel_boxes = true;
};

// One entry point per peer. Error: InvalidArgument for a mode the peer cannot run
// (FCL with self_collision on).
Result<std::unique_ptr<Peer>> createFclPeer(FclVolume volume, const PeerMode& mode, unsigned threads = 0);
Result<std::unique_ptr<Peer>> createEmbreePeer(EmbreeUpdate update, const PeerMode& mode, unsigned threads = 0);
Result<std::unique_ptr<Peer>> createCgalPeer(const CgalOptions& options, const PeerMode& mode, unsigned threads = 0);

}  // namespace vkcollide::bench
