// Exact rational arithmetic for the contact-point tests: a small owner of GMP's mpq_t, the
// exact constructions the contacts round from, and round-to-nearest-even to float.
#pragma once

#include <gmp.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "vkcollide/mesh.hpp"

namespace vkcollide::test {

class Rational {
public:
    Rational() { mpq_init(v_); }
    Rational(double d) : Rational() { mpq_set_d(v_, d); }  // exact for every finite double
    Rational(const Rational& o) : Rational() { mpq_set(v_, o.v_); }
    Rational& operator=(const Rational& o) {
        mpq_set(v_, o.v_);
        return *this;
    }
    ~Rational() { mpq_clear(v_); }

    friend Rational operator+(const Rational& a, const Rational& b) { return apply(mpq_add, a, b); }
    friend Rational operator-(const Rational& a, const Rational& b) { return apply(mpq_sub, a, b); }
    friend Rational operator*(const Rational& a, const Rational& b) { return apply(mpq_mul, a, b); }
    friend Rational operator/(const Rational& a, const Rational& b) { return apply(mpq_div, a, b); }
    friend int compare(const Rational& a, const Rational& b) { return mpq_cmp(a.v_, b.v_); }
    friend bool operator==(const Rational& a, const Rational& b) { return mpq_equal(a.v_, b.v_) != 0; }
    int sign() const { return mpq_sgn(v_); }
    double approx() const { return mpq_get_d(v_); }

private:
    template <class Op>
    static Rational apply(Op op, const Rational& a, const Rational& b) {
        Rational r;
        op(r.v_, a.v_, b.v_);
        return r;
    }
    mpq_t v_;
};

struct R3 {
    Rational x, y, z;
    const Rational& operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
};
inline R3 r3(const Float3& p) { return {p.x, p.y, p.z}; }
inline R3 operator-(const R3& a, const R3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Rational dot(const R3& a, const R3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline R3 cross(const R3& a, const R3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline bool operator==(const R3& a, const R3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// det[b - a, c - a, d - a].
inline Rational orient(const R3& a, const R3& b, const R3& c, const R3& d) { return dot(d - a, cross(b - a, c - a)); }

// The point where segment p..q has side value sp (at p) and sq (at q) go through zero.
inline R3 crossingAt(const R3& p, const R3& q, const Rational& sp, const Rational& sq) {
    const Rational den = sp - sq;
    return {(sp * q.x - sq * p.x) / den, (sp * q.y - sq * p.y) / den, (sp * q.z - sq * p.z) / den};
}

// v rounded to the nearest float, ties to even: from a guess, stepped across the exact
// midpoints with the neighbours (exact doubles) while v lies beyond.
inline float roundToFloat(const Rational& v) {
    float f = static_cast<float>(v.approx());
    const auto even = [](float g) {
        std::uint32_t bits;
        std::memcpy(&bits, &g, 4);
        return (bits & 1u) == 0;
    };
    for (;;) {
        const float up = std::nextafter(f, INFINITY), down = std::nextafter(f, -INFINITY);
        const int above = compare(v, Rational(0.5 * (double(f) + double(up))));
        if (above > 0 || (above == 0 && !even(f))) {
            f = up;
            continue;
        }
        const int below = compare(v, Rational(0.5 * (double(f) + double(down))));
        if (below < 0 || (below == 0 && !even(f))) {
            f = down;
            continue;
        }
        return f;
    }
}
inline Float3 roundToFloat(const R3& p) { return {roundToFloat(p.x), roundToFloat(p.y), roundToFloat(p.z)}; }

}  // namespace vkcollide::test
