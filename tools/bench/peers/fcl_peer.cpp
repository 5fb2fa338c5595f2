// FCL 0.7: one BVHModel per object (AABB or OBBRSS), a dynamic AABB tree over the
// objects, and fcl::collide with a request for every contact on each pair of objects
// whose boxes overlap. FCL's own triangle test (Intersect::intersect_Triangle, double)
// decides; the benchmark measures its pairs against the exact reference.
//
// FCL has no self-collision for a BVHModel (fcl#333): only pairs between objects.
// FCL itself is single-threaded; we build, refit and query the object pairs on a pool of
// threads, which is what a user with many cores would do. With two objects there is one
// pair, so the query runs on one thread.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "vkcollide/thread_pool.hpp"
#include "peer_common.hpp"
#include "peers.hpp"

namespace vkcollide::bench {
namespace {

using detail::Stopwatch;

std::vector<fcl::Vector3d> toFcl(const HostMesh& m) {
    std::vector<fcl::Vector3d> points(m.positions.size());
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = {m.positions[i].x, m.positions[i].y, m.positions[i].z};
    return points;
}

template <typename BV>
class FclPeer final : public Peer {
public:
    using Model = fcl::BVHModel<BV>;

    FclPeer(std::string_view name, const PeerMode& mode, unsigned threads) : name_(name), mode_(mode), pool_(threads) {}

    std::string_view name() const noexcept override { return name_; }

    Result<PeerFrame> frame(std::span<const HostMesh> meshes) override {
        if (Result<void> ok = detail::validateScene(meshes); !ok) return ok.error();
        const bool update = mode_.motion == Motion::Deforming && !models_.empty();
        if (update) {
            if (Result<void> ok = topology_.check(meshes); !ok) return ok.error();
        } else if (mode_.motion == Motion::Deforming) {
            topology_.remember(meshes);
        }

        PeerFrame out;
        const Stopwatch build_clock;
        Result<void> built = update ? refit(meshes) : build(meshes);
        if (!built) return built.error();
        out.timings.build_ms = build_clock.ms();

        const Stopwatch query_clock;
        out.pairs = query();
        out.timings.query_ms = query_clock.ms();
        out.timings.total_ms = out.timings.build_ms + out.timings.query_ms;
        for (const auto& m : models_) out.timings.memory_bytes += memoryOf(*m);
        return out;
    }

private:
    // BVHModel::memUsage returns BVH_OK, not the size it prints (fcl 0.7.0), so count as it
    // does: nodes, triangles, vertices (twice once a model has been updated: FCL keeps the
    // previous vertices).
    std::size_t memoryOf(const Model& m) const {
        const std::size_t vertex_copies = mode_.motion == Motion::Deforming ? 2 : 1;
        return sizeof(Model) + static_cast<std::size_t>(m.getNumBVs()) * sizeof(fcl::BVNode<BV>) +
               static_cast<std::size_t>(m.num_tris) * sizeof(fcl::Triangle) +
               vertex_copies * static_cast<std::size_t>(m.num_vertices) * sizeof(fcl::Vector3d);
    }

    Result<void> build(std::span<const HostMesh> meshes) {
        manager_.reset();  // it points at the objects replaced below
        models_.assign(meshes.size(), nullptr);
        objects_.clear();
        objects_.resize(meshes.size());
        std::vector<int> status(meshes.size(), fcl::BVH_OK);
        // Each object's BVH is independent of the others: build them in parallel.
        pool_.parallelFor(meshes.size(), 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t o = begin; o < end; ++o) {
                const HostMesh& m = meshes[o];
                std::vector<fcl::Triangle> triangles(m.triangleCount());
                for (std::size_t t = 0; t < triangles.size(); ++t) {
                    triangles[t] = fcl::Triangle(m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
                }
                auto model = std::make_shared<Model>();
                int s = model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(m.positions.size()));
                if (s == fcl::BVH_OK) s = model->addSubModel(toFcl(m), triangles);
                if (s == fcl::BVH_OK) s = model->endModel();
                model->computeLocalAABB();
                status[o] = s;
                models_[o] = model;
                objects_[o] = std::make_unique<fcl::CollisionObjectd>(model);  // identity transform: world space
                objects_[o]->setUserData(reinterpret_cast<void*>(o));
            }
        });
        if (Result<void> ok = checkStatus(status, "building"); !ok) return ok;
        manager_ = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
        std::vector<fcl::CollisionObjectd*> raw;
        for (auto& object : objects_) raw.push_back(object.get());
        manager_->registerObjects(raw);
        manager_->setup();
        return {};
    }

