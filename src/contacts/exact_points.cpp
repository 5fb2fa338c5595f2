#include "contacts/exact_points.hpp"

#include <bit>
#include <cmath>
#include <limits>

#include "narrow/exact_predicates.hpp"

// Why the points are exact
// ------------------------
// An edge p..q crossing a plane: with D_p, D_q the exact orientation determinants of p and q
// against it (orient3d's value; opposite signs), the crossing is
//     x = (D_p * q - D_q * p) / (D_p - D_q),
// so every coordinate is a quotient of two expansions built from exact operations: D is a
// sum of products of floats (every component a multiple of 2^-447 below 2^390, see
// exact_predicates.cpp), numerator components are those times a float (multiples of 2^-596,
// below 2^520). A coplanar edge crossing a line is the same with orient2d's value in the
// two coordinates that keep the plane's projection regular; the third coordinate follows
// the same parameter, so the point lies in the plane and on both edges.
//
// Rounding N / D correctly: a double approximation n, d of each with bounds e_n, e_d on the
// absolute errors gives
//     |N/D - n/d| <= (e_n + |n/d| e_d) / (|d| - e_d),
// plus 2^-53 |q| for the division q = fl(n/d); the bound is scaled by 1 + 2^-40 (its own
// few roundings) and padded by 2^-600 (underflow in its terms; every float midpoint is a
// multiple of 2^-150). f = float(q) is the answer when [q - bound, q + bound] lies strictly
// between the midpoints of f and its two float neighbours: checked as float(q - bound) ==
// float(q + bound) == f, rounding being monotonic (2^-52 |q| more covers q -+ bound's own
// rounding).
//  * First n, d come from the filters' double determinants and their error bounds
//    (orient3dEstimate: Shewchuk's), with the products' and differences' roundings added.
//  * When that cannot decide, from the exact expansions, compressed: n, d are their largest
//    components, e_n, e_d the sums of the other components' magnitudes.
//  * When q is still within the bound of a midpoint m (about 2^-50 relative: rare), the side
//    of m is decided exactly by the sign of N - m D (m has at most 25 significant bits, so m
//    times a component is exact), and f steps to the neighbour while the exact value lies
//    beyond, ties going to the even one.
// Constructed points lie between input floats, so nothing here overflows float; subnormal
// results are handled like any other (their midpoints are multiples of 2^-150).

