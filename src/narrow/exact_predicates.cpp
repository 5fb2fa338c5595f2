#include "narrow/exact_predicates.hpp"

#include "narrow/expansion.hpp"

#include <algorithm>
#include <array>
#include <cmath>

// Why these predicates are exact for float inputs
// -----------------------------------------------
// Every finite float is an integer multiple of 2^-149 with magnitude below 2^128.
//  * The product of two floats has at most 24 + 24 = 48 significant bits, so it is
//    exact in a double (53 bits); its magnitude lies in [2^-298, 2^256] or is zero,
//    far from double underflow (2^-1022) and overflow (2^1024).
//  * twoSum/twoDiff of doubles is exact (Knuth) whenever the sum does not overflow.
//  * twoProduct uses std::fma: x = fl(a*b), y = fma(a, b, -x) = a*b - x exactly,
//    provided the error term is representable. All operands we multiply are multiples
//    of 2^-298 (exact float products and their twoSum errors) times a float (a multiple
//    of 2^-149), so every product and error term is a multiple of 2^-447: no underflow.
//    Magnitudes stay below 2^390: no overflow.
//  * Expansion sums (grow-expansion, Shewchuk 1997, Thm. 10) built from those exact
//    operations keep the value exact; the sign of a zero-free nonoverlapping expansion is
//    the sign of its largest component.
// The fast paths use Shewchuk's "A" error bounds for orient2d/orient3d on double
// inputs; floats are doubles, and by the same magnitude argument nothing underflows.
// std::fma is called explicitly, so the exact path is immune to floating-point
// contraction (-ffp-contract); the filters only get tighter if the compiler fuses.

