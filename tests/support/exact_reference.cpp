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

// Grid cells per task: cells are uneven (a few hold many triangles), so many small tasks
// balance better across threads.
constexpr std::size_t kCellsPerTask = 256;

struct WorldTriangle {
    std::uint32_t object, triangle;
    std::uint32_t vertex_index[3];
    Float3 v[3];
};

struct Box {
    float lo[3], hi[3];
    std::uint32_t id;  // index into the WorldTriangle list
};

// A uniform grid over the scene's triangle boxes. Cells are about twice the median
// triangle box, grown until there are at most kCellsPerTriangle cells per triangle, so
// memory stays linear for scenes that are mostly empty space. Cell coordinates come
// from a monotone function of the position, so a point inside a box always falls in one
// of the cells the box is listed in.
struct Grid {
    static constexpr double kCellsPerTriangle = 4.0;
    double lo[3] = {0, 0, 0};
    double size = 1;
    std::uint64_t dim[3] = {1, 1, 1};

    static Grid fit(const std::vector<Box>& boxes) {
        Grid g;
        double hi[3];
        for (int a = 0; a < 3; ++a) {
            g.lo[a] = boxes[0].lo[a];
            hi[a] = boxes[0].hi[a];
        }
        for (const Box& b : boxes)
            for (int a = 0; a < 3; ++a) {
                g.lo[a] = std::min(g.lo[a], double(b.lo[a]));
                hi[a] = std::max(hi[a], double(b.hi[a]));
            }
        // Median of the boxes' largest extents, from an even sample for big scenes.
        std::vector<double> extents;
        const std::size_t step = std::max<std::size_t>(1, boxes.size() / 65536);
        for (std::size_t i = 0; i < boxes.size(); i += step) {
            const Box& b = boxes[i];
            extents.push_back(std::max({double(b.hi[0]) - b.lo[0], double(b.hi[1]) - b.lo[1], double(b.hi[2]) - b.lo[2]}));
        }
        std::nth_element(extents.begin(), extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2), extents.end());
        const double span = std::max({hi[0] - g.lo[0], hi[1] - g.lo[1], hi[2] - g.lo[2]});
        g.size = std::max(2.0 * extents[extents.size() / 2], span * 1e-6);
        if (!(g.size > 0)) g.size = 1;  // every triangle a point at one place
        const double budget = kCellsPerTriangle * static_cast<double>(boxes.size()) + 8.0;
        for (;;) {
            double cells = 1;
            for (int a = 0; a < 3; ++a) {
                g.dim[a] = static_cast<std::uint64_t>(std::floor((hi[a] - g.lo[a]) / g.size)) + 1;
                cells *= static_cast<double>(g.dim[a]);
            }
            if (cells <= budget) break;
            g.size *= 1.25;
        }
        return g;
    }

    std::uint64_t cellCount() const { return dim[0] * dim[1] * dim[2]; }

    std::uint64_t coord(double x, int a) const {
        const double c = std::floor((x - lo[a]) / size);
        return c <= 0 ? 0 : std::min(dim[a] - 1, static_cast<std::uint64_t>(c));
    }

    std::uint64_t cellOf(double x, double y, double z) const {
        return (coord(z, 2) * dim[1] + coord(y, 1)) * dim[0] + coord(x, 0);
    }

    template <typename F>
    void forEachCell(const Box& b, F&& f) const {
        const std::uint64_t x0 = coord(b.lo[0], 0), x1 = coord(b.hi[0], 0);
        const std::uint64_t y0 = coord(b.lo[1], 1), y1 = coord(b.hi[1], 1);
        const std::uint64_t z0 = coord(b.lo[2], 2), z1 = coord(b.hi[2], 2);
        for (std::uint64_t z = z0; z <= z1; ++z)
            for (std::uint64_t y = y0; y <= y1; ++y)
                for (std::uint64_t x = x0; x <= x1; ++x) f((z * dim[1] + y) * dim[0] + x);
    }
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
    if (tris.empty()) return std::vector<TrianglePair>{};

    std::vector<Box> boxes(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) boxes[i] = boxOf(tris[i], static_cast<std::uint32_t>(i));
    const Grid grid = Grid::fit(boxes);

    // Bucket the triangles by the cells their boxes cover (a counting sort by cell).
    std::vector<std::uint32_t> first(grid.cellCount() + 1, 0);
    for (const Box& b : boxes) grid.forEachCell(b, [&](std::uint64_t cell) { ++first[cell + 1]; });
    for (std::size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];
    std::vector<std::uint32_t> entries(first.back());
    {
        std::vector<std::uint32_t> cursor(first.begin(), first.end() - 1);
        for (const Box& b : boxes) grid.forEachCell(b, [&](std::uint64_t cell) { entries[cursor[cell]++] = b.id; });
    }
    std::vector<std::uint64_t> busy;  // cells holding two triangles or more
    for (std::uint64_t c = 0; c + 1 < first.size(); ++c)
        if (first[c + 1] - first[c] >= 2) busy.push_back(c);

    // Each pair is tested in one cell only: the one holding the low corner of the
    // intersection of the two boxes (it lies in both boxes, so both are listed there).
    ThreadPool pool(options.threads);
    const std::size_t task_count = (busy.size() + kCellsPerTask - 1) / kCellsPerTask;
    std::vector<std::vector<TrianglePair>> found(task_count);
    pool.parallelFor(busy.size(), kCellsPerTask, [&](std::size_t begin, std::size_t end) {
        std::vector<TrianglePair>& out = found[begin / kCellsPerTask];
        std::vector<std::uint32_t> here;
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint64_t cell = busy[k];
            here.assign(entries.begin() + first[cell], entries.begin() + first[cell + 1]);
            // Sorted along x, a triangle meets only the run of successors that start
            // before it ends: big cells cost their overlaps, not their square.
            std::sort(here.begin(), here.end(), [&](std::uint32_t a, std::uint32_t b) { return boxes[a].lo[0] < boxes[b].lo[0]; });
            for (std::size_t i = 0; i < here.size(); ++i) {
                const Box& a = boxes[here[i]];
                const WorldTriangle& ta = tris[a.id];
                for (std::size_t j = i + 1; j < here.size() && boxes[here[j]].lo[0] <= a.hi[0]; ++j) {
                    const Box& b = boxes[here[j]];
                    if (b.lo[1] > a.hi[1] || a.lo[1] > b.hi[1] || b.lo[2] > a.hi[2] || a.lo[2] > b.hi[2]) continue;
                    if (grid.cellOf(std::max(a.lo[0], b.lo[0]), std::max(a.lo[1], b.lo[1]), std::max(a.lo[2], b.lo[2])) != cell)
                        continue;
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