namespace vkcollide::contacts {
namespace {

using narrow::exact::Expansion;

constexpr double kInf = std::numeric_limits<double>::infinity();

bool isEven(float f) { return (std::bit_cast<std::uint32_t>(f) & 1u) == 0; }

// The midpoint of f and its float neighbour toward `toward` (+-infinity), exact in double;
// infinite beyond the largest float.
double midpoint(float f, double toward) {
    const float g = std::nextafter(f, static_cast<float>(toward));
    return std::isinf(g) ? toward : 0.5 * (double(f) + double(g));
}

// float(n / d) when that is certainly the correct rounding of N / D, given |N - n| <= error_n
// and |D - d| <= error_d (the bound above); false when too close to a midpoint to tell.
bool clearRounding(double n, double error_n, double d, double error_d, float& out) {
    const double q = n / d;
    constexpr float kMax = std::numeric_limits<float>::max();
    const float f = std::fabs(q) > kMax ? std::copysign(kMax, static_cast<float>(q)) : static_cast<float>(q);
    out = f;  // the exact steps' start when this cannot decide
    if (!(std::fabs(d) > error_d)) return false;
    // The bound, plus 2^-52 |q| for rounding q -+ bound themselves: the real interval lies
    // within [lo, hi], and rounding is monotonic, so when both ends round to f, so does N/D.
    const double bound = ((error_n + std::fabs(q) * error_d) / (std::fabs(d) - error_d) + std::fabs(q) * 0x1p-53) * (1 + 0x1p-40) +
                         std::fabs(q) * 0x1p-52 + 0x1p-600;
    return static_cast<float>(q - bound) == f && static_cast<float>(q + bound) == f;
}

// The crossing from the filters' double determinants d_p, d_q (errors e_p, e_q), when every
// coordinate's rounding is clear from them: the usual case, with no expansion built.
bool crossingFromEstimates(const Float3& p, const Float3& q, double d_p, double e_p, double d_q, double e_q, Float3& out) {
    if (!(std::fabs(d_p) > e_p && std::fabs(d_q) > e_q)) return false;
    const double denominator = d_p - d_q;
    // D_p - D_q: the two errors, and the subtraction's rounding.
    const double error_d = (e_p + e_q + std::fabs(denominator) * 0x1p-52) * (1 + 0x1p-40);
    const float pc[3] = {p.x, p.y, p.z}, qc[3] = {q.x, q.y, q.z};
    float result[3];
    for (int k = 0; k < 3; ++k) {
        if (pc[k] == qc[k]) {
            result[k] = pc[k];
            continue;
        }
        const double left = d_p * qc[k], right = d_q * pc[k];
        // The determinants' errors times the coordinates, plus two products and a difference
        // each rounded by at most 2^-53 of |left| + |right|.
        const double error_n =
            (e_p * std::fabs(qc[k]) + e_q * std::fabs(pc[k]) + (std::fabs(left) + std::fabs(right)) * 0x1p-51) * (1 + 0x1p-40) + 0x1p-600;
        if (!clearRounding(left - right, error_n, denominator, error_d, result[k])) return false;
    }
    out = {result[0], result[1], result[2]};
    return true;
}

// sign(N / D - m), exactly.
int compareQuotient(const Expansion<256>& numerator, const Expansion<128>& denominator, int denominator_sign, double m) {
    if (std::isinf(m)) return m > 0 ? -1 : 1;
    Expansion<512> difference;
    difference.add(numerator);
    difference.addScaled(denominator, -m);
    return difference.sign() * denominator_sign;
}

template <int kCapacity>
Float3 crossing(const Float3& p, const Float3& q, Expansion<kCapacity>& d_p, Expansion<kCapacity>& d_q) {
    static_assert(2 * kCapacity <= 128);
    // Compressed first (same values): the determinants usually shrink to a component or
    // two, and every product and sum below grows with their lengths.
    d_p.compress();
    d_q.compress();
    Expansion<128> denominator;
    denominator.add(d_p);
    denominator.add(d_q, -1.0);
    const int denominator_sign = denominator.sign();
    const float pc[3] = {p.x, p.y, p.z}, qc[3] = {q.x, q.y, q.z};
    float out[3];
    for (int k = 0; k < 3; ++k) {
        if (pc[k] == qc[k]) {
            out[k] = pc[k];  // the edge keeps this coordinate: exact as it is
            continue;
        }
        Expansion<256> numerator;
        numerator.addScaled(d_p, qc[k]);
        numerator.addScaled(d_q, -pc[k]);
        out[k] = roundQuotient(numerator, denominator, denominator_sign);
    }
    return {out[0], out[1], out[2]};
}

narrow::Float2 drop(const Float3& p, int axis) {
    return axis == 0 ? narrow::Float2{p.y, p.z} : (axis == 1 ? narrow::Float2{p.x, p.z} : narrow::Float2{p.x, p.y});
}

}  // namespace

float roundQuotient(Expansion<256>& io_numerator, Expansion<128>& io_denominator, int denominator_sign) noexcept {
    io_numerator.compress();
    io_denominator.compress();
    double error_n, error_d;
    const double n = io_numerator.approximate(error_n), d = io_denominator.approximate(error_d);
    float f;
    if (clearRounding(n, error_n, d, error_d, f)) return f;
    // Too close to a midpoint (or d too rough, never after compress): step exactly from f.
    for (;;) {
        const int above = compareQuotient(io_numerator, io_denominator, denominator_sign, midpoint(f, kInf));
        if (above > 0 || (above == 0 && !isEven(f))) {
            f = std::nextafter(f, std::numeric_limits<float>::infinity());
            continue;
        }
        const int below = compareQuotient(io_numerator, io_denominator, denominator_sign, midpoint(f, -kInf));
        if (below < 0 || (below == 0 && !isEven(f))) {
            f = std::nextafter(f, -std::numeric_limits<float>::infinity());
            continue;
        }
        return f;
    }
}

Float3 roundPlaneCrossing(const Float3& p, const Float3& q, const std::array<Float3, 3>& plane, double d_p, double e_p, double d_q,
                          double e_q) noexcept {
    Float3 out;
    if (crossingFromEstimates(p, q, d_p, e_p, d_q, e_q, out)) return out;
    Expansion<64> exact_p, exact_q;
    narrow::orient3dValue(plane[0], plane[1], plane[2], p, exact_p);
    narrow::orient3dValue(plane[0], plane[1], plane[2], q, exact_q);
    return crossing(p, q, exact_p, exact_q);
}

Float3 roundExact(const ExactPoint& point) noexcept {
    switch (point.kind) {
        case ExactPoint::Kind::Vertex: return point.p;
        case ExactPoint::Kind::PlaneCrossing: {
            double e_p, e_q;
            const double d_p = narrow::orient3dEstimate(point.a, point.b, point.c, point.p, e_p);
            const double d_q = narrow::orient3dEstimate(point.a, point.b, point.c, point.q, e_q);
            return roundPlaneCrossing(point.p, point.q, {point.a, point.b, point.c}, d_p, e_p, d_q, e_q);
        }
        case ExactPoint::Kind::LineCrossing: {
            const narrow::Float2 a = drop(point.a, point.drop), b = drop(point.b, point.drop);
            const narrow::Float2 p = drop(point.p, point.drop), q = drop(point.q, point.drop);
            Float3 out;
            double e_p, e_q;
            const double d_p = narrow::orient2dEstimate(a, b, p, e_p), d_q = narrow::orient2dEstimate(a, b, q, e_q);
            if (crossingFromEstimates(point.p, point.q, d_p, e_p, d_q, e_q, out)) return out;
            Expansion<8> exact_p, exact_q;
            narrow::orient2dValue(a, b, p, exact_p);
            narrow::orient2dValue(a, b, q, exact_q);
            return crossing(point.p, point.q, exact_p, exact_q);
        }
    }
    return point.p;
}

}  // namespace vkcollide::contacts