    // What FCL asks of a deforming mesh: new vertices, a bottom-up refit, then the object
    // boxes and the broad phase by hand (fcl#577).
    Result<void> refit(std::span<const HostMesh> meshes) {
        std::vector<int> status(meshes.size(), fcl::BVH_OK);
        pool_.parallelFor(meshes.size(), 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t o = begin; o < end; ++o) {
                Model& model = *models_[o];
                int s = model.beginUpdateModel();
                if (s == fcl::BVH_OK) s = model.updateSubModel(toFcl(meshes[o]));
                if (s == fcl::BVH_OK) s = model.endUpdateModel(true, true);
                model.computeLocalAABB();
                objects_[o]->computeAABB();
                status[o] = s;
            }
        });
        if (Result<void> ok = checkStatus(status, "refitting"); !ok) return ok;
        manager_->update();
        return {};
    }

    static Result<void> checkStatus(const std::vector<int>& status, const char* what) {
        for (std::size_t o = 0; o < status.size(); ++o) {
            if (status[o] != fcl::BVH_OK) {
                return Error(ErrorCode::InvalidArgument, std::string("fcl: ") + what + " object " + std::to_string(o) +
                                                             " failed with BVHReturnCode " + std::to_string(status[o]));
            }
        }
        return {};
    }

    std::vector<TrianglePair> query() {
        // Broad phase over objects (cheap, serial), then one fcl::collide per object pair.
        std::vector<std::pair<fcl::CollisionObjectd*, fcl::CollisionObjectd*>> object_pairs;
        manager_->collide(&object_pairs, [](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
            static_cast<std::vector<std::pair<fcl::CollisionObjectd*, fcl::CollisionObjectd*>>*>(data)->emplace_back(a,
                                                                                                                     b);
            return false;  // keep going
        });
        std::vector<std::vector<TrianglePair>> found(object_pairs.size());
        pool_.parallelFor(object_pairs.size(), 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                fcl::CollisionObjectd* a = object_pairs[i].first;
                fcl::CollisionObjectd* b = object_pairs[i].second;
                // All contacts: the traversal stops only when num_max_contacts is reached.
                const fcl::CollisionRequestd request(std::numeric_limits<std::size_t>::max(), false);
                fcl::CollisionResultd result;
                fcl::collide(a, b, request, result);
                std::vector<fcl::Contactd> contacts;
                result.getContacts(contacts);
                const auto oa = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(a->getUserData()));
                const auto ob = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(b->getUserData()));
                const fcl::CollisionGeometryd* ga = a->collisionGeometry().get();
                for (const fcl::Contactd& c : contacts) {
                    // b1 indexes the first object's triangles. Contact::o1 could say which that
                    // is, but for AABB models FCL collides temporary copies (BVHCollide copies
                    // both models), so o1 matches neither geometry: only trust a clear swap.
                    const bool swapped = c.o2 == ga && c.o1 != ga;
                    TrianglePair p{swapped ? ob : oa, static_cast<std::uint32_t>(c.b1), swapped ? oa : ob,
                                   static_cast<std::uint32_t>(c.b2)};
                    if (std::pair(p.object_b, p.triangle_b) < std::pair(p.object_a, p.triangle_a)) {
                        p = {p.object_b, p.triangle_b, p.object_a, p.triangle_a};
                    }
                    found[i].push_back(p);
                }
            }
        });
        std::vector<TrianglePair> pairs;
        for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        return pairs;
    }

    std::string_view name_;
    PeerMode mode_;
    ThreadPool pool_;
    std::vector<std::shared_ptr<Model>> models_;
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;
    std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager_;
    detail::TopologyCheck topology_;
};

}  // namespace

Result<std::unique_ptr<Peer>> createFclPeer(FclVolume volume, const PeerMode& mode, unsigned threads) {
    if (mode.self_collision) {
        return Error(ErrorCode::InvalidArgument,
                     "fcl: FCL finds no triangle pairs within one object (fcl#333); run it with self_collision off");
    }
    if (volume == FclVolume::Aabb)
        return std::unique_ptr<Peer>(std::make_unique<FclPeer<fcl::AABBd>>("fcl-aabb", mode, threads));
    return std::unique_ptr<Peer>(std::make_unique<FclPeer<fcl::OBBRSSd>>("fcl-obbrss", mode, threads));
}

}  // namespace vkcollide::bench
