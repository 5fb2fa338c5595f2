#include "support/exact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <string>

#include "narrow/exact_predicates.hpp"
#include "narrow/neighbours.hpp"
#include "vkcollide/thread_pool.hpp"
#include "narrow/triangle_intersection.hpp"

namespace vkcollide::test {
namespace {

// Sweep positions per task: each position scans its overlapping successors, so tasks
// are cheap to hand out yet uneven; many small ones balance better.
constexpr std::size_t kSweepPerTask = 1024;

struct WorldTriangle {
    std::uint32_t object, triangle;
    std::uint32_t vertex_index[3];
    Float3 v[3];
};

struct Box {
    float lo[3], hi[3];
    std::uint32_t id;  // index into the WorldTriangle list
};

std::string objectName(std::size_t index, const HostMesh* mesh) {
    std::string s = "object " + std::to_string(index);
    if (mesh && !mesh->name.empty()) s += " ('" + mesh->name + "')";
    return s;
}

Result<std::vector<WorldTriangle>> gatherTriangles(std::span<const ReferenceObject> objects) {
    std::vector<WorldTriangle> tris;
    for (std::size_t o = 0; o < objects.size(); ++o) {
        const ReferenceObject& object = objects[o];
        const HostMesh* mesh = object.mesh;
        if (!mesh) return Error(ErrorCode::InvalidMesh, objectName(o, mesh) + ": mesh is null");
        if (mesh->indices.size() % 3 != 0) {
            return Error(ErrorCode::InvalidMesh, objectName(o, mesh) + ": index count is not a multiple of 3");
        }
        const Transform& m = object.transform;
        if (!std::all_of(m.begin(), m.end(), [](float x) { return std::isfinite(x); })) {
            return Error(ErrorCode::InvalidArgument, objectName(o, mesh) + ": transform is not finite");
        }
        if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1) {
            return Error(ErrorCode::InvalidArgument, objectName(o, mesh) + ": transform's last row is not (0,0,0,1)");
        }
        for (const Float3& p : mesh->positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                return Error(ErrorCode::InvalidMesh, objectName(o, mesh) + ": non-finite vertex");
            }
        }
        const std::vector<Float3> world = worldPositions(*mesh, m);
        for (const Float3& p : world) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                return Error(ErrorCode::InvalidArgument, objectName(o, mesh) + ": transform overflows a vertex");
            }
        }
        for (std::size_t t = 0; t < mesh->triangleCount(); ++t) {
            WorldTriangle tri{};
            tri.object = static_cast<std::uint32_t>(o);
            tri.triangle = static_cast<std::uint32_t>(t);
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t index = mesh->indices[3 * t + k];
                if (index >= world.size()) {
                    return Error(ErrorCode::InvalidMesh, objectName(o, mesh) + ": triangle " + std::to_string(t) +
                                                             " has index " + std::to_string(index) + " out of range");
                }
                tri.vertex_index[k] = index;
                tri.v[k] = world[index];
            }
            tris.push_back(tri);
        }
    }
    return tris;
}

Box boxOf(const WorldTriangle& t, std::uint32_t id) {
    Box b{};
    b.id = id;
    const float xs[3] = {t.v[0].x, t.v[1].x, t.v[2].x};
    const float ys[3] = {t.v[0].y, t.v[1].y, t.v[2].y};
    const float zs[3] = {t.v[0].z, t.v[1].z, t.v[2].z};
    const float* axes[3] = {xs, ys, zs};
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = std::min({axes[a][0], axes[a][1], axes[a][2]});
        b.hi[a] = std::max({axes[a][0], axes[a][1], axes[a][2]});
    }
    return b;
}

TrianglePair orderedPair(const WorldTriangle& a, const WorldTriangle& b) {
    TrianglePair p{a.object, a.triangle, b.object, b.triangle};
    if (std::pair(b.object, b.triangle) < std::pair(a.object, a.triangle)) p = {b.object, b.triangle, a.object, a.triangle};
    return p;
}

}  // namespace

Transform transformFrom3x4(const std::array<float, 12>& rows) {
    Transform m = kIdentityTransform;
    std::copy(rows.begin(), rows.end(), m.begin());
    return m;
}

Transform translation(float x, float y, float z) { return transformFrom3x4({1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z}); }

