#include "contacts/pair_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "contacts/exact_points.hpp"
#include "narrow/exact_predicates.hpp"

// How (docs/contacts.md, "Where two triangles meet"): the exact orientation signs of each
// triangle's vertices against the other's plane decide the case, as in the exact test.
//   Crossing planes: each triangle's cut by the other's plane (its vertices in that plane,
//     and the points where its edges change side) is a segment of the planes' common line;
//     the contact is where the two cuts overlap along that line.
//   One plane: the overlap of triangle a and b (in the plane's two dominant axes, points
//     kept in 3D): an area (Coplanar), a segment or a point.
//   A zero-area triangle (a segment or a point) has no plane of its own: its cut by the
//     other's plane, or, when it lies in that plane, its overlap with the other triangle.
// Every end point is an exact intersection point (a vertex, an edge crossing a plane, an
// edge crossing an edge) with each coordinate correctly rounded from its exact construction
// (contacts/exact_points.hpp). Crossing planes: every cut point is rounded, and the overlap
// of the cuts is ordered on the rounded points (a double interpolation is too rough to order
// them when coordinates differ by many magnitudes, and a point taken out of order would lie
// outside the other cut). One plane: every corner is a corner of the overlap, so the
// diameter is chosen on double approximations and only its two ends rounded. The coplanar
// area stays a double computation (a Sutherland-Hodgman clip).

