// Big-integer orientation signs (support/big_orient.hpp).
#include "support/big_orient.hpp"

#include <array>
#include <cmath>
#include <cstdint>

namespace vkcollide::test {
namespace {

// A 1024-bit two's-complement integer, enough for det of float differences scaled to
// integers (each float is a multiple of 2^-149 below 2^128: 277 bits; the 3x3 product
// of differences needs about 837). Arithmetic is modulo 2^1024, exact while in range.
struct BigInt {
    static constexpr int kLimbs = 32;
    std::array<std::uint32_t, kLimbs> limb{};

    static BigInt fromFloat(float f) {
        BigInt r;
        if (f == 0) return r;
        int exponent = 0;
        const double fraction = std::frexp(static_cast<double>(std::fabs(f)), &exponent);
        auto mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 24));  // exact: 24 bits
        int shift = exponent - 24 + 149;  // value * 2^149 = mantissa * 2^shift
        while (shift < 0) {
            mantissa >>= 1;  // only trailing zeros for subnormals
            ++shift;
        }
        r.limb[static_cast<std::size_t>(shift / 32)] = static_cast<std::uint32_t>(mantissa << (shift % 32));
        const std::uint64_t high = (mantissa << (shift % 32)) >> 32;
        r.limb[static_cast<std::size_t>(shift / 32 + 1)] = static_cast<std::uint32_t>(high);
        return f < 0 ? -r : r;
    }

    friend BigInt operator+(const BigInt& a, const BigInt& b) {
        BigInt r;
        std::uint64_t carry = 0;
        for (int i = 0; i < kLimbs; ++i) {
            const std::uint64_t s = std::uint64_t(a.limb[i]) + b.limb[i] + carry;
            r.limb[i] = static_cast<std::uint32_t>(s);
            carry = s >> 32;
        }
        return r;
    }
    BigInt operator-() const {
        BigInt r;
        for (int i = 0; i < kLimbs; ++i) r.limb[i] = ~limb[i];
        BigInt one;
        one.limb[0] = 1;
        return r + one;
    }
    friend BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }
    friend BigInt operator*(const BigInt& a, const BigInt& b) {
        BigInt r;
        for (int i = 0; i < kLimbs; ++i) {
            if (a.limb[i] == 0) continue;
            std::uint64_t carry = 0;
            for (int j = 0; i + j < kLimbs; ++j) {
                const std::uint64_t t = std::uint64_t(a.limb[i]) * b.limb[j] + r.limb[i + j] + carry;
                r.limb[i + j] = static_cast<std::uint32_t>(t);
                carry = t >> 32;
            }
        }
        return r;
    }
    int sign() const {
        if (limb[kLimbs - 1] >> 31) return -1;
        for (std::uint32_t l : limb) {
            if (l) return 1;
        }
        return 0;
    }
};

}  // namespace

int bigOrient3d(const Float3& a, const Float3& b, const Float3& c, const Float3& d) {
    const auto B = [](float f) { return BigInt::fromFloat(f); };
    const BigInt bax = B(b.x) - B(a.x), bay = B(b.y) - B(a.y), baz = B(b.z) - B(a.z);
    const BigInt cax = B(c.x) - B(a.x), cay = B(c.y) - B(a.y), caz = B(c.z) - B(a.z);
    const BigInt dax = B(d.x) - B(a.x), day = B(d.y) - B(a.y), daz = B(d.z) - B(a.z);
    return (bax * (cay * daz - caz * day) + bay * (caz * dax - cax * daz) + baz * (cax * day - cay * dax)).sign();
}

int bigOrient2d(const narrow::Float2& a, const narrow::Float2& b, const narrow::Float2& c) {
    const auto B = [](float f) { return BigInt::fromFloat(f); };
    return ((B(b.x) - B(a.x)) * (B(c.y) - B(a.y)) - (B(b.y) - B(a.y)) * (B(c.x) - B(a.x))).sign();
}

}  // namespace vkcollide::test
