#include "proximity/proximity_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <tuple>

namespace vkcollide::test {
namespace {

using Q = __float128;
struct V {
    Q x, y, z;
};
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator*(Q s, V a) { return {s * a.x, s * a.y, s * a.z}; }
Q dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V of(Float3 p) { return {Q(p.x), Q(p.y), Q(p.z)}; }
Q clamp01(Q t) { return t < 0 ? Q(0) : (t > 1 ? Q(1) : t); }

Q pointSegment2(V p, V a, V b) {
    const V ab = b - a;
    const Q l2 = dot(ab, ab);
    const Q t = l2 > 0 ? clamp01(dot(p - a, ab) / l2) : Q(0);
    const V d = p - (a + t * ab);
    return dot(d, d);
}

Q pointTriangle2(V p, V a, V b, V c) {
    Q best = std::min(pointSegment2(p, a, b), std::min(pointSegment2(p, b, c), pointSegment2(p, c, a)));
    const V n = cross(b - a, c - a);
    const Q nn = dot(n, n);
    if (nn > 0) {
        // Inside when p's projection is on the inner side of all three edges.
        const V q = p - (dot(p - a, n) / nn) * n;
        if (dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 && dot(cross(a - c, q - c), n) >= 0) {
            const Q h = dot(p - a, n);
            best = std::min(best, h * h / nn);
        }
    }
    return best;
}

Q segmentSegment2(V p1, V q1, V p2, V q2) {
    Q best = std::min(std::min(pointSegment2(p1, p2, q2), pointSegment2(q1, p2, q2)),
                      std::min(pointSegment2(p2, p1, q1), pointSegment2(q2, p1, q1)));
    const V d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const V c = cross(d1, d2);
    const Q cc = dot(c, c);
    if (cc > 0) {
        // The lines' closest points; when both lie inside the segments they are the closest.
        const Q a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), cd = dot(d1, r), f = dot(d2, r);
        const Q denom = a * e - b * b;
        const Q s = (b * f - cd * e) / denom, t = (a * f - b * cd) / denom;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            const V d = (p1 + s * d1) - (p2 + t * d2);
            best = std::min(best, dot(d, d));
        }
    }
    return best;
}

bool sameBits(Float3 a, Float3 b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Edge {
    std::uint32_t lo, hi;
};
std::vector<Edge> edgesOf(const ProximityObject& o) {
    std::vector<Edge> e;
    for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = o.indices[t + k], b = o.indices[t + (k + 1) % 3];
            e.push_back({std::min(a, b), std::max(a, b)});
        }
    std::sort(e.begin(), e.end(), [](Edge x, Edge y) { return std::tie(x.lo, x.hi) < std::tie(y.lo, y.hi); });
    e.erase(std::unique(e.begin(), e.end(), [](Edge x, Edge y) { return x.lo == y.lo && x.hi == y.hi; }), e.end());
    return e;
}
std::vector<std::uint32_t> verticesOf(const ProximityObject& o) {
    std::vector<std::uint32_t> v(o.indices);
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

// Box of points, padded: pairs whose boxes are farther apart than the limit are skipped.
struct Box {
    float lo[3], hi[3];
};
template <typename It>
Box boxOf(const ProximityObject& o, It first, It last) {
    Box b{{3e38f, 3e38f, 3e38f}, {-3e38f, -3e38f, -3e38f}};
    for (It i = first; i != last; ++i) {
        const Float3 p = o.world[*i];
        const float c[3] = {p.x, p.y, p.z};
        for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], c[k]), b.hi[k] = std::max(b.hi[k], c[k]);
    }
    return b;
}
bool apart(const Box& a, const Box& b, double limit) {
    for (int k = 0; k < 3; ++k)
        if (double(a.lo[k]) - double(b.hi[k]) > limit * 1.001 || double(b.lo[k]) - double(a.hi[k]) > limit * 1.001) return true;
    return false;
}

}  // namespace