namespace vkcollide::contacts {
namespace {

struct D3 {
    double x = 0, y = 0, z = 0;
};
D3 d3(const Float3& p) { return {p.x, p.y, p.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(double s, const D3& a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(const D3& a) { return std::sqrt(dot(a, a)); }
D3 unit(const D3& a) {
    const double l = length(a);
    return l > 0 && std::isfinite(l) ? (1 / l) * a : D3{};
}
Float3 toFloat(const D3& a) { return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)}; }

// A corner of a coplanar overlap: what it is exactly, and roughly where (in double, to
// choose the two ends before rounding only those).
struct Corner {
    D3 approx;
    ExactPoint exact;
};

narrow::Float2 dropAxis(const Float3& p, int axis) {
    return axis == 0 ? narrow::Float2{p.y, p.z} : (axis == 1 ? narrow::Float2{p.x, p.z} : narrow::Float2{p.x, p.y});
}

// The coplanar overlap's diameter: chosen on the corners' approximations, only the two
// chosen rounded exactly.
PairContact fromCorners(const Corner* corners, int count, const D3& normal) {
    PairContact c;
    c.normal = toFloat(normal);
    if (count == 0) return c;
    int first = 0, second = 0;
    double far = -1;
    for (int i = 0; i < count; ++i)
        for (int j = i + 1; j < count; ++j)
            if (const D3 d = corners[j].approx - corners[i].approx; dot(d, d) > far) {
                far = dot(d, d);
                first = i;
                second = j;
            }
    c.start = roundExact(corners[first].exact);
    c.end = roundExact(corners[second].exact);
    c.shape = c.start.x == c.end.x && c.start.y == c.end.y && c.start.z == c.end.z ? ContactShape::Point : ContactShape::Segment;
    return c;
}

// Exactly: the triangle's vertices are collinear (its three axis projections have no area).
// Not the double normal's being zero: differences of floats of very different magnitudes
// round, and a thin triangle's double cross product can vanish.
bool zeroArea(const std::array<Float3, 3>& t) {
    for (int axis = 0; axis < 3; ++axis)
        if (narrow::orient2d(dropAxis(t[0], axis), dropAxis(t[1], axis), dropAxis(t[2], axis)) != 0) return false;
    return true;
}

// The points of triangle t in the plane of `plane`: its vertices with sign 0, and where an
// edge goes from one side to the other (signs exact, each point rounded from its exact
// construction).
int planeCut(const std::array<Float3, 3>& t, const int (&sign)[3], const std::array<Float3, 3>& plane, const double (&det)[3],
             const double (&error)[3], Float3 (&out)[6]) {
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        if (sign[i] == 0) out[count++] = t[i];
        const int j = (i + 1) % 3;
        if (sign[i] * sign[j] < 0) out[count++] = roundPlaneCrossing(t[i], t[j], plane, det[i], error[i], det[j], error[j]);
    }
    return count;
}

// The two points farthest apart, measured in double (the first twice for one point).
std::pair<Float3, Float3> diameter(const Float3* points, int count) {
    std::pair<Float3, Float3> best{points[0], points[0]};
    double far = -1;
    for (int i = 0; i < count; ++i)
        for (int j = i + 1; j < count; ++j)
            if (const D3 d = d3(points[j]) - d3(points[i]); dot(d, d) > far) {
                far = dot(d, d);
                best = {points[i], points[j]};
            }
    return best;
}

// The contact of a point set on one line or in one plane: Segment/Point from its extremes.
PairContact fromPoints(const Float3* points, int count, const D3& normal) {
    PairContact c;
    c.normal = toFloat(normal);
    if (count == 0) return c;
    std::tie(c.start, c.end) = diameter(points, count);
    c.shape = c.start.x == c.end.x && c.start.y == c.end.y && c.start.z == c.end.z ? ContactShape::Point : ContactShape::Segment;
    return c;
}

// The corners of the overlap of `subject` with `clipper` (all six points in one plane, the
// clipper with an area), decided combinatorially by exact orient2d in the two coordinates
// that drop `axis` (the projection keeps the clipper's area): subject vertices in the
// clipper, clipper vertices in the subject (on it, for a zero-area subject), and proper
// crossings of a subject edge with a clipper edge. Returns 0 when the projection loses the
// clipper's area on every axis (a clipper only the double normal calls non-flat).
int overlapCorners(const std::array<Float3, 3>& subject, const std::array<Float3, 3>& clipper, int axis, Corner (&out)[16]) {
    narrow::Float2 s[3], c[3];
    int c_turn = 0;
    for (int tries = 0; tries < 3 && c_turn == 0; ++tries, axis = (axis + 1) % 3) {
        for (int i = 0; i < 3; ++i) c[i] = dropAxis(clipper[i], axis);
        c_turn = narrow::orient2d(c[0], c[1], c[2]);
    }
    if (c_turn == 0) return 0;
    axis = (axis + 2) % 3;  // the loop stepped past the axis that worked
    for (int i = 0; i < 3; ++i) s[i] = dropAxis(subject[i], axis);
    const int s_turn = narrow::orient2d(s[0], s[1], s[2]);
    // side_s[i][e]: subject vertex i against clipper edge e; side_c[e][i]: clipper vertex e
    // against subject edge i. Each is needed twice (inside, crossing): computed once.
    int side_s[3][3], side_c[3][3];
    for (int i = 0; i < 3; ++i)
        for (int e = 0; e < 3; ++e) {
            side_s[i][e] = narrow::orient2d(c[e], c[(e + 1) % 3], s[i]);
            side_c[e][i] = narrow::orient2d(s[i], s[(i + 1) % 3], c[e]);
        }
    // Inside (or on) triangle t of turn `turn` by the signs against its edges; for turn 0,
    // on one of its edges.
    const auto inside = [](const narrow::Float2(&t)[3], int turn, const int(&side)[3], const narrow::Float2& p) {
        for (int i = 0; i < 3; ++i) {
            const narrow::Float2 &e0 = t[i], &e1 = t[(i + 1) % 3];
            if (turn != 0 && side[i] * turn < 0) return false;
            if (turn == 0 && side[i] == 0 && std::min(e0.x, e1.x) <= p.x && p.x <= std::max(e0.x, e1.x) && std::min(e0.y, e1.y) <= p.y &&
                p.y <= std::max(e0.y, e1.y))
                return true;
        }
        return turn != 0;
    };
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        if (inside(c, c_turn, side_s[i], s[i])) out[count++] = {d3(subject[i]), {ExactPoint::Kind::Vertex, 0, subject[i], {}, {}, {}, {}}};
        if (inside(s, s_turn, side_c[i], c[i])) out[count++] = {d3(clipper[i]), {ExactPoint::Kind::Vertex, 0, clipper[i], {}, {}, {}, {}}};
    }
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        for (int e = 0; e < 3; ++e) {
            const int f = (e + 1) % 3;
            if (side_s[i][e] * side_s[j][e] >= 0 || side_c[e][i] * side_c[f][i] >= 0) continue;
            double error_i, error_j;  // unused: the approximation needs no bound
            const double side_i = narrow::orient2dEstimate(c[e], c[f], s[i], error_i);
            const double side_j = narrow::orient2dEstimate(c[e], c[f], s[j], error_j);
            const double t = side_i != side_j ? std::clamp(side_i / (side_i - side_j), 0.0, 1.0) : 0.5;
            out[count++] = {
                d3(subject[i]) + t * (d3(subject[j]) - d3(subject[i])),
                {ExactPoint::Kind::LineCrossing, static_cast<std::uint8_t>(axis), subject[i], subject[j], clipper[e], clipper[f], {}}};
        }
    }
    return count;
}