std::vector<Float3> worldPositions(const HostMesh& mesh, const Transform& m) {
    if (m == kIdentityTransform) return mesh.positions;  // keeps -0.0f and friends bit for bit
    std::vector<Float3> out;
    out.reserve(mesh.positions.size());
    for (const Float3& p : mesh.positions) {
        const auto row = [&](int r) {
            return static_cast<float>(double(m[4 * r]) * p.x + double(m[4 * r + 1]) * p.y + double(m[4 * r + 2]) * p.z +
                                      double(m[4 * r + 3]));
        };
        out.push_back({row(0), row(1), row(2)});
    }
    return out;
}

Result<std::vector<TrianglePair>> computeReferencePairs(std::span<const ReferenceObject> objects,
                                                       const ReferenceOptions& options) {
    Result<std::vector<WorldTriangle>> gathered = gatherTriangles(objects);
    if (!gathered) return gathered.error();
    const std::vector<WorldTriangle>& tris = *gathered;

    std::vector<Box> boxes(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) boxes[i] = boxOf(tris[i], static_cast<std::uint32_t>(i));

    // Sweep along the axis where box centres spread most: fewer false overlaps than a
    // fixed x axis for elongated scenes.
    int axis = 0;
    {
        double best = -1;
        for (int a = 0; a < 3; ++a) {
            double mean = 0, sq = 0;
            for (const Box& b : boxes) {
                const double c = 0.5 * (double(b.lo[a]) + b.hi[a]);
                mean += c;
                sq += c * c;
            }
            const double n = std::max<double>(1.0, static_cast<double>(boxes.size()));
            const double variance = sq / n - (mean / n) * (mean / n);
            if (variance > best) {
                best = variance;
                axis = a;
            }
        }
    }
    const int axis1 = (axis + 1) % 3, axis2 = (axis + 2) % 3;
    std::sort(boxes.begin(), boxes.end(),
              [&](const Box& a, const Box& b) { return a.lo[axis] != b.lo[axis] ? a.lo[axis] < b.lo[axis] : a.id < b.id; });

    ThreadPool pool(options.threads);
    const std::size_t task_count = (boxes.size() + kSweepPerTask - 1) / kSweepPerTask;
    std::vector<std::vector<TrianglePair>> found(task_count);
    pool.parallelFor(boxes.size(), kSweepPerTask, [&](std::size_t begin, std::size_t end) {
        std::vector<TrianglePair>& out = found[begin / kSweepPerTask];
        for (std::size_t s = begin; s < end; ++s) {
            const Box& a = boxes[s];
            const WorldTriangle& ta = tris[a.id];
            for (std::size_t t = s + 1; t < boxes.size() && boxes[t].lo[axis] <= a.hi[axis]; ++t) {
                const Box& b = boxes[t];
                if (b.lo[axis1] > a.hi[axis1] || a.lo[axis1] > b.hi[axis1]) continue;
                if (b.lo[axis2] > a.hi[axis2] || a.lo[axis2] > b.hi[axis2]) continue;
                const WorldTriangle& tb = tris[b.id];
                if (ta.object == tb.object) {
                    if (!objects[ta.object].self_collision) continue;
                    if (narrow::areNeighbours(ta.vertex_index, ta.v, tb.vertex_index, tb.v)) continue;
                } else if (options.may_collide &&
                           !options.may_collide(std::min(ta.object, tb.object), std::max(ta.object, tb.object))) {
                    continue;
                }
                if (narrow::trianglesIntersect(ta.v, tb.v)) out.push_back(orderedPair(ta, tb));
            }
        }
    });

    std::vector<TrianglePair> pairs;
    for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

Result<std::vector<CandidateTriangle>> allTrianglesAsCandidates(std::span<const ReferenceObject> objects) {
    Result<std::vector<WorldTriangle>> gathered = gatherTriangles(objects);
    if (!gathered) return gathered.error();
    const std::vector<WorldTriangle>& tris = *gathered;

    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const Box b = boxOf(tris[i], 0);
        for (int a = 0; a < 3; ++a) {
            lo[a] = i == 0 ? b.lo[a] : std::min(lo[a], b.lo[a]);
            hi[a] = i == 0 ? b.hi[a] : std::max(hi[a], b.hi[a]);
        }
    }
    // Rounded subtraction and division by a positive constant are both monotone, so the
    // mapping keeps every (non-strict) order between coordinates.
    const auto map = [&](float x, int a) {
        const float extent = hi[a] - lo[a];
        return extent > 0 ? (x - lo[a]) / extent : 0.0f;
    };
    std::vector<CandidateTriangle> out;
    out.reserve(tris.size());
    for (const WorldTriangle& t : tris) {
        const Box b = boxOf(t, 0);
        CandidateTriangle c{};
        c.object = t.object;
        c.triangle = t.triangle;
        std::copy(std::begin(t.vertex_index), std::end(t.vertex_index), c.vertex_index);
        std::copy(std::begin(t.v), std::end(t.v), c.v);
        c.box[0] = map(b.lo[0], 0);
        c.box[1] = map(b.lo[1], 1);
        c.box[2] = map(b.hi[0], 0);
        c.box[3] = map(b.hi[1], 1);
        c.zmin = map(b.lo[2], 2);
        c.zmax = map(b.hi[2], 2);
        out.push_back(c);
    }
    return out;
}

