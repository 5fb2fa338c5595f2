// Exact orientation predicates for float coordinates.
//
// Each predicate first evaluates the determinant in double with Shewchuk's static error
// bound (a filter that is right whenever it answers) and only falls back to exact
// expansion arithmetic when the filter cannot decide. For float inputs the fallback is
// exact for every finite input: see exact_predicates.cpp for the argument.
#pragma once

#include "narrow/expansion.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide::narrow {

struct Float2 {
    float x = 0, y = 0;
};

// Sign of det[b - a, c - a, d - a]: +1 when d lies on the side of the plane through
// a, b, c that (b - a) x (c - a) points to, -1 on the other side, 0 when the four
// points are coplanar (or a, b, c are collinear). Exact for all finite floats.
int orient3d(const Float3& a, const Float3& b, const Float3& c, const Float3& d) noexcept;

// Sign of det[b - a, c - a]: +1 when a, b, c turn counter-clockwise, -1 clockwise,
// 0 collinear. Exact for all finite floats.
int orient2d(const Float2& a, const Float2& b, const Float2& c) noexcept;

// orient3d(a, b, c, d) for many d against one plane: the filter's products for a, b, c
// are computed once, and so, on the first d the filter cannot decide, is the exact cross
// product (b - a) x (c - a) (three coplanar vertices of a tilted contact cost one cross
// product instead of three). side(d) returns exactly orient3d(a, b, c, d). Not thread-safe
// (side() fills the cache): one object per thread.
class PlaneOrientation {
public:
    PlaneOrientation(const Float3& a, const Float3& b, const Float3& c) noexcept;
    int side(const Float3& d) const noexcept;
    // True when the filter alone proves a, b, c not collinear (some component of
    // (b - a) x (c - a) is certainly non-zero); false means "maybe collinear".
    bool certainlyNotCollinear() const noexcept;

private:
    int sideExact(const Float3& d) const noexcept;

    Float3 a_, b_, c_;
    double normal_[3];     // (b - a) x (c - a), rounded
    double magnitude_[3];  // per component, the sum of the two products' magnitudes
    // The exact cross product: component k is the expansion cross_[k][0, cross_size_[k]),
    // valid when cross_state_ is kCrossReady; kCrossInexact when b - a or c - a does not
    // fit a double (then orient3dExact's general form runs).
    enum : unsigned char { kCrossUnknown, kCrossReady, kCrossInexact };
    mutable unsigned char cross_state_ = kCrossUnknown;
    mutable int cross_size_[3] = {};
    mutable double cross_[3][4] = {};
};

// The exact fallbacks alone (no filter), exposed so tests can check filter and
// fallback against each other.
int orient3dExact(const Float3& a, const Float3& b, const Float3& c, const Float3& d) noexcept;
int orient2dExact(const Float2& a, const Float2& b, const Float2& c) noexcept;

// The filters' double evaluations of the same determinants, with in out_error a bound on
// their absolute error (the bound whose excess decides orient3d's / orient2d's sign).
double orient3dEstimate(const Float3& a, const Float3& b, const Float3& c, const Float3& d, double& out_error) noexcept;
double orient2dEstimate(const Float2& a, const Float2& b, const Float2& c, double& out_error) noexcept;

// The exact determinants themselves (orient3d's det[b - a, c - a, d - a], orient2d's
// det[b - a, c - a]) as expansions, for constructions that divide by them
// (contacts/exact_points.cpp). out is overwritten. Exact for all finite floats, and every
// component is a multiple of 2^-447 (3D) / 2^-298 (2D) below 2^390 in magnitude.
void orient3dValue(const Float3& a, const Float3& b, const Float3& c, const Float3& d, exact::Expansion<64>& out) noexcept;
void orient2dValue(const Float2& a, const Float2& b, const Float2& c, exact::Expansion<8>& out) noexcept;

}  // namespace vkcollide::narrow