namespace vkcollide::narrow {
namespace {

constexpr double kEpsilon = 0x1p-53;  // half an ulp of 1.0: the unit roundoff
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

using exact::differenceOfProducts;
using exact::Expansion;
using exact::minorXY;
using exact::signOf;
using exact::twoProduct;
using exact::twoSum;

inline Expansion<2> minorXY(const Float3& u, const Float3& v) { return minorXY(u.x, u.y, v.x, v.y); }

// det[p; q; r] (rows), expanded along z: pz*M(q,r) - qz*M(p,r) + rz*M(p,q).
inline Expansion<16> det3(const Float3& p, const Float3& q, const Float3& r, const Expansion<2>& m_qr,
                          const Expansion<2>& m_pr, const Expansion<2>& m_pq) {
    Expansion<16> e;
    e.addScaled(m_qr, p.z);
    e.addScaled(m_pr, -static_cast<double>(q.z));
    e.addScaled(m_pq, r.z);
    return e;
}

// zeroFactors: the filters' free exact answer for contacts along axis-aligned planes and
// lines (boxes resting on boxes: every test of such a pair would otherwise take the exact
// path). With float inputs a rounded difference is 0 only when the two floats are equal
// (x - y rounds to 0 only for x == y), a nonzero one is at least 2^-149 in magnitude, so a
// product of two or three of them is at least 2^-447 and never rounds to 0 in double. So a
// product term that rounds to 0 has an exact zero factor and is exactly 0; when the
// filter's permanent (the sum of the terms' magnitudes) is 0, so is the exact determinant.


// The nine differences b - a, c - a, d - a, rounded to double; true when all are exact,
// which is the rule for float inputs (a float difference fits a double unless the two
// exponents are more than 29 apart).
bool exactDifferences(const Float3& a, const Float3& b, const Float3& c, const Float3& d, double (&out)[9]) {
    const Float3* const points[3] = {&b, &c, &d};
    bool exact = true;
    for (int k = 0; k < 3; ++k) {
        const double coords[3][2] = {{points[k]->x, a.x}, {points[k]->y, a.y}, {points[k]->z, a.z}};
        for (int axis = 0; axis < 3; ++axis) {
            double err;
            twoSum(coords[axis][0], -coords[axis][1], out[3 * k + axis], err);
            exact = exact && err == 0;
        }
    }
    return exact;
}

// u x v on exact differences, each component an exact expansion of at most 4 terms.
std::array<Expansion<4>, 3> exactCross(const double (&diff)[9]) {
    const double ux = diff[0], uy = diff[1], uz = diff[2], vx = diff[3], vy = diff[4], vz = diff[5];
    return {differenceOfProducts(uy, vz, uz, vy), differenceOfProducts(uz, vx, ux, vz), differenceOfProducts(ux, vy, uy, vx)};
}

// sign(w . n) for an exact cross product n and exact differences w. Products and their
// errors are multiples of 2^-447 and below 2^390 (same argument as above), so this stays
// exact; at most 24 components.
int crossDotSign(const std::array<Expansion<4>, 3>& n, double wx, double wy, double wz) {
    if (n[0].n <= 1 && n[1].n <= 1 && n[2].n <= 1) {
        // Each component a single double (a coplanar contact on a grid of few bits): when
        // the three products and two sums have no rounding error the double sum is the
        // exact determinant; otherwise the expansions below.
        double t[3], e[3];
        const double w[3] = {wx, wy, wz};
        for (int k = 0; k < 3; ++k) twoProduct(n[k].n == 0 ? 0.0 : n[k].c[0], w[k], t[k], e[k]);
        if (e[0] == 0 && e[1] == 0 && e[2] == 0) {
            double partial, partial_err, det, det_err;
            twoSum(t[0], t[1], partial, partial_err);
            twoSum(partial, t[2], det, det_err);
            if (partial_err == 0 && det_err == 0) return signOf(det);
        }
    }
    Expansion<24> det;
    det.addScaled(n[0], wx);
    det.addScaled(n[1], wy);
    det.addScaled(n[2], wz);
    return det.sign();
}

// det[b-a, c-a, d-a] = -det4[(a,1);(b,1);(c,1);(d,1)]
//                    = det3(b,c,d) - det3(a,c,d) + det3(a,b,d) - det3(a,b,c).
// Working on the raw coordinates (not differences) keeps every product a product of
// floats, which is exact in double. Adds to io_det (4 x 16 components at most).
void undifferencedOrient3d(const Float3& a, const Float3& b, const Float3& c, const Float3& d, Expansion<64>& io_det) {
    const Expansion<2> ab = minorXY(a, b), ac = minorXY(a, c), ad = minorXY(a, d);
    const Expansion<2> bc = minorXY(b, c), bd = minorXY(b, d), cd = minorXY(c, d);
    io_det.add(det3(b, c, d, cd, bd, bc));
    io_det.add(det3(a, c, d, cd, ad, ac), -1.0);
    io_det.add(det3(a, b, d, bd, ad, ab));
    io_det.add(det3(a, b, c, bc, ac, ab), -1.0);
}

// det[b-a, c-a] = M(a,b) + M(b,c) + M(c,a), on the raw coordinates; adds to io_det.
void undifferencedOrient2d(const Float2& a, const Float2& b, const Float2& c, Expansion<8>& io_det) {
    io_det.add(minorXY(a.x, a.y, b.x, b.y));
    io_det.add(minorXY(b.x, b.y, c.x, c.y));
    io_det.add(minorXY(c.x, c.y, a.x, a.y));
}

}  // namespace

int orient3dExact(const Float3& a, const Float3& b, const Float3& c, const Float3& d) noexcept {
    double diff[9];
    if (exactDifferences(a, b, c, d, diff)) {
        // The usual case: det[u, v, w] = w . (u x v) on the exact differences u = b - a,
        // v = c - a, w = d - a.
        return crossDotSign(exactCross(diff), diff[6], diff[7], diff[8]);
    }
    Expansion<64> det;
    undifferencedOrient3d(a, b, c, d, det);
    return det.sign();
}

void orient3dValue(const Float3& a, const Float3& b, const Float3& c, const Float3& d, exact::Expansion<64>& out) noexcept {
    out.n = 0;
    double diff[9];
    if (!exactDifferences(a, b, c, d, diff)) return undifferencedOrient3d(a, b, c, d, out);
    // w . (u x v) as orient3dExact's first form, kept as a value: 3 x 4 components, each
    // scaled into two.
    const std::array<Expansion<4>, 3> n = exactCross(diff);
    for (int k = 0; k < 3; ++k) out.addScaled(n[k], diff[6 + k]);
}

void orient2dValue(const Float2& a, const Float2& b, const Float2& c, exact::Expansion<8>& out) noexcept {
    out.n = 0;
    double bax, bay, cax, cay, e0, e1, e2, e3;
    twoSum(b.x, -double(a.x), bax, e0);
    twoSum(b.y, -double(a.y), bay, e1);
    twoSum(c.x, -double(a.x), cax, e2);
    twoSum(c.y, -double(a.y), cay, e3);
    if (e0 == 0 && e1 == 0 && e2 == 0 && e3 == 0) return out.add(differenceOfProducts(bax, cay, bay, cax));
    undifferencedOrient2d(a, b, c, out);
}

int orient2dExact(const Float2& a, const Float2& b, const Float2& c) noexcept {
    double bax, bay, cax, cay, e0, e1, e2, e3;
    twoSum(b.x, -double(a.x), bax, e0);
    twoSum(b.y, -double(a.y), bay, e1);
    twoSum(c.x, -double(a.x), cax, e2);
    twoSum(c.y, -double(a.y), cay, e3);
    if (e0 == 0 && e1 == 0 && e2 == 0 && e3 == 0) {
        // Exact differences; when both products are exact too, comparing them is the sign
        // (the collinear vertices of a grid's shared diagonals end here).
        double left, left_err, right, right_err;
        twoProduct(bax, cay, left, left_err);
        twoProduct(bay, cax, right, right_err);
        if (left_err == 0 && right_err == 0) return (left > right) - (left < right);
        return differenceOfProducts(bax, cay, bay, cax).sign();
    }
    Expansion<8> det;
    undifferencedOrient2d(a, b, c, det);
    return det.sign();
}

int orient3d(const Float3& a, const Float3& b, const Float3& c, const Float3& d) noexcept {
    const double bax = double(b.x) - a.x, bay = double(b.y) - a.y, baz = double(b.z) - a.z;
    const double cax = double(c.x) - a.x, cay = double(c.y) - a.y, caz = double(c.z) - a.z;
    const double dax = double(d.x) - a.x, day = double(d.y) - a.y, daz = double(d.z) - a.z;

    const double cay_daz = cay * daz, caz_day = caz * day;
    const double caz_dax = caz * dax, cax_daz = cax * daz;
    const double cax_day = cax * day, cay_dax = cay * dax;
    const double det = bax * (cay_daz - caz_day) + bay * (caz_dax - cax_daz) + baz * (cax_day - cay_dax);
    const double permanent = std::fabs(bax) * (std::fabs(cay_daz) + std::fabs(caz_day)) +
                             std::fabs(bay) * (std::fabs(caz_dax) + std::fabs(cax_daz)) +
                             std::fabs(baz) * (std::fabs(cax_day) + std::fabs(cay_dax));
    const double bound = kOrient3dBound * permanent;
    if (det > bound || -det > bound) return signOf(det);
    if (permanent == 0) return 0;  // every term has an exact zero factor (zeroFactors)
    return orient3dExact(a, b, c, d);
}

PlaneOrientation::PlaneOrientation(const Float3& a, const Float3& b, const Float3& c) noexcept : a_(a), b_(b), c_(c) {
    const double ux = double(b.x) - a.x, uy = double(b.y) - a.y, uz = double(b.z) - a.z;
    const double vx = double(c.x) - a.x, vy = double(c.y) - a.y, vz = double(c.z) - a.z;
    // n = u x v, each component exactly as orient2d evaluates the projected triangle.
    const double p[6] = {uy * vz, uz * vy, uz * vx, ux * vz, ux * vy, uy * vx};
    for (int k = 0; k < 3; ++k) {
        normal_[k] = p[2 * k] - p[2 * k + 1];
        magnitude_[k] = std::fabs(p[2 * k]) + std::fabs(p[2 * k + 1]);
    }
}

int PlaneOrientation::side(const Float3& d) const noexcept {
    // det[u, v, w] = w . (u x v): Shewchuk's orient3d filter expanded along w instead of
    // along the first row. The error analysis only uses the shape "rounded difference
    // times (difference of two products of rounded differences), summed", so the same
    // bound holds.
    const double wx = double(d.x) - a_.x, wy = double(d.y) - a_.y, wz = double(d.z) - a_.z;
    const double det = wx * normal_[0] + wy * normal_[1] + wz * normal_[2];
    const double permanent = std::fabs(wx) * magnitude_[0] + std::fabs(wy) * magnitude_[1] + std::fabs(wz) * magnitude_[2];
    const double bound = kOrient3dBound * permanent;
    if (det > bound || -det > bound) return signOf(det);
    if (permanent == 0) return 0;  // every term has an exact zero factor (zeroFactors)
    return sideExact(d);
}

int PlaneOrientation::sideExact(const Float3& d) const noexcept {
    // orient3dExact's first form, with u x v kept from the first call: the same exact
    // value, so the same sign. Its condition (all nine differences exact) is checked in
    // two parts: u and v once, w per call.
    double diff[9];
    if (cross_state_ == kCrossUnknown) {
        cross_state_ = exactDifferences(a_, b_, c_, c_, diff) ? kCrossReady : kCrossInexact;
        if (cross_state_ == kCrossReady) {
            const std::array<Expansion<4>, 3> n = exactCross(diff);
            for (int k = 0; k < 3; ++k) {
                cross_size_[k] = n[k].n;
                std::copy(n[k].c, n[k].c + n[k].n, cross_[k]);
            }
        }
    }
    if (cross_state_ == kCrossInexact) return orient3dExact(a_, b_, c_, d);
    double w[3], err[3];
    twoSum(d.x, -double(a_.x), w[0], err[0]);
    twoSum(d.y, -double(a_.y), w[1], err[1]);
    twoSum(d.z, -double(a_.z), w[2], err[2]);
    if (err[0] != 0 || err[1] != 0 || err[2] != 0) return orient3dExact(a_, b_, c_, d);
    std::array<Expansion<4>, 3> n;
    for (int k = 0; k < 3; ++k) {
        n[k].n = cross_size_[k];
        std::copy(cross_[k], cross_[k] + cross_size_[k], n[k].c);
    }
    return crossDotSign(n, w[0], w[1], w[2]);
}

bool PlaneOrientation::certainlyNotCollinear() const noexcept {
    for (int k = 0; k < 3; ++k) {
        const double bound = kOrient2dBound * magnitude_[k];
        if (normal_[k] > bound || -normal_[k] > bound) return true;
    }
    return false;
}

double orient3dEstimate(const Float3& a, const Float3& b, const Float3& c, const Float3& d, double& out_error) noexcept {
    // orient3d's filter, kept as a value: Shewchuk's bound is a bound on the absolute error
    // of this evaluation (rounded differences included), which is what the sign test uses.
    const double bax = double(b.x) - a.x, bay = double(b.y) - a.y, baz = double(b.z) - a.z;
    const double cax = double(c.x) - a.x, cay = double(c.y) - a.y, caz = double(c.z) - a.z;
    const double dax = double(d.x) - a.x, day = double(d.y) - a.y, daz = double(d.z) - a.z;
    const double cay_daz = cay * daz, caz_day = caz * day;
    const double caz_dax = caz * dax, cax_daz = cax * daz;
    const double cax_day = cax * day, cay_dax = cay * dax;
    const double permanent = std::fabs(bax) * (std::fabs(cay_daz) + std::fabs(caz_day)) +
                             std::fabs(bay) * (std::fabs(caz_dax) + std::fabs(cax_daz)) +
                             std::fabs(baz) * (std::fabs(cax_day) + std::fabs(cay_dax));
    out_error = kOrient3dBound * permanent;
    return bax * (cay_daz - caz_day) + bay * (caz_dax - cax_daz) + baz * (cax_day - cay_dax);
}

double orient2dEstimate(const Float2& a, const Float2& b, const Float2& c, double& out_error) noexcept {
    const double left = (double(b.x) - a.x) * (double(c.y) - a.y);
    const double right = (double(b.y) - a.y) * (double(c.x) - a.x);
    out_error = kOrient2dBound * (std::fabs(left) + std::fabs(right));
    return left - right;
}

int orient2d(const Float2& a, const Float2& b, const Float2& c) noexcept {
    const double left = (double(b.x) - a.x) * (double(c.y) - a.y);
    const double right = (double(b.y) - a.y) * (double(c.x) - a.x);
    const double det = left - right;
    const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
    if (det > bound || -det > bound) return signOf(det);
    if (left == 0 && right == 0) return 0;  // both products have an exact zero factor (zeroFactors)
    return orient2dExact(a, b, c);
}

}  // namespace vkcollide::narrow
