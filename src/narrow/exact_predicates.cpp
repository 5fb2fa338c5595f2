#include "narrow/exact_predicates.hpp"

#include <cassert>
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

inline void twoSum(double a, double b, double& out_sum, double& out_err) {
    const double x = a + b;
    const double b_virtual = x - a;
    const double a_virtual = x - b_virtual;
    out_err = (a - a_virtual) + (b - b_virtual);
    out_sum = x;
}

inline void twoProduct(double a, double b, double& out_product, double& out_err) {
    const double x = a * b;
    out_err = std::fma(a, b, -x);
    out_product = x;
}

// A nonoverlapping expansion: the exact value is the sum of c[0..n), components ordered
// by increasing magnitude, zeros eliminated (n == 0 means the value zero).
template <int kCapacity>
struct Expansion {
    double c[kCapacity];
    int n = 0;

    // this += b (Shewchuk's GROW-EXPANSION with zero elimination).
    void add(double b) {
        double q = b;
        int out = 0;
        for (int i = 0; i < n; ++i) {
            double sum, err;
            twoSum(q, c[i], sum, err);
            q = sum;
            if (err != 0) c[out++] = err;
        }
        if (q != 0) {
            assert(out < kCapacity);
            c[out++] = q;
        }
        n = out;
    }

    template <int kOther>
    void add(const Expansion<kOther>& e, double sign = 1.0) {
        for (int i = 0; i < e.n; ++i) add(sign * e.c[i]);
    }

    // this += e * b (Shewchuk's SCALE-EXPANSION, each partial product added exactly).
    template <int kOther>
    void addScaled(const Expansion<kOther>& e, double b) {
        for (int i = 0; i < e.n; ++i) {
            double product, err;
            twoProduct(e.c[i], b, product, err);
            add(err);
            add(product);
        }
    }

    int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
};

// u.x * v.y - v.x * u.y as an exact two-component expansion (the float products are exact).
inline Expansion<2> minorXY(double ux, double uy, double vx, double vy) {
    Expansion<2> e;
    double diff, err;
    twoSum(ux * vy, -(vx * uy), diff, err);
    if (err != 0) e.c[e.n++] = err;
    if (diff != 0) e.c[e.n++] = diff;
    return e;
}

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

inline int signOf(double x) { return (x > 0) - (x < 0); }

}  // namespace

int orient3dExact(const Float3& a, const Float3& b, const Float3& c, const Float3& d) noexcept {
    // det[b-a, c-a, d-a] = -det4[(a,1);(b,1);(c,1);(d,1)]
    //                    = det3(b,c,d) - det3(a,c,d) + det3(a,b,d) - det3(a,b,c).
    // Working on the raw coordinates (not differences) keeps every product a product of
    // floats, which is exact in double.
    const Expansion<2> ab = minorXY(a, b), ac = minorXY(a, c), ad = minorXY(a, d);
    const Expansion<2> bc = minorXY(b, c), bd = minorXY(b, d), cd = minorXY(c, d);
    Expansion<64> det;
    det.add(det3(b, c, d, cd, bd, bc));
    det.add(det3(a, c, d, cd, ad, ac), -1.0);
    det.add(det3(a, b, d, bd, ad, ab));
    det.add(det3(a, b, c, bc, ac, ab), -1.0);
    return det.sign();
}

int orient2dExact(const Float2& a, const Float2& b, const Float2& c) noexcept {
    // det[b-a, c-a] = M(a,b) + M(b,c) + M(c,a).
    Expansion<8> det;
    det.add(minorXY(a.x, a.y, b.x, b.y));
    det.add(minorXY(b.x, b.y, c.x, c.y));
    det.add(minorXY(c.x, c.y, a.x, a.y));
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
    return orient3dExact(a, b, c, d);
}

int orient2d(const Float2& a, const Float2& b, const Float2& c) noexcept {
    const double left = (double(b.x) - a.x) * (double(c.y) - a.y);
    const double right = (double(b.y) - a.y) * (double(c.x) - a.x);
    const double det = left - right;
    const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
    if (det > bound || -det > bound) return signOf(det);
    return orient2dExact(a, b, c);
}

}  // namespace vkcollide::narrow