// Clips `subject` (n points, in the plane of `clipper`) by the clipper triangle, in the two
// coordinates that drop the clipper normal's largest axis. Returns the clipped polygon's size.
int clipInPlane(const D3* subject, int n, const D3 (&clipper)[3], const D3& clipper_normal, D3 (&out)[12]) {
    const double ax = std::fabs(clipper_normal.x), ay = std::fabs(clipper_normal.y), az = std::fabs(clipper_normal.z);
    const int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
    const auto u = [drop](const D3& p) { return drop == 0 ? p.y : p.x; };
    const auto v = [drop](const D3& p) { return drop == 2 ? p.y : p.z; };
    const auto side = [&](const D3& a, const D3& b, const D3& p) { return (u(b) - u(a)) * (v(p) - v(a)) - (v(b) - v(a)) * (u(p) - u(a)); };
    const double orientation = side(clipper[0], clipper[1], clipper[2]) >= 0 ? 1.0 : -1.0;
    D3 buffer[2][12];
    int size = std::min(n, 12);
    std::copy(subject, subject + size, buffer[0]);
    int current = 0;
    for (int e = 0; e < 3 && size > 0; ++e) {
        const D3 &a = clipper[e], &b = clipper[(e + 1) % 3];
        const D3* in = buffer[current];
        D3* kept = buffer[1 - current];
        int next = 0;
        for (int i = 0; i < size && next < 11; ++i) {
            const D3 &p = in[i], &q = in[(i + 1) % size];
            const double sp = orientation * side(a, b, p), sq = orientation * side(a, b, q);
            if (sp >= 0) kept[next++] = p;
            if ((sp >= 0) != (sq >= 0) && size > 1) {
                const double s = std::clamp(sp / (sp - sq), 0.0, 1.0);
                kept[next++] = p + s * (q - p);
            }
        }
        size = next;
        current = 1 - current;
    }
    std::copy(buffer[current], buffer[current] + size, out);
    return size;
}

double polygonArea(const D3* points, int count) {
    D3 sum;
    for (int i = 1; i + 1 < count; ++i) sum = sum + cross(points[i] - points[0], points[i + 1] - points[0]);
    return 0.5 * length(sum);
}

}  // namespace

PairContact pairContact(const std::array<Float3, 3>& a, const std::array<Float3, 3>& b) noexcept {
    const D3 A[3] = {d3(a[0]), d3(a[1]), d3(a[2])}, B[3] = {d3(b[0]), d3(b[1]), d3(b[2])};
    const D3 na = cross(A[1] - A[0], A[2] - A[0]), nb = cross(B[1] - B[0], B[2] - B[0]);
    const D3 normal = unit(unit(nb) - unit(na));
    // The signs as orient3d gives them, its filter's values kept for the crossings' rounding.
    int sa[3], sb[3];
    double det_a[3], error_a[3], det_b[3], error_b[3];
    for (int i = 0; i < 3; ++i) {
        det_a[i] = narrow::orient3dEstimate(b[0], b[1], b[2], a[i], error_a[i]);
        det_b[i] = narrow::orient3dEstimate(a[0], a[1], a[2], b[i], error_b[i]);
        sa[i] = std::fabs(det_a[i]) > error_a[i] ? (det_a[i] > 0 ? 1 : -1) : narrow::orient3d(b[0], b[1], b[2], a[i]);
        sb[i] = std::fabs(det_b[i]) > error_b[i] ? (det_b[i] > 0 ? 1 : -1) : narrow::orient3d(a[0], a[1], a[2], b[i]);
    }
    const bool a_flat = zeroArea(a), b_flat = zeroArea(b);
    const bool a_in_b = !b_flat && sa[0] == 0 && sa[1] == 0 && sa[2] == 0;
    const bool b_in_a = !a_flat && sb[0] == 0 && sb[1] == 0 && sb[2] == 0;
    if (a_flat && b_flat) {  // two segments or points: where they are closest to each other's centroid
        const D3 mid = (1.0 / 6) * (A[0] + A[1] + A[2] + B[0] + B[1] + B[2]);
        PairContact c;
        c.start = c.end = toFloat(mid);
        return c;
    }
    if (a_in_b || b_in_a) {
        // One plane: the overlap with a triangle with an area (the other, or the flat one).
        const bool clip_by_b = !b_flat;
        const D3 clip_normal = clip_by_b ? nb : na;
        const double ax = std::fabs(clip_normal.x), ay = std::fabs(clip_normal.y), az = std::fabs(clip_normal.z);
        Corner corners[16];
        const int count = overlapCorners(clip_by_b ? a : b, clip_by_b ? b : a, ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2), corners);
        PairContact c = fromCorners(corners, count, normal);
        if (count == 0 || a_flat || b_flat) return c;
        D3 polygon[12];
        const int clipped = clipInPlane(clip_by_b ? A : B, 3, clip_by_b ? B : A, clip_normal, polygon);
        const double area = polygonArea(polygon, clipped);
        if (area > 0 && c.shape == ContactShape::Segment) {
            c.shape = ContactShape::Coplanar;
            c.area = static_cast<float>(area);
        }
        return c;
    }
    Float3 cut_a[6], cut_b[6];
    const int na_count = b_flat ? 0 : planeCut(a, sa, b, det_a, error_a, cut_a);
    const int nb_count = a_flat ? 0 : planeCut(b, sb, a, det_b, error_b, cut_b);
    if (a_flat) return fromPoints(cut_a, na_count, normal);  // a's segment meets b's plane in a point
    if (b_flat) return fromPoints(cut_b, nb_count, normal);
    if (na_count == 0 || nb_count == 0) return fromPoints(na_count ? cut_a : cut_b, std::max(na_count, nb_count), normal);
    // Both cuts lie on the planes' common line: their overlap along it. The direction is
    // that of the points' own diameter, not n_a x n_b, which near-parallel planes make
    // inaccurate in double; the order is that of the rounded points (ones closer than their
    // rounding may be taken in the wrong order).
    Float3 all[12];
    std::copy(cut_a, cut_a + na_count, all);
    std::copy(cut_b, cut_b + nb_count, all + na_count);
    const auto [from, to] = diameter(all, na_count + nb_count);
    const D3 line = d3(to) - d3(from);
    const auto extent = [&](const Float3* points, int count) {
        std::pair<int, int> ends{0, 0};
        for (int i = 1; i < count; ++i) {
            if (dot(d3(points[i]), line) < dot(d3(points[ends.first]), line)) ends.first = i;
            if (dot(d3(points[i]), line) > dot(d3(points[ends.second]), line)) ends.second = i;
        }
        return ends;
    };
    const auto [a_lo, a_hi] = extent(cut_a, na_count);
    const auto [b_lo, b_hi] = extent(cut_b, nb_count);
    const Float3 lo = dot(d3(cut_a[a_lo]), line) >= dot(d3(cut_b[b_lo]), line) ? cut_a[a_lo] : cut_b[b_lo];
    const Float3 hi = dot(d3(cut_a[a_hi]), line) <= dot(d3(cut_b[b_hi]), line) ? cut_a[a_hi] : cut_b[b_hi];
    // Touching (one point) with the rounded points crossed: the point is lo (and hi).
    const Float3 ends[2] = {lo, dot(d3(hi), line) < dot(d3(lo), line) ? lo : hi};
    return fromPoints(ends, 2, normal);
}

