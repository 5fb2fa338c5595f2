#include "cli/picture.hpp"

#include <algorithm>
#include <cmath>

#include "render/output.hpp"

namespace cli {
namespace {

using vkcollide::Float3;

Float3 sub(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Float3 add(Float3 a, Float3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Float3 mul(Float3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
float dot(Float3 a, Float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Float3 cross(Float3 a, Float3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Float3 normalize(Float3 a) {
    const float l = std::sqrt(dot(a, a));
    return l > 0 ? mul(a, 1.0f / l) : a;
}

constexpr float kFovDegrees = 40.0f;
// An oblique view from above, so that neither a flat scene nor a row of objects is seen edge-on.
constexpr Float3 kDefaultView{0.55f, 0.45f, 0.70f};
constexpr render::Rgb kRayColour{1.0f, 0.9f, 0.1f};

// Each ray as a thin square prism (four sides, eight triangles) of half-width h.
vkcollide::HostMesh rayPrisms(const vkcollide::CollisionRays& rays, float h) {
    vkcollide::HostMesh m;
    m.name = "collision rays";
    m.positions.reserve(rays.segments.size() * 8);
    m.indices.reserve(rays.segments.size() * 24);
    for (const auto& [a, b] : rays.segments) {
        const Float3 t = normalize(sub(b, a));
        const Float3 any = std::fabs(t.x) < 0.9f ? Float3{1, 0, 0} : Float3{0, 1, 0};
        const Float3 u = mul(normalize(cross(t, any)), h), v = mul(normalize(cross(t, u)), h);
        const Float3 corner[4] = {add(u, v), sub(u, v), mul(add(u, v), -1), sub(v, u)};
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        for (const Float3& c : corner) m.positions.push_back(add(a, c));
        for (const Float3& c : corner) m.positions.push_back(add(b, c));
        for (std::uint32_t k = 0; k < 4; ++k) {
            const std::uint32_t k1 = (k + 1) % 4;
            for (std::uint32_t i : {k, k1, 4 + k1, k, 4 + k1, 4 + k}) m.indices.push_back(base + i);
        }
    }
    return m;
}

}  // namespace

Picture::Picture(render::Engine& engine, const CommandLine& line, const Scene& scene, const EngineMeshes* engine_meshes)
    : renderer_(engine, line.png_width, line.png_height), dynamic_(line.sequence) {
    std::size_t gpu = 0;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        const render::Rgb colour = render::objectColour(i);
        render::DrawId id = 0;
        if (o.gpu_mesh && engine_meshes) {
            // The buffers vkcollide read: the picture shows exactly the geometry tested.
            id = renderer_.addGpuMesh(engine_meshes->vertices(gpu), 0, sizeof(Float3), engine_meshes->indices(gpu), 0,
                                      static_cast<std::uint32_t>(o.mesh.triangleCount()), colour);
            ++gpu;
        } else {
            id = renderer_.addMesh(o.mesh, colour, dynamic_);
        }
        renderer_.setTransform(id, o.options.transform);
        draws_.push_back(id);
        host_.push_back(!(o.gpu_mesh && engine_meshes));
    }

    const std::array<float, 6> b = scene.worldBounds();
    const Float3 centre{(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
    const float radius = std::max(0.5f * std::sqrt((b[3] - b[0]) * (b[3] - b[0]) + (b[4] - b[1]) * (b[4] - b[1]) + (b[5] - b[2]) * (b[5] - b[2])),
                                  1e-6f);
    const Float3 view = normalize(line.view ? Float3{(*line.view)[0], (*line.view)[1], (*line.view)[2]} : kDefaultView);
    const float half_fov = kFovDegrees * 3.14159265f / 360.0f;
    // The bounding sphere fits the vertical field of view (the narrower one for W >= H).
    const float aspect = static_cast<float>(line.png_width) / static_cast<float>(line.png_height);
    const float fit = aspect >= 1 ? std::sin(half_fov) : std::sin(std::atan(std::tan(half_fov) * aspect));
    const float distance = radius / fit * 1.05f;
    camera_.target = centre;
    camera_.eye = add(centre, mul(view, distance));
    camera_.up = std::fabs(view.y) > 0.99f ? Float3{0, 0, 1} : Float3{0, 1, 0};
    camera_.fov_degrees = kFovDegrees;
    camera_.near_plane = std::max(distance - 2 * radius, distance * 1e-3f);
    camera_.far_plane = distance + 2 * radius;
    screen_pixel_ = 2 * distance * std::tan(half_fov) / static_cast<float>(line.png_height);
}

std::string Picture::framePath(const std::string& path, std::size_t frame) {
    char number[32];
    std::snprintf(number, sizeof number, "_%04zu", frame);
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
    return has_ext ? path.substr(0, dot) + number + path.substr(dot) : path + number;
}

vkcollide::Result<void> Picture::write(const std::string& path, const Scene& scene, const vkcollide::DetectResult& result,
                                       const vkcollide::CollisionRays* rays) {
    if (dynamic_)
        for (std::size_t i = 0; i < scene.objects.size(); ++i)
            if (host_[i]) renderer_.updateVertices(draws_[i], scene.objects[i].mesh.positions);
    renderer_.clearHighlights();
    for (const vkcollide::TrianglePair& p : result.pairs) {
        renderer_.highlight(draws_[p.object_a], p.triangle_a);
        renderer_.highlight(draws_[p.object_b], p.triangle_b);
    }
    if (rays) {
        // A fifth of a ray's own pixel wide, but at least a screen pixel and a half (visible).
        const vkcollide::HostMesh sticks = rayPrisms(*rays, std::max(0.2f * rays->pixel_size, 0.75f * screen_pixel_));
        if (rays_) renderer_.replaceMesh(*rays_, sticks);
        else rays_ = renderer_.addMesh(sticks, kRayColour);
    }
    const std::vector<std::uint8_t>& pixels = renderer_.render(camera_);
    if (!render::writePng(path, renderer_.width(), renderer_.height(), pixels))
        return vkcollide::Error(vkcollide::ErrorCode::IoError, "--png: cannot write " + path);
    return {};
}

}  // namespace cli
