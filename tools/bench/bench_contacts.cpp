// Object-level contacts against closed forms, by resolution (docs/contacts.md): the
// error of the volume, normal, depth and centroid for two overlapping spheres, a box
// inside a box and a sphere half sunk into a box, along the automatic direction and along
// a diagonal one, with the stage's cost. One table on stdout.
//
//   vkcollide_bench_contacts [--resolutions 16,32,64,128,256,512] [--repeat N]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

using V3 = std::array<double, 3>;

Transform3x4 translation(double x, double y, double z) { return {1, 0, 0, float(x), 0, 1, 0, float(y), 0, 0, 1, float(z)}; }

double meshVolume(const HostMesh& m) {
    double v = 0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const Float3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]], &c = m.positions[m.indices[t + 2]];
        v += (double(a.x) * (double(b.y) * c.z - double(b.z) * c.y) - double(a.y) * (double(b.x) * c.z - double(b.z) * c.x) +
              double(a.z) * (double(b.x) * c.y - double(b.y) * c.x)) / 6.0;
    }
    return v;
}

struct Case {
    std::string name;
    std::vector<std::pair<HostMesh, Transform3x4>> objects;
    double volume = 0;           // reference
    std::optional<V3> normal;    // unit; none: contained
    double depth = 0;
    V3 centroid{};
    double length = 1;           // errors of depth and centroid in % of this
};

Case twoSpheres() {
    const double r1 = 1.0, r2 = 0.8, d = 1.2;
    const V3 axis{0.8, 0.48, 0.36};
    Case c{"two spheres (lens)"};
    c.objects.push_back({*icosphere(float(r1), 4), kIdentity3x4});
    c.objects.push_back({*icosphere(float(r2), 4), translation(axis[0] * d, axis[1] * d, axis[2] * d)});
    const double a = (d * d + r1 * r1 - r2 * r2) / (2 * d), h1 = r1 - a, h2 = r2 - (d - a);
    auto cap = [](double r, double h) { return std::numbers::pi * h * h * (3 * r - h) / 3; };
    auto cz = [](double r, double h) { return 3 * (2 * r - h) * (2 * r - h) / (4 * (3 * r - h)); };
    const double v1 = cap(r1, h1), v2 = cap(r2, h2), at = (v1 * cz(r1, h1) + v2 * (d - cz(r2, h2))) / (v1 + v2);
    c.volume = v1 + v2;
    c.normal = axis;
    c.depth = r1 + r2 - d;
    c.centroid = {axis[0] * at, axis[1] * at, axis[2] * at};
    c.length = c.depth;
    return c;
}

Case boxInBox() {
    Case c{"box in box"};
    HostMesh inner = *box({0.3f, 0.2f, 0.4f}, 2);
    c.volume = meshVolume(inner);
    c.objects.push_back({*box({1, 1, 1}, 2), kIdentity3x4});
    c.objects.push_back({std::move(inner), translation(0.1, -0.2, 0.3)});
    c.centroid = {0.1, -0.2, 0.3};
    c.length = 0.4;
    return c;
}

Case halfSunk() {
    Case c{"sphere half in box"};
    const double r = 0.4;
    HostMesh ball = *uvSphere(float(r), 48, 24);
    c.volume = meshVolume(ball) / 2;  // the equator is a ring of vertices: exactly half the mesh
    c.objects.push_back({*box({1, 1, 0.5f}, 1), kIdentity3x4});
    c.objects.push_back({std::move(ball), translation(0.1, 0.2, 0.5)});
    c.normal = V3{0, 0, 1};
    c.depth = r;
    c.centroid = {0.1, 0.2, 0.5 - 3 * r / 8};
    c.length = r;
    return c;
}

double angle(Float3 n, V3 d) {
    const double ln = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
    if (ln == 0) return 180;
    return std::acos(std::clamp((n.x * d[0] + n.y * d[1] + n.z * d[2]) / ln, -1.0, 1.0)) * 180 / std::numbers::pi;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::uint32_t> resolutions = {16, 32, 64, 128, 256, 512};
    int repeat = 3;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--resolutions") {
            resolutions.clear();
            std::stringstream ss(argv[i + 1]);
            for (std::string item; std::getline(ss, item, ',');) resolutions.push_back(static_cast<std::uint32_t>(std::stoul(item)));
        } else if (a == "--repeat") {
            repeat = std::max(1, std::atoi(argv[i + 1]));
        } else {
            std::fprintf(stderr, "usage: vkcollide_bench_contacts [--resolutions 16,32,...] [--repeat N]\n");
            return 2;
        }
    }
    auto ctx = Context::create();
    if (!ctx) return std::fprintf(stderr, "%s\n", ctx.error().message().c_str()), 1;
    std::printf("device: %s\n", (*ctx)->deviceInfo().name.c_str());
    std::printf("%-20s %-9s %5s %9s %9s %9s %9s %9s %9s %9s %9s\n", "case", "direction", "res", "rays", "volume%", "normal deg",
                "depth%", "centroid%", "gpu ms", "stage ms", "detect ms");
    for (Case c : {twoSpheres(), boxInBox(), halfSunk()}) {
        auto world = CollisionWorld::create(**ctx);
        if (!world) return std::fprintf(stderr, "%s\n", world.error().message().c_str()), 1;
        for (auto& [mesh, at] : c.objects)
            if (auto id = (*world)->addMesh(mesh, {.transform = at}); !id) return std::fprintf(stderr, "%s\n", id.error().message().c_str()), 1;
        for (const char* dir : {"auto", "diagonal"})
            for (std::uint32_t res : resolutions) {
                DetectSettings s{.contacts = {.objects = true, .resolution = res}};
                if (std::string(dir) == "diagonal") s.direction = std::array<float, 3>{0.577f, -0.577f, 0.577f};
                double gpu = 0, stage = 0, total = 0;
                std::optional<DetectResult> last;
                for (int k = 0; k < repeat + 1; ++k) {  // the first run warms up
                    auto r = (*world)->detect(s);
                    if (!r) return std::fprintf(stderr, "%s\n", r.error().message().c_str()), 1;
                    if (k > 0) gpu += r->stats.contacts.gpu_ms, stage += r->stats.contacts.host_ms, total += r->stats.total_ms;
                    last = std::move(*r);
                }
                if (last->contacts.size() != 1) {
                    std::printf("%-20s %-9s %5u: %zu contacts\n", c.name.c_str(), dir, res, last->contacts.size());
                    continue;
                }
                const ObjectContact& oc = last->contacts[0];
                const double dv = 100 * (oc.volume - c.volume) / c.volume;
                const double dn = c.normal ? angle(oc.normal, *c.normal) : (oc.normal.x == 0 && oc.normal.y == 0 && oc.normal.z == 0 ? 0 : 180);
                const double dd = c.normal ? 100 * (oc.depth - c.depth) / c.length : 0;
                const double dc = 100 * std::sqrt((oc.point.x - c.centroid[0]) * (oc.point.x - c.centroid[0]) +
                                                  (oc.point.y - c.centroid[1]) * (oc.point.y - c.centroid[1]) +
                                                  (oc.point.z - c.centroid[2]) * (oc.point.z - c.centroid[2])) / c.length;
                std::printf("%-20s %-9s %5u %9u %+9.3f %9.3f %+9.3f %9.3f %9.3f %9.3f %9.3f\n", c.name.c_str(), dir, res,
                            last->stats.contacts.rays_x * last->stats.contacts.rays_y, dv, dn, dd, dc, gpu / repeat, stage / repeat, total / repeat);
            }
    }
    return 0;
}
