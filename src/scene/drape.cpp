// A cloth draped over a sphere, without a simulator: the flat cloth is mapped by arc
// length onto the sphere cap and the cone tangent to it, folds are waves around the hanging
// part, and the flap is a fold made in the flat cloth before draping (so it follows the
// drape) whose height above the cloth rises and then falls below zero: it passes through.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

using Vec = std::array<double, 3>;

Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec scale(const Vec& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

struct Drape {
    const DrapeOptions& o;

    // The cloth point at flat coordinates (u, v), lifted `w` along the cloth's normal.
    Vec surface(double u, double v) const {
        const double r = std::hypot(u, v);
        const double alpha = std::atan2(v, u);
        const double ca = std::cos(alpha), sa = std::sin(alpha);
        const double rest = double{o.radius} + o.gap;
        const double phi_c = o.contact_angle;
        const double phi = r / rest;
        if (phi <= phi_c) return {rest * std::sin(phi) * ca, rest * std::sin(phi) * sa, rest * std::cos(phi)};
        const double hang = r - rest * phi_c;
        const Vec contact = {rest * std::sin(phi_c) * ca, rest * std::sin(phi_c) * sa, rest * std::cos(phi_c)};
        const Vec down = {std::cos(phi_c) * ca, std::cos(phi_c) * sa, -std::sin(phi_c)};
        const Vec out = {std::sin(phi_c) * ca, std::sin(phi_c) * sa, std::cos(phi_c)};
        // Waves grow like hang^2 over the first radius of hang: the tangent cone leaves the
        // sphere like hang^2 / (2 radius), so an inward wave never reaches into it.
        const double grow = std::min(1.0, hang / o.radius);
        const double depth = o.fold_depth * o.radius * grow * grow;
        return add(add(contact, scale(down, hang)), scale(out, depth * std::sin(o.folds * alpha)));
    }

    Vec normal(double u, double v) const {
        const double e = 1e-4 * o.size;
        const Vec n = cross(sub(surface(u + e, v), surface(u - e, v)), sub(surface(u, v + e), surface(u, v - e)));
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        return len > 0 ? scale(n, 1.0 / len) : Vec{0, 0, 1};
    }

    Vec point(double u, double v) const {
        if (o.flap <= 0) return surface(u, v);
        // Distance beyond the fold line u + v = d, along (1, 1) / sqrt 2.
        const double d = o.size * (1.0 - 2.0 * o.flap);
        const double t = (u + v - d) / std::numbers::sqrt2;
        if (t <= 0) return surface(u, v);
        // Turned over: mirrored across the fold line onto the cloth, then lifted along the
        // cloth's normal by a parabola that is 0 at the fold, peaks at flap_lift * radius
        // and crosses zero at 70 % of the flap's width (where the flap passes through).
        const double width = std::numbers::sqrt2 * o.size * o.flap;
        const double t0 = 0.7 * width;
        const double a = 4.0 * o.flap_lift * o.radius / (t0 * t0);
        const double w = a * t * (t0 - t);
        const double mu = u - std::numbers::sqrt2 * t, mv = v - std::numbers::sqrt2 * t;
        return add(surface(mu, mv), scale(normal(mu, mv), w));
    }
};

}  // namespace

Result<HostMesh> drapedCloth(const DrapeOptions& o) {
    const auto finite_positive = [](float x) { return std::isfinite(x) && x > 0.0f; };
    if (!finite_positive(o.radius) || !finite_positive(o.size))
        return Error(ErrorCode::InvalidArgument, "drapedCloth: radius and size must be positive and finite");
    if (!std::isfinite(o.gap) || !(o.gap > -o.radius)) return Error(ErrorCode::InvalidArgument, "drapedCloth: needs a finite gap > -radius");
    if (!(o.contact_angle > 0.0f) || !(o.contact_angle <= 0.5f * std::numbers::pi_v<float>))
        return Error(ErrorCode::InvalidArgument, "drapedCloth: contact_angle must be in (0, pi/2]");
    if (!std::isfinite(o.fold_depth) || !std::isfinite(o.flap_lift) || !(o.flap >= 0.0f) || !(o.flap < 0.5f))
        return Error(ErrorCode::InvalidArgument, "drapedCloth: needs finite fold_depth and flap_lift, flap in [0, 0.5)");
    if (o.quads < 1) return Error(ErrorCode::InvalidArgument, "drapedCloth: needs quads >= 1");
    if (2ull * o.quads * o.quads > kMaxGeneratedTriangles) return Error(ErrorCode::InvalidArgument, "drapedCloth: too many quads");

    const Drape drape{o};
    HostMesh mesh;
    mesh.name = "draped_cloth";
    const std::uint32_t n = o.quads;
    mesh.positions.reserve((n + 1ull) * (n + 1ull));
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) {
            const double u = o.size * (static_cast<double>(i) / n - 0.5), v = o.size * (static_cast<double>(j) / n - 0.5);
            const Vec p = drape.point(u, v);
            mesh.positions.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
        }
    // Counter-clockwise in (u, v): the front faces away from the sphere.
    const auto at = [n](std::uint32_t i, std::uint32_t j) { return j * (n + 1) + i; };
    mesh.indices.reserve(6ull * n * n);
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i)
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    return mesh;
}

}  // namespace vkcollide
