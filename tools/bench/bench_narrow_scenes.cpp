#include "bench_narrow_scenes.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>

namespace vkcollide::bench {

std::optional<std::vector<SceneObject>> touchingScene(const std::string& scene, std::size_t size) {
    if (scene != "touching" && scene != "touching-tilted") return std::nullopt;
    const double exponent = std::round(std::log2(std::sqrt(std::max(1.0, double(size) / 144.0))));
    const auto n = static_cast<std::uint32_t>(std::exp2(std::max(0.0, exponent)));
    Result<HostMesh> unit = box({0.5f, 0.5f, 0.5f}, n);
    if (!unit) {
        std::fprintf(stderr, "bench_narrow: box: %s\n", unit.error().message().c_str());
        std::exit(1);
    }
    // Rows of the linear part: the identity, or a map with entries that are multiples of
    // 1/8 (exact in float; with coordinates that are multiples of 1/(2n) and below 4, every
    // world coordinate is exact, so coplanar faces stay exactly coplanar).
    const bool tilted = scene == "touching-tilted";
    const float m[3][3] = {{1.0f, tilted ? 0.25f : 0.0f, tilted ? 0.125f : 0.0f},
                           {tilted ? -0.125f : 0.0f, 1.0f, tilted ? 0.375f : 0.0f},
                           {tilted ? 0.375f : 0.0f, tilted ? -0.25f : 0.0f, 1.0f}};
    std::vector<SceneObject> objects;
    for (int k = 0; k < 12; ++k) {
        const float at[3] = {float(k % 3), float(k / 3 % 2), float(k / 6)};
        SceneObject o{*unit, {}};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) o.transform[4 * r + c] = m[r][c];
            o.transform[4 * r + 3] = m[r][0] * at[0] + m[r][1] * at[1] + m[r][2] * at[2];
        }
        objects.push_back(std::move(o));
    }
    return objects;
}

}  // namespace vkcollide::bench
