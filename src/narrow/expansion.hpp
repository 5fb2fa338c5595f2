// Exact floating-point expansion arithmetic (Shewchuk 1997), shared by the exact predicates
// (narrow/exact_predicates.cpp) and the exact contact points (contacts/exact_points.cpp).
// Internal: every caller must keep its operands in the range where the operations below are
// exact (no overflow, no error term below double's subnormal range); exact_predicates.cpp
// states that argument for float inputs.
#pragma once

#include <cassert>
#include <cmath>

namespace vkcollide::narrow::exact {

inline int signOf(double x) { return (x > 0) - (x < 0); }

// a + b = out_sum + out_err exactly (Knuth), unless the sum overflows.
inline void twoSum(double a, double b, double& out_sum, double& out_err) {
    const double x = a + b;
    const double b_virtual = x - a;
    const double a_virtual = x - b_virtual;
    out_err = (a - a_virtual) + (b - b_virtual);
    out_sum = x;
}

// a * b = out_product + out_err exactly, provided the error term is representable. std::fma
// is called explicitly, so this stays exact whatever -ffp-contract does.
inline void twoProduct(double a, double b, double& out_product, double& out_err) {
    const double x = a * b;
    out_err = std::fma(a, b, -x);
    out_product = x;
}

// A nonoverlapping expansion: the exact value is the sum of c[0..n), components ordered
// by increasing magnitude, zeros eliminated (n == 0 means the value zero). kCapacity must
// bound the component count: each add() of a double adds at most one, addScaled() two per
// component of the scaled expansion.
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

    // The same value in as few components as Shewchuk's COMPRESS gives (1997, Sec. 2.8):
    // afterwards the largest component is within about one ulp of the whole value, so it is
    // a good approximation (approximate() bounds its error without relying on that). Uses
    // twoSum where COMPRESS has the cheaper fast variant, so the value stays exact whatever
    // the components' order; sign() is only for expansions built by add() (take it first).
    void compress() {
        if (n < 2) return;
        double h[kCapacity];
        int bottom = n - 1;
        double q = c[bottom];
        for (int i = n - 2; i >= 0; --i) {
            double sum, err;
            twoSum(q, c[i], sum, err);
            if (err != 0) {
                h[bottom--] = sum;
                q = err;
            } else {
                q = sum;
            }
        }
        int top = 0;
        for (int i = bottom + 1; i < n; ++i) {
            double sum, err;
            twoSum(h[i], q, sum, err);
            if (err != 0) c[top++] = err;
            q = sum;
        }
        if (q != 0) c[top++] = q;
        n = top;
    }

    // The largest component, and in out_error a bound on |value - it|: the sum of the other
    // components' magnitudes, rounded up (the n - 1 additions round by at most n * 2^-53
    // relative; 2^-40 covers that for any capacity below 2^12).
    double approximate(double& out_error) const {
        if (n == 0) {
            out_error = 0;
            return 0;
        }
        double rest = 0;
        for (int i = 0; i < n - 1; ++i) rest += std::fabs(c[i]);
        out_error = rest * (1 + 0x1p-40);
        return c[n - 1];
    }
};

// u.x * v.y - v.x * u.y for floats: an exact two-component expansion (the float products
// are exact in double).
inline Expansion<2> minorXY(double ux, double uy, double vx, double vy) {
    Expansion<2> e;
    double diff, err;
    twoSum(ux * vy, -(vx * uy), diff, err);
    if (err != 0) e.c[e.n++] = err;
    if (diff != 0) e.c[e.n++] = diff;
    return e;
}

// p * q - r * s, exactly (a four-component expansion).
inline Expansion<4> differenceOfProducts(double p, double q, double r, double s) {
    double pq, pq_err, rs, rs_err;
    twoProduct(p, q, pq, pq_err);
    twoProduct(r, s, rs, rs_err);
    Expansion<4> e;
    if (pq_err == 0 && rs_err == 0) {
        // Both products exact (coordinates with few significant bits, as on a grid): one
        // exact subtraction, as minorXY does, instead of four expansion steps.
        double diff, err;
        twoSum(pq, -rs, diff, err);
        if (err != 0) e.c[e.n++] = err;
        if (diff != 0) e.c[e.n++] = diff;
        return e;
    }
    e.add(pq_err);
    e.add(pq);
    e.add(-rs_err);
    e.add(-rs);
    return e;
}

}  // namespace vkcollide::narrow::exact
