#include "contacts/pair_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "narrow/exact_predicates.hpp"

// How (docs/contacts.md, "Where two triangles meet"): the exact orientation signs of each
// triangle's vertices against the other's plane decide the case, as in the exact test;
// coordinates are computed in double and rounded once to float.
//   Crossing planes: each triangle's cut by the other's plane (its vertices in that plane,
//     and the points where its edges change side, interpolated) is a segment of the planes'
//     common line; the contact is where the two cuts overlap along that line.
//   One plane: triangle a clipped by b's edges (Sutherland-Hodgman in the plane's two
//     dominant axes, points kept in 3D): an area (Coplanar), a segment or a point.
//   A zero-area triangle (a segment or a point) has no plane of its own: its cut by the
//     other's plane, or, when it lies in that plane, its clip by the other triangle.

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
bool isZero(const D3& a) { return a.x == 0 && a.y == 0 && a.z == 0; }
D3 unit(const D3& a) {
    const double l = length(a);
    return l > 0 && std::isfinite(l) ? (1 / l) * a : D3{};
}
Float3 toFloat(const D3& a) { return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)}; }

// The points of triangle t in the plane through p0 with normal n: its vertices with sign 0,
// and where an edge goes from one side to the other (signs exact, positions interpolated).
int planeCut(const D3 (&t)[3], const int (&sign)[3], const D3& p0, const D3& n, D3 (&out)[6]) {
    int count = 0;
    double dist[3];
    for (int i = 0; i < 3; ++i) dist[i] = dot(n, t[i] - p0);
    for (int i = 0; i < 3; ++i) {
        if (sign[i] == 0) out[count++] = t[i];
        const int j = (i + 1) % 3;
        if (sign[i] * sign[j] < 0) {
            const double denominator = dist[i] - dist[j];
            double s = denominator != 0 ? dist[i] / denominator : 0.5;
            s = std::clamp(std::isfinite(s) ? s : 0.5, 0.0, 1.0);
            out[count++] = t[i] + s * (t[j] - t[i]);
        }
    }
    return count;
}

// The two points of `points` farthest apart (the first point twice for one point).
std::pair<D3, D3> diameter(const D3* points, int count) {
    std::pair<D3, D3> best{points[0], points[0]};
    double far = -1;
    for (int i = 0; i < count; ++i)
        for (int j = i + 1; j < count; ++j)
            if (const D3 d = points[j] - points[i]; dot(d, d) > far) {
                far = dot(d, d);
                best = {points[i], points[j]};
            }
    return best;
}

// The contact of a point set on one line or in one plane: Segment/Point from its extremes.
PairContact fromPoints(const D3* points, int count, const D3& normal) {
    PairContact c;
    c.normal = toFloat(normal);
    if (count == 0) return c;
    const auto [s, e] = diameter(points, count);
    c.start = toFloat(s);
    c.end = toFloat(e);
    c.shape = c.start.x == c.end.x && c.start.y == c.end.y && c.start.z == c.end.z ? ContactShape::Point : ContactShape::Segment;
    return c;
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
    int sa[3], sb[3];
    for (int i = 0; i < 3; ++i) {
        sa[i] = narrow::orient3d(b[0], b[1], b[2], a[i]);
        sb[i] = narrow::orient3d(a[0], a[1], a[2], b[i]);
    }
    const bool a_flat = isZero(na), b_flat = isZero(nb);
    const bool a_in_b = !b_flat && sa[0] == 0 && sa[1] == 0 && sa[2] == 0;
    const bool b_in_a = !a_flat && sb[0] == 0 && sb[1] == 0 && sb[2] == 0;
    if (a_flat && b_flat) {  // two segments or points: where they are closest to each other's centroid
        const D3 mid = (1.0 / 6) * (A[0] + A[1] + A[2] + B[0] + B[1] + B[2]);
        PairContact c;
        c.start = c.end = toFloat(mid);
        return c;
    }
    if (a_in_b || b_in_a) {
        // One plane: clip the other (or the flat one) by a triangle with an area.
        const bool clip_by_b = !b_flat;
        const D3(&clipper)[3] = clip_by_b ? B : A;
        const D3(&subject)[3] = clip_by_b ? A : B;
        D3 polygon[12];
        const int count = clipInPlane(subject, 3, clipper, clip_by_b ? nb : na, polygon);
        if (count == 0) return fromPoints(clip_by_b ? A : B, 0, normal);  // rounding lost a touching point
        const double area = a_flat || b_flat ? 0 : polygonArea(polygon, count);
        PairContact c = fromPoints(polygon, count, normal);
        if (area > 0 && c.shape == ContactShape::Segment) {
            c.shape = ContactShape::Coplanar;
            c.area = static_cast<float>(area);
        }
        return c;
    }
    D3 cut_a[6], cut_b[6];
    const int na_count = b_flat ? 0 : planeCut(A, sa, B[0], nb, cut_a);
    const int nb_count = a_flat ? 0 : planeCut(B, sb, A[0], na, cut_b);
    if (a_flat) return fromPoints(cut_a, na_count, normal);  // a's segment meets b's plane in a point
    if (b_flat) return fromPoints(cut_b, nb_count, normal);
    // Both cuts lie on the planes' common line: their overlap along it.
    const D3 line = cross(na, nb);
    const auto extent = [&](const D3* points, int count) {
        std::pair<int, int> ends{0, 0};
        for (int i = 1; i < count; ++i) {
            if (dot(points[i], line) < dot(points[ends.first], line)) ends.first = i;
            if (dot(points[i], line) > dot(points[ends.second], line)) ends.second = i;
        }
        return ends;
    };
    if (na_count == 0 || nb_count == 0) return fromPoints(na_count ? cut_a : cut_b, std::max(na_count, nb_count), normal);
    const auto [a_lo, a_hi] = extent(cut_a, na_count);
    const auto [b_lo, b_hi] = extent(cut_b, nb_count);
    const D3 lo = dot(cut_a[a_lo], line) >= dot(cut_b[b_lo], line) ? cut_a[a_lo] : cut_b[b_lo];
    const D3 hi = dot(cut_a[a_hi], line) <= dot(cut_b[b_hi], line) ? cut_a[a_hi] : cut_b[b_hi];
    D3 ends[2] = {lo, hi};
    if (dot(hi, line) < dot(lo, line)) ends[0] = ends[1] = 0.5 * (lo + hi);  // touching, rounding crossed the ends
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
