// Checks shared by the contact-geometry tests: how far a point is from a triangle.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "vkcollide/mesh.hpp"

namespace vkcollide::test {

// Distance from p to the closed triangle t (Ericson, Real-Time Collision Detection 5.1.5), in
// double; a zero-area triangle is handled as its longest edge.
inline double distanceToTriangle(const Float3& pf, const std::array<Float3, 3>& t) {
    struct V {
        double x, y, z;
    };
    const auto v = [](const Float3& f) { return V{f.x, f.y, f.z}; };
    const auto sub = [](V a, V b) { return V{a.x - b.x, a.y - b.y, a.z - b.z}; };
    const auto dot = [](V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    const auto len = [&](V a) { return std::sqrt(dot(a, a)); };
    const V p = v(pf), a = v(t[0]), b = v(t[1]), c = v(t[2]);
    const auto segment = [&](V s0, V s1) {
        const V d = sub(s1, s0);
        const double dd = dot(d, d);
        const double u = dd > 0 ? std::clamp(dot(sub(p, s0), d) / dd, 0.0, 1.0) : 0.0;
        return len(sub(p, V{s0.x + u * d.x, s0.y + u * d.y, s0.z + u * d.z}));
    };
    const V ab = sub(b, a), ac = sub(c, a);
    const V n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
    const double edges = std::min({segment(a, b), segment(b, c), segment(c, a)});
    const double nn = dot(n, n);
    if (!(nn > 0)) return edges;
    // Inside the prism over the triangle: the distance to the plane.
    const V ap = sub(p, a);
    const double s = dot(n, ap) / nn;
    const V q{p.x - s * n.x, p.y - s * n.y, p.z - s * n.z};
    const auto side = [&](V e0, V e1) {
        const V e = sub(e1, e0), w = sub(q, e0);
        const V x{e.y * w.z - e.z * w.y, e.z * w.x - e.x * w.z, e.x * w.y - e.y * w.x};
        return dot(x, n);
    };
    if (side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0) return std::fabs(s) * std::sqrt(nn);
    return edges;
}

}  // namespace vkcollide::test