PairComparison comparePairs(std::span<const TrianglePair> found, std::span<const TrianglePair> reference) {
    const auto normalise = [](std::span<const TrianglePair> in) {
        std::vector<TrianglePair> out;
        out.reserve(in.size());
        for (const TrianglePair& p : in) {
            if (std::pair(p.object_b, p.triangle_b) < std::pair(p.object_a, p.triangle_a)) {
                out.push_back({p.object_b, p.triangle_b, p.object_a, p.triangle_a});
            } else {
                out.push_back(p);
            }
        }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    };
    const std::vector<TrianglePair> f = normalise(found), r = normalise(reference);
    PairComparison c;
    std::set_difference(r.begin(), r.end(), f.begin(), f.end(), std::back_inserter(c.missed));
    std::set_difference(f.begin(), f.end(), r.begin(), r.end(), std::back_inserter(c.spurious));
    c.false_negatives = c.missed.size();
    c.false_positives = c.spurious.size();
    c.true_positives = f.size() - c.false_positives;
    if (c.true_positives + c.false_positives > 0) {
        c.precision = static_cast<double>(c.true_positives) / static_cast<double>(c.true_positives + c.false_positives);
    }
    if (c.true_positives + c.false_negatives > 0) {
        c.recall = static_cast<double>(c.true_positives) / static_cast<double>(c.true_positives + c.false_negatives);
    }
    return c;
}

Contact classifyContact(const std::array<Float3, 3>& a, const std::array<Float3, 3>& b) {
    auto straddles = [](const std::array<Float3, 3>& plane, const std::array<Float3, 3>& t) {
        bool below = false, above = false;
        for (const Float3& p : t) {
            const int o = narrow::orient3d(plane[0], plane[1], plane[2], p);
            below |= o < 0, above |= o > 0;
        }
        return below && above;
    };
    return straddles(a, b) && straddles(b, a) ? Contact::Crossing : Contact::Touching;
}

Result<std::vector<Contact>> classifyPairs(std::span<const ReferenceObject> objects, std::span<const TrianglePair> pairs) {
    std::vector<std::vector<Float3>> world;
    for (const ReferenceObject& o : objects) {
        if (!o.mesh) return Error(ErrorCode::InvalidMesh, "classifyPairs: null mesh");
        world.push_back(worldPositions(*o.mesh, o.transform));
    }
    auto corners = [&](std::uint32_t object, std::uint32_t triangle) -> Result<std::array<Float3, 3>> {
        if (object >= objects.size() || std::size_t(triangle) * 3 + 2 >= objects[object].mesh->indices.size())
            return Error(ErrorCode::InvalidArgument, "classifyPairs: pair outside the scene");
        const auto& idx = objects[object].mesh->indices;
        return std::array<Float3, 3>{world[object][idx[triangle * 3]], world[object][idx[triangle * 3 + 1]],
                                     world[object][idx[triangle * 3 + 2]]};
    };
    std::vector<Contact> out;
    out.reserve(pairs.size());
    for (const TrianglePair& p : pairs) {
        auto a = corners(p.object_a, p.triangle_a), b = corners(p.object_b, p.triangle_b);
        if (!a) return a.error();
        if (!b) return b.error();
        out.push_back(classifyContact(*a, *b));
    }
    return out;
}

}  // namespace vkcollide::test
