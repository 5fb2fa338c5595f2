#include "narrow/triangle_intersection.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "narrow/exact_predicates.hpp"

// The non-degenerate, non-coplanar case follows Moeller's interval test (1997): reject
// when one triangle lies strictly on one side of the other's plane, otherwise both
// triangles cut the line L where the planes meet in an interval, and they intersect iff
// the intervals overlap. Moeller computes the interval ends in floating point; we decide
// the overlap with two exact orientation signs instead (the formulation of Guigue and
// Devillers 2003), so no interval end is ever rounded:
//
// Rotate triangle 1 (p1,q1,r1) and flip the winding of triangle 2 so that p1 is on the
// non-negative side of plane 2 and q1, r1 on the non-positive side (strictly below p1);
// then do the same for triangle 2 against plane 1 (flipping triangle 1). With normals
// n1, n2 and d = n1 x n2, the interval of triangle 1 on L runs from the crossing j of edge
// p1r1 to the crossing i of edge p1q1 (d.j <= d.i), and that of triangle 2 from k on p2q2
// to l on p2r2 (d.k <= d.l). Multilinearity gives
//     orient3d(p1,q1,p2,q2) = -det(q1-p1, q2-p2, k-i),   det(q1-p1, q2-p2, d) < 0,
// so sign(orient3d(p1,q1,p2,q2)) = sign(d.k - d.i), and likewise
// sign(orient3d(p1,r1,p2,r2)) = sign(d.l - d.j). The intervals overlap iff
// d.k <= d.i and d.j <= d.l.