void pairContacts(std::span<const TrianglePair> pairs, const TriangleLookup& triangle, Executor& executor,
                  std::vector<PairContact>& out_contacts, std::vector<ObjectPairContact>& out_totals) {
    constexpr std::size_t kChunk = 256;  // fixed: the sums' order does not depend on the threads
    struct Sum {
        std::uint32_t pairs = 0;
        double length = 0, area = 0;
        D3 normal;
    };
    const std::size_t n = pairs.size(), chunks = (n + kChunk - 1) / kChunk;
    out_contacts.resize(n);
    std::vector<std::map<std::uint64_t, Sum>> sums(chunks);
    executor.parallelFor(chunks, 1, [&](std::size_t first, std::size_t last) {
        for (std::size_t chunk = first; chunk < last; ++chunk) {
            std::map<std::uint64_t, Sum>& local = sums[chunk];
            for (std::size_t k = chunk * kChunk; k < std::min(n, (chunk + 1) * kChunk); ++k) {
                const TrianglePair& p = pairs[k];
                const PairContact c = pairContact(triangle(p.object_a, p.triangle_a), triangle(p.object_b, p.triangle_b));
                out_contacts[k] = c;
                Sum& s = local[(std::uint64_t{p.object_a} << 32) | p.object_b];
                ++s.pairs;
                if (c.shape == ContactShape::Segment) s.length += length(d3(c.end) - d3(c.start));
                s.area += c.area;
                s.normal = s.normal + d3(c.normal);
            }
        }
    });
    std::map<std::uint64_t, Sum> total;
    for (const auto& local : sums)
        for (const auto& [key, s] : local) {
            Sum& t = total[key];
            t.pairs += s.pairs;
            t.length += s.length;
            t.area += s.area;
            t.normal = t.normal + s.normal;
        }
    out_totals.clear();
    for (const auto& [key, s] : total)
        out_totals.push_back({static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key), s.pairs, static_cast<float>(s.length),
                              static_cast<float>(s.area), toFloat(unit(s.normal))});
}

}  // namespace vkcollide::contacts