std::vector<ReferenceProximity> referenceProximity(const std::vector<ProximityObject>& objects, double limit) {
    std::vector<ReferenceProximity> out;
    const Q limit2 = Q(limit) * Q(limit);
    for (std::size_t ia = 0; ia < objects.size(); ++ia)
        for (std::size_t ib = 0; ib < objects.size(); ++ib) {
            const ProximityObject& A = objects[ia];
            const ProximityObject& B = objects[ib];
            const bool same = ia == ib;
            if (same && !A.self) continue;
            // Vertices of A against triangles of B.
            for (std::uint32_t v : verticesOf(A)) {
                const std::uint32_t vv[1] = {v};
                const Box bv = boxOf(A, vv, vv + 1);
                for (std::size_t t = 0; t + 2 < B.indices.size(); t += 3) {
                    const std::uint32_t* tri = &B.indices[t];
                    if (apart(bv, boxOf(B, tri, tri + 3), limit)) continue;
                    if (same && (v == tri[0] || v == tri[1] || v == tri[2] || sameBits(A.world[v], B.world[tri[0]]) ||
                                 sameBits(A.world[v], B.world[tri[1]]) || sameBits(A.world[v], B.world[tri[2]])))
                        continue;
                    const Q d2 = pointTriangle2(of(A.world[v]), of(B.world[tri[0]]), of(B.world[tri[1]]), of(B.world[tri[2]]));
                    if (d2 <= limit2)
                        out.push_back({ProximityKind::VertexTriangle, A.id, v, kNoPrimitive, B.id, std::uint32_t(t / 3), kNoPrimitive,
                                       std::sqrt((long double)d2)});
                }
            }
            if (ib < ia) continue;  // edge-edge pairs once per object pair
            const std::vector<Edge> ea = edgesOf(A), eb = edgesOf(B);
            for (std::size_t i = 0; i < ea.size(); ++i) {
                const std::uint32_t ai[2] = {ea[i].lo, ea[i].hi};
                const Box ba = boxOf(A, ai, ai + 2);
                for (std::size_t j = same ? i + 1 : 0; j < eb.size(); ++j) {
                    const std::uint32_t bi[2] = {eb[j].lo, eb[j].hi};
                    if (apart(ba, boxOf(B, bi, bi + 2), limit)) continue;
                    if (same && (ai[0] == bi[0] || ai[0] == bi[1] || ai[1] == bi[0] || ai[1] == bi[1] ||
                                 sameBits(A.world[ai[0]], B.world[bi[0]]) || sameBits(A.world[ai[0]], B.world[bi[1]]) ||
                                 sameBits(A.world[ai[1]], B.world[bi[0]]) || sameBits(A.world[ai[1]], B.world[bi[1]])))
                        continue;
                    const Q d2 = segmentSegment2(of(A.world[ai[0]]), of(A.world[ai[1]]), of(B.world[bi[0]]), of(B.world[bi[1]]));
                    if (d2 > limit2) continue;
                    // The library's order: the lower (object, lo, hi) first.
                    ReferenceProximity r{ProximityKind::EdgeEdge, A.id, ai[0], ai[1], B.id, bi[0], bi[1], std::sqrt((long double)d2)};
                    if (std::tie(r.object_b, r.b0, r.b1) < std::tie(r.object_a, r.a0, r.a1)) {
                        std::swap(r.object_a, r.object_b);
                        std::swap(r.a0, r.b0);
                        std::swap(r.a1, r.b1);
                    }
                    out.push_back(r);
                }
            }
        }
    std::sort(out.begin(), out.end(), [](const ReferenceProximity& x, const ReferenceProximity& y) {
        return std::tie(x.kind, x.object_a, x.a0, x.a1, x.object_b, x.b0, x.b1) < std::tie(y.kind, y.object_a, y.a0, y.a1, y.object_b, y.b0, y.b1);
    });
    return out;
}

}  // namespace vkcollide::test