namespace vkcollide::narrow {
namespace {

// Lexicographic order. On a line it is the order along the line (or its reverse), which
// is how the ends of a collinear point set are found without arithmetic.
bool lexLess(const Float3& a, const Float3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// Projection that drops one axis; `axis` 2 keeps (x, y), 0 keeps (y, z), 1 keeps (z, x),
// so the projected orientation of a triangle is the sign of its normal's `axis` component.
Float2 project(const Float3& p, int axis) {
    switch (axis) {
        case 0: return {p.y, p.z};
        case 1: return {p.z, p.x};
        default: return {p.x, p.y};
    }
}

// An axis along which the normal of p, q, r is non-zero, or -1 when they are collinear.
int normalAxis(const Float3& p, const Float3& q, const Float3& r) {
    for (int axis : {2, 0, 1}) {
        if (orient2d(project(p, axis), project(q, axis), project(r, axis)) != 0) return axis;
    }
    return -1;
}

bool sameStrictSign(int a, int b, int c) { return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0); }

// Closed-box test for a point already known to be on the line through a and b.
bool withinBox2d(const Float2& a, const Float2& b, const Float2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Closed 2D segments, either may be a point (Cormen et al., SEGMENTS-INTERSECT).
bool segmentsIntersect2d(const Float2& a, const Float2& b, const Float2& c, const Float2& d) {
    const int d1 = orient2d(c, d, a), d2 = orient2d(c, d, b);
    const int d3 = orient2d(a, b, c), d4 = orient2d(a, b, d);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && withinBox2d(c, d, a)) || (d2 == 0 && withinBox2d(c, d, b)) ||
           (d3 == 0 && withinBox2d(a, b, c)) || (d4 == 0 && withinBox2d(a, b, d));
}

// Point in a closed, non-degenerate 2D triangle of either winding.
bool pointInTriangle2d(const Float2& p, const std::array<Float2, 3>& t) {
    const int s0 = orient2d(t[0], t[1], p), s1 = orient2d(t[1], t[2], p), s2 = orient2d(t[2], t[0], p);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// A closed 2D segment (possibly a point) against a non-degenerate closed 2D triangle:
// either an end is inside, or the segment enters through an edge.
bool segmentTriangle2d(const Float2& a, const Float2& b, const std::array<Float2, 3>& t) {
    if (pointInTriangle2d(a, t) || pointInTriangle2d(b, t)) return true;
    for (int e = 0; e < 3; ++e) {
        if (segmentsIntersect2d(a, b, t[e], t[(e + 1) % 3])) return true;
    }
    return false;
}

std::array<Float2, 3> projectTriangle(std::span<const Float3, 3> t, int axis) {
    return {project(t[0], axis), project(t[1], axis), project(t[2], axis)};
}

// Whether all of `t` lies strictly outside the edge (p, q) of a triangle whose
// orientation is `winding` (+1 or -1): a separating line along that edge.
bool strictlyOutside(const Float2& p, const Float2& q, int winding, const std::array<Float2, 3>& t) {
    for (const Float2& v : t) {
        if (orient2d(p, q, v) * winding >= 0) return false;
    }
    return true;
}

// Two coplanar, non-degenerate triangles, projected to 2D where the projection is
// injective on their plane. Separating axis test: two disjoint convex polygons are
// strictly separated by a line parallel to one of their edges, so the closed triangles
// intersect iff no edge of either has the whole other triangle strictly outside. At most
// 20 orientations (vertex-in-triangle plus edge-crossing tests would take up to 54).
bool coplanarTrianglesIntersect(std::span<const Float3, 3> a, std::span<const Float3, 3> b) {
    const int axis = normalAxis(a[0], a[1], a[2]);  // not -1: a is not degenerate
    const std::array<Float2, 3> pa = projectTriangle(a, axis), pb = projectTriangle(b, axis);
    const int winding_a = orient2d(pa[0], pa[1], pa[2]), winding_b = orient2d(pb[0], pb[1], pb[2]);  // both non-zero
    for (int i = 0; i < 3; ++i) {
        if (strictlyOutside(pa[i], pa[(i + 1) % 3], winding_a, pb)) return false;
        if (strictlyOutside(pb[i], pb[(i + 1) % 3], winding_b, pa)) return false;
    }
    return true;
}

// The two ends of a collinear point triple.
std::pair<Float3, Float3> collinearEnds(std::span<const Float3, 3> t) {
    Float3 lo = t[0], hi = t[0];
    for (int i = 1; i < 3; ++i) {
        if (lexLess(t[i], lo)) lo = t[i];
        if (lexLess(hi, t[i])) hi = t[i];
    }
    return {lo, hi};
}

// Chooses the apex of a triangle from the side signs s of its vertices (not all of one
// strict sign, not all zero) and a flip f (+1/-1) so that f*s[apex] >= 0, f*s[other] < 0
// or f*s[apex] > 0, f*s[other] <= 0: the apex's two edges then cut the plane in the
// two ends of the triangle's interval on L.
int chooseApex(const int s[3], int& out_flip) {
    for (int i = 0; i < 3; ++i) {
        const int o1 = s[(i + 1) % 3], o2 = s[(i + 2) % 3];
        if (s[i] > 0 && o1 <= 0 && o2 <= 0) { out_flip = 1; return i; }
        if (s[i] < 0 && o1 >= 0 && o2 >= 0) { out_flip = -1; return i; }
    }
    // Left: two strictly on one side, the apex on the plane.
    for (int i = 0; i < 3; ++i) {
        if (s[i] == 0) { out_flip = s[(i + 1) % 3] > 0 ? -1 : 1; return i; }
    }
    out_flip = 1;  // unreachable for valid input
    return 0;
}

}  // namespace

bool collinear(const Float3& p, const Float3& q, const Float3& r) noexcept { return normalAxis(p, q, r) < 0; }

bool segmentsIntersect(const Float3& a0, const Float3& a1, const Float3& b0, const Float3& b1) noexcept {
    if (orient3d(a0, a1, b0, b1) != 0) return false;  // intersecting segments are coplanar
    // Coplanar: project along an axis where the common plane has a non-zero normal
    // component, which is injective on that plane.
    const std::array<std::array<Float3, 3>, 4> triples = {{{a0, a1, b0}, {a0, a1, b1}, {b0, b1, a0}, {b0, b1, a1}}};
    for (const auto& t : triples) {
        const int axis = normalAxis(t[0], t[1], t[2]);
        if (axis >= 0) {
            return segmentsIntersect2d(project(a0, axis), project(a1, axis), project(b0, axis), project(b1, axis));
        }
    }
    // All four points on one line: compare the intervals in lexicographic order.
    const Float3& alo = lexLess(a1, a0) ? a1 : a0;
    const Float3& ahi = lexLess(a1, a0) ? a0 : a1;
    const Float3& blo = lexLess(b1, b0) ? b1 : b0;
    const Float3& bhi = lexLess(b1, b0) ? b0 : b1;
    return !lexLess(ahi, blo) && !lexLess(bhi, alo);
}

bool segmentTriangleIntersect(const Float3& s0, const Float3& s1, std::span<const Float3, 3> t) noexcept {
    const int axis = normalAxis(t[0], t[1], t[2]);
    if (axis < 0) {
        const auto [lo, hi] = collinearEnds(t);
        return segmentsIntersect(s0, s1, lo, hi);
    }
    const int o0 = orient3d(t[0], t[1], t[2], s0), o1 = orient3d(t[0], t[1], t[2], s1);
    if (o0 * o1 > 0) return false;
    if (o0 == 0 && o1 == 0) return segmentTriangle2d(project(s0, axis), project(s1, axis), projectTriangle(t, axis));
    // The segment crosses the plane once, so its line is not parallel to it: the line
    // hits the closed triangle iff it passes no edge on the "wrong" side (Pluecker signs).
    const int e0 = orient3d(s0, s1, t[0], t[1]), e1 = orient3d(s0, s1, t[1], t[2]), e2 = orient3d(s0, s1, t[2], t[0]);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

bool trianglesIntersect(std::span<const Float3, 3> a, std::span<const Float3, 3> b) noexcept {
    // Each plane's filter products are shared by its three side tests and by the
    // degeneracy check (the normal's components are the projected orientations).
    //
    // Sides of a's vertices against b's plane; reject if all strictly on one side. This
    // is valid before the degeneracy checks: a degenerate b has every side 0 (exactly),
    // and a degenerate a strictly on one side of b's plane cannot meet b. Most pairs end
    // here or at the same test the other way round.
    const PlaneOrientation plane_b(b[0], b[1], b[2]);
    int side_a[3], side_b[3];
    for (int i = 0; i < 3; ++i) side_a[i] = plane_b.side(a[i]);
    if (sameStrictSign(side_a[0], side_a[1], side_a[2])) return false;
    const PlaneOrientation plane_a(a[0], a[1], a[2]);
    // a in b's plane (the resting contacts' coplanar pairs): the sides of b against a's
    // plane are not needed. They could not reject (a non-degenerate a spans b's plane, so
    // all are 0; a degenerate a has every side 0), and the paths below for a pair with
    // a in b's plane (degenerate or coplanar) do not read them. On a tilted contact each
    // is an exact orient3d, so this halves the exact work of a coplanar pair.
    const bool a_in_plane_b = side_a[0] == 0 && side_a[1] == 0 && side_a[2] == 0;
    if (!a_in_plane_b) {
        for (int i = 0; i < 3; ++i) side_b[i] = plane_a.side(b[i]);
        if (sameStrictSign(side_b[0], side_b[1], side_b[2])) return false;
    }

    // Degenerate triangles are segments (or points).
    if (!plane_a.certainlyNotCollinear() && collinear(a[0], a[1], a[2])) {
        const auto [lo, hi] = collinearEnds(a);
        return segmentTriangleIntersect(lo, hi, b);
    }
    if (!plane_b.certainlyNotCollinear() && collinear(b[0], b[1], b[2])) {
        const auto [lo, hi] = collinearEnds(b);
        return segmentTriangleIntersect(lo, hi, a);
    }

    if (a_in_plane_b) return coplanarTrianglesIntersect(a, b);

    // Normalise a: rotate its apex to p1; a flip of b's winding negates side_a.
    int flip_b = 1;
    const int apex_a = chooseApex(side_a, flip_b);
    Float3 p1 = a[apex_a], q1 = a[(apex_a + 1) % 3], r1 = a[(apex_a + 2) % 3];
    Float3 tb[3] = {b[0], b[1], b[2]};
    if (flip_b < 0) {
        std::swap(tb[1], tb[2]);
        std::swap(side_b[1], side_b[2]);  // side_b does not depend on b's winding
    }
    // Normalise b against a's plane; a flip of a's winding negates side_b and keeps p1.
    int flip_a = 1;
    const int apex_b = chooseApex(side_b, flip_a);
    const Float3 p2 = tb[apex_b], q2 = tb[(apex_b + 1) % 3], r2 = tb[(apex_b + 2) % 3];
    if (flip_a < 0) std::swap(q1, r1);

    return orient3d(p1, q1, p2, q2) <= 0 && orient3d(p1, r1, p2, r2) >= 0;
}

}  // namespace vkcollide::narrow
