// Brute-force geometry checks for the scene tests, in double.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "vkcollide/mesh.hpp"

namespace vkcollide::test {

using Vec3 = std::array<double, 3>;

inline Vec3 toVec(const Float3& p) { return {p.x, p.y, p.z}; }
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Does the segment p0-p1 cross the triangle's interior? Moller-Trumbore with a small
// margin so that touching at an edge or an end point does not count.
inline bool segmentCrossesTriangle(const Vec3& p0, const Vec3& p1, const Vec3& a, const Vec3& b, const Vec3& c,
                                   Vec3& out_point) {
    constexpr double kMargin = 1e-9;
    const Vec3 dir = sub(p1, p0);
    const Vec3 e1 = sub(b, a), e2 = sub(c, a);
    const Vec3 h = cross(dir, e2);
    const double det = dot(e1, h);
    if (std::fabs(det) < 1e-18) return false;  // parallel to the plane
    const double inv = 1.0 / det;
    const Vec3 s = sub(p0, a);
    const double u = dot(s, h) * inv;
    if (u <= kMargin || u >= 1.0 - kMargin) return false;
    const Vec3 q = cross(s, e1);
    const double v = dot(dir, q) * inv;
    if (v <= kMargin || u + v >= 1.0 - kMargin) return false;
    const double t = dot(e2, q) * inv;
    if (t <= kMargin || t >= 1.0 - kMargin) return false;
    out_point = {p0[0] + t * dir[0], p0[1] + t * dir[1], p0[2] + t * dir[2]};
    return true;
}

// Every point where an edge of the mesh crosses a triangle that shares no vertex with
// it: empty exactly when the surface does not pass through itself.
inline std::vector<Vec3> selfIntersectionPoints(const HostMesh& mesh) {
    struct Box {
        Vec3 lo, hi;
    };
    const auto boxOf = [](std::initializer_list<Vec3> points) {
        Box box{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
        for (const Vec3& p : points)
            for (int k = 0; k < 3; ++k) box.lo[k] = std::min(box.lo[k], p[k]), box.hi[k] = std::max(box.hi[k], p[k]);
        return box;
    };
    const std::size_t triangles = mesh.triangleCount();
    std::vector<Box> boxes;
    for (std::size_t t = 0; t < triangles; ++t)
        boxes.push_back(boxOf({toVec(mesh.positions[mesh.indices[3 * t]]), toVec(mesh.positions[mesh.indices[3 * t + 1]]),
                               toVec(mesh.positions[mesh.indices[3 * t + 2]])}));
    std::vector<Vec3> points;
    for (std::size_t e = 0; e < triangles; ++e) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i0 = mesh.indices[3 * e + k], i1 = mesh.indices[3 * e + (k + 1) % 3];
            if (i0 > i1) continue;  // each edge of a closed mesh once (the other use runs i1 -> i0)
            const Vec3 p0 = toVec(mesh.positions[i0]), p1 = toVec(mesh.positions[i1]);
            const Box edge_box = boxOf({p0, p1});
            for (std::size_t t = 0; t < triangles; ++t) {
                const std::uint32_t* tri = &mesh.indices[3 * t];
                if (tri[0] == i0 || tri[1] == i0 || tri[2] == i0 || tri[0] == i1 || tri[1] == i1 || tri[2] == i1) continue;
                const Box& box = boxes[t];
                if (box.lo[0] > edge_box.hi[0] || box.hi[0] < edge_box.lo[0] || box.lo[1] > edge_box.hi[1] ||
                    box.hi[1] < edge_box.lo[1] || box.lo[2] > edge_box.hi[2] || box.hi[2] < edge_box.lo[2])
                    continue;
                Vec3 point;
                if (segmentCrossesTriangle(p0, p1, toVec(mesh.positions[tri[0]]), toVec(mesh.positions[tri[1]]),
                                           toVec(mesh.positions[tri[2]]), point))
                    points.push_back(point);
            }
        }
    }
    return points;
}

}  // namespace vkcollide::test
