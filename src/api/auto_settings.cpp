// Automatic settings: what the world knows about its scene on the host (object boxes,
// typical edge lengths and area-weighted normals of host meshes, the typical edge lengths
// engines give for GPU meshes, and the scene box the last detection measured on the GPU)
// turned into a direction, a resolution, an open epsilon and a coverage, with a note saying
// how each was chosen. The tunables are in spirv/common/config.h.
#include "api/auto_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "api/vertex_scans.hpp"
#include "common/broadphase.h"
#include "contacts/contacts.h"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

using gpu::kFallbackResolution;
using gpu::kMaxAutoResolution;
using gpu::kMinAutoResolution;
using gpu::kOpenEpsilonPerEdge;
using gpu::kPixelsPerEdge;

// Largest factor by which the transform stretches a length (row norms bound it).
float maxScale(const Transform3x4& t) {
    float s = 0;
    for (int r = 0; r < 3; ++r) s = std::max(s, std::sqrt(t[r * 4] * t[r * 4] + t[r * 4 + 1] * t[r * 4 + 1] + t[r * 4 + 2] * t[r * 4 + 2]));
    return s;
}

std::uint32_t nextPowerOfTwo(double x) {
    std::uint32_t p = 1;
    while (p < x && p < (1u << 30)) p *= 2;
    return p;
}

using Vec3 = std::array<double, 3>;
Vec3 cross(const Vec3& a, const Vec3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The cofactor matrix of a transform's linear part, by rows (row i: the cross product of the
// other two rows): it maps object-space area vectors to world space.
using Cofactor = std::array<Vec3, 3>;
Cofactor cofactor(const Transform3x4& t) {
    const Vec3 r[3] = {Vec3{t[0], t[1], t[2]}, Vec3{t[4], t[5], t[6]}, Vec3{t[8], t[9], t[10]}};
    return {cross(r[1], r[2]), cross(r[2], r[0]), cross(r[0], r[1])};
}

// How much of an object's triangle area faces each world axis: sum over its triangles of
// area * (n . axis)^2 in world space. Area vectors map by the cofactor matrix C of the
// transform's linear part; C M C^T / |det|^(2/3) is exact for rotations with uniform scale
// and a fair estimate for the rest (the direction is a speed choice for the reliable
// method, a recall choice for peeling).
Vec3 worldFacing(const std::array<double, 6>& m, const Transform3x4& t) {
    const Vec3 r0{t[0], t[1], t[2]};
    const Cofactor c = cofactor(t);
    const double det = std::fabs(dot(r0, c[0]));
    const double norm = det > 0 ? std::cbrt(det * det) : 1.0;
    Vec3 out{};
    for (int a = 0; a < 3; ++a) {
        const Vec3& v = c[a];
        const double q = v[0] * v[0] * m[0] + v[1] * v[1] * m[1] + v[2] * v[2] * m[2] +
                         2 * (v[0] * v[1] * m[3] + v[0] * v[2] * m[4] + v[1] * v[2] * m[5]);
        out[a] = q / norm;
    }
    return out;
}

// The reliable method tilts its automatic axis where at least this share of the scene's
// area is exactly edge-on along it (faces of boxes aligned with the world's axes).
constexpr double kTiltFromEdgeOn = 0.25;

// The reliable method's direction where much of the scene's area would be seen edge-on
// along `axis`: that axis tilted by 20 degrees towards an azimuth that lines up with nothing.
// Along an axis, faces parallel to it (an axis-aligned box's four side faces: stacks, walls,
// mating parts) project to lines: their triangles pile up in lines of deep cells, swept pair
// by pair. Tilted they spread, and a face-on floor is still seen almost face-on (0.94 of its
// area). Only then: a tilt gives face-on triangles a depth, so they meet more others in
// depth (tilted always, the bench's pile of shapes on a floor made 84 % more candidates).
// The pairs are the same along any direction.
std::array<float, 3> tiltedAxis(int axis) {
    std::array<float, 3> d{};
    d[axis] = 0.94f, d[(axis + 1) % 3] = 0.21f, d[(axis + 2) % 3] = 0.27f;
    return d;
}

// Adds to `io_area` the world area of an object's axis-facing triangles (Shape::axis_area)
// that faces a world axis within kAxisFaceCos after transform `t`: a face with normal e_a maps
// to the cofactor matrix's column a (its area scaled by that column's length).
void addAxisFaces(const std::array<double, 3>& axis_area, const Transform3x4& t, Vec3& io_area) {
    const Cofactor c = cofactor(t);
    for (int a = 0; a < 3; ++a) {
        if (!(axis_area[a] > 0)) continue;
        const Vec3 v{c[0][a], c[1][a], c[2][a]};
        const double len = std::sqrt(dot(v, v));
        for (int w = 0; w < 3; ++w)
            if (len > 0 && std::fabs(v[w]) >= vertex_scans::kAxisFaceCos * len) io_area[w] += axis_area[a] * len;
    }
}

// The axis with the most facing area; within 1 %, z before y before x.
int largestFacing(const Vec3& score) {
    int best = 2;
    for (int a : {1, 0})
        if (score[a] > score[best] * 1.01) best = a;
    return best;
}

void append(std::string& note, const std::string& part) { note += (note.empty() ? "" : "; ") + part; }

}  // namespace

// On a GPU the tuner's grid was as fast as the fixed one or faster on every bench scene (the
// H200, docs/results.md); on a CPU implementation (lavapipe) its times are shared cores', so
// it stays off there.
GridTuning autoGridTuning(const vk::Device& device) {
    return device.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? GridTuning::Off : GridTuning::On;
}

// A host mesh's object-space box and largest |coordinate|: one pass over its vertices.
void AutoSettings::measureHost(Object& o, std::span<const Float3> positions) {
    float lo[3] = {positions[0].x, positions[0].y, positions[0].z}, hi[3] = {lo[0], lo[1], lo[2]};
    float max_abs = 0;
    for (const Float3& p : positions) {
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]), max_abs = std::max(max_abs, std::fabs(c[a]));
    }
    o.box = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
    o.max_abs = max_abs;
    o.shape_stale = true;
}

// The shapes steer automatic settings only (resolution rounded to a power of two or a cell
// count, direction the largest of three facings), so a deterministic sample of at most
// kShapeSampleTriangles triangles (evenly spaced blocks) measures them as well as all of them
// would (vertex_scans::measureShape). They are measured when a detection or resolveSettings
// needs them: here, for meshes still stale, or already by updateVertices, in its own loop,
// while the last settings needed them (wantsShape); not at all while the settings that use
// the shape are given. The direction and resolution use every object's; the open epsilon
// only open objects'.
// All of them in one parallel loop: a scene of deforming meshes starts the executor's
// threads once per detection, not once per mesh.
void AutoSettings::measureShapes(const DetectSettings& in, const ObjectRegistry& registry, Executor& executor) const {
    shapes_wanted_all = !in.direction || !in.resolution;
    shapes_wanted_open = !in.peeling.open_epsilon;
    std::vector<const Object*> stale;
    std::vector<vertex_scans::ShapeMesh> meshes;
    for (const Object& o : registry.objects) {
        if (!o.alive || !o.host || !o.shape_stale || !wantsShape(o)) continue;
        stale.push_back(&o);
        meshes.push_back({o.host_positions, o.host_indices});
    }
    if (stale.empty()) return;
    std::vector<vertex_scans::Shape> shapes(stale.size());
    vertex_scans::measureShapes(executor, meshes, shapes);
    for (std::size_t i = 0; i < stale.size(); ++i) {
        stale[i]->shape = shapes[i];
        stale[i]->shape_stale = false;
    }
}

// Fills every automatic field from the host's knowledge of the scene.
DetectSettings AutoSettings::resolve(const DetectSettings& in, const ObjectRegistry& registry, const vk::Device& device, Executor& executor,
                                     std::string* note, std::optional<GridChoice>* grid_choice) const {
    measureShapes(in, registry, executor);
    DetectSettings s = in;
    if (grid_choice) grid_choice->reset();
    const bool reliable = s.method == DetectMethod::Reliable;
    if (s.reliable.grid_tuning == GridTuning::Auto) s.reliable.grid_tuning = autoGridTuning(device);
    std::uint32_t live_objects = 0;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double edge_weighted = 0, edge_triangles = 0, open_edge = 0, open_triangles = 0;
    double host_triangles = 0, gpu_known_area = 0, gpu_known_triangles = 0, gpu_unknown_triangles = 0;
    std::uint64_t triangles = 0;
    Vec3 facing{};
    Vec3 axis_faces{};  // world area facing each world axis exactly (addAxisFaces)
    bool any_box = false, any_gpu = false;
    for (const Object& o : registry.objects) {
        if (!o.alive) continue;
        ++live_objects;
        const Transform3x4& t = o.options.transform;
        const double n = o.gpu.triangle_count, scale = maxScale(t);
        triangles += o.gpu.triangle_count;
        if (o.host) {
            for (int c = 0; c < 8; ++c) {
                const float p[3] = {o.box[(c & 1) ? 3 : 0], o.box[(c & 2) ? 4 : 1], o.box[(c & 4) ? 5 : 2]};
                for (int r = 0; r < 3; ++r) {
                    const float x = t[r * 4] * p[0] + t[r * 4 + 1] * p[1] + t[r * 4 + 2] * p[2] + t[r * 4 + 3];
                    lo[r] = std::min(lo[r], x), hi[r] = std::max(hi[r], x);
                }
            }
            any_box = true;
            const Vec3 f = worldFacing(o.shape.area_moment, t);
            for (int a = 0; a < 3; ++a) facing[a] += f[a];
            addAxisFaces(o.shape.axis_area, t, axis_faces);
            host_triangles += n;
        } else {
            any_gpu = true;
            if (o.shape.edge_length > 0) {
                const double e = double(o.shape.edge_length) * scale;
                gpu_known_area += n * 0.4330127 * e * e, gpu_known_triangles += n;  // equilateral triangles of that edge
            } else {
                gpu_unknown_triangles += n;
            }
        }
        if (o.shape.edge_length > 0) {
            const double e = double(o.shape.edge_length) * scale;
            edge_weighted += e * n, edge_triangles += n;
            if (o.options.open) open_edge += e * n, open_triangles += n;
        }
    }
    std::string why = std::string("method ") + toString(s.method);
    // GPU meshes: the host never sees their geometry. Their extent is the scene box the
    // last detection measured on the GPU; their facing is taken as that box's faces'.
    const bool use_measured = any_gpu && measured_box.has_value();
    if (use_measured) {
        const auto& m = *measured_box;
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], m[a]), hi[a] = std::max(hi[a], m[a + 3]);
        any_box = true;
        const double host_area = facing[0] + facing[1] + facing[2];
        const double per_triangle = host_triangles > 0 && host_area > 0 ? host_area / host_triangles
                                    : gpu_known_triangles > 0         ? gpu_known_area / gpu_known_triangles
                                                                      : 1.0;
        const double gpu_area = gpu_known_area + gpu_unknown_triangles * per_triangle;
        const double ext[3] = {double(m[3]) - m[0], double(m[4]) - m[1], double(m[5]) - m[2]};
        const double faces[3] = {ext[1] * ext[2], ext[0] * ext[2], ext[0] * ext[1]};
        const double total = faces[0] + faces[1] + faces[2];
        if (total > 0)
            for (int a = 0; a < 3; ++a) facing[a] += gpu_area * faces[a] / total;
        append(why, "engine meshes' extent and facing from the scene box the last detection measured");
    } else if (any_gpu) {
        append(why, "engine meshes not measured yet (first detection): host meshes only");
    }
    if (!s.direction) {
        std::array<float, 3> d{0, 0, 0};
        const double total = facing[0] + facing[1] + facing[2];
        char buf[160];
        int axis = 2;
        if (total > 0) {
            axis = largestFacing(facing);
            std::snprintf(buf, sizeof buf, "direction %c (most triangle area faces it: x %.0f %%, y %.0f %%, z %.0f %%)", "xyz"[axis],
                          100 * facing[0] / total, 100 * facing[1] / total, 100 * facing[2] / total);
        } else if (any_box) {
            for (int a : {1, 0})
                if (hi[a] - lo[a] < hi[axis] - lo[axis]) axis = a;
            std::snprintf(buf, sizeof buf, "direction %c (no triangle area measured: the scene's thinnest axis)", "xyz"[axis]);
        } else {
            std::snprintf(buf, sizeof buf, "direction z (no geometry measured yet)");
        }
        d[axis] = 1;
        append(why, buf);
        const double edge_on = axis_faces[(axis + 1) % 3] + axis_faces[(axis + 2) % 3];
        if (reliable && total > 0 && edge_on >= kTiltFromEdgeOn * total) {
            d = tiltedAxis(axis);
            std::snprintf(buf, sizeof buf, ", tilted 20 degrees to (%.2f, %.2f, %.2f): %.0f %% of the area would be edge-on", d[0], d[1],
                          d[2], 100 * edge_on / total);
            why += buf;
        }
        s.direction = d;
    }
    if (reliable && s.peeling.axes == 3) {  // any other count stays, for the check to name it
        s.peeling.axes = 1;
        append(why, "axes 1 (the reliable method's one grid finds every pair)");
    }
    const double typical_edge = edge_triangles > 0 ? edge_weighted / edge_triangles : 0;
    if (!s.resolution) {
        // Extent across the image: the box's widest extent perpendicular to the direction.
        const auto& d = *s.direction;
        const double dl = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
        double extent = 0;
        if (any_box) {
            const double size[3] = {double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]};
            for (int a = 0; a < 3; ++a) extent = std::max(extent, size[a] * std::sqrt(std::max(0.0, 1.0 - (d[a] / dl) * (d[a] / dl))));
        }
        if (s.region) {
            const auto& r = *s.region;
            extent = std::max({double(r[3] - r[0]), double(r[4] - r[1]), double(r[5] - r[2])});
        } else {
            extent *= 1.0 + 2.0 * double(gpu::kFitMargin);  // the fit's square
        }
        // Far from the origin, cells below the coordinates' rounding only add footprints.
        double magnitude = 0;
        if (any_box)
            for (int a = 0; a < 3; ++a) magnitude = std::max({magnitude, std::fabs(double(lo[a])), std::fabs(double(hi[a]))});
        char buf[200];
        std::string tuned;  // the grid tuner's reason, after the resolution's
        if (extent > 0 && typical_edge > 0 && reliable) {
            // The tuned grid: a step of the scene's tuner (GridTuner), or kCellsPerEdge as is.
            int step = 0;
            if (s.reliable.grid_tuning == GridTuning::On) {
                const GridTuner::Scene scene{triangles, live_objects};
                step = grid.next(scene);
                if (grid_choice) *grid_choice = GridChoice{scene, step};
            }
            const double per_edge = gpu::kCellsPerEdge * GridTuner::scale(step);
            const double want = per_edge * extent / typical_edge;
            const double budget = std::sqrt(std::max(gpu::kMaxCellsPerTriangle * double(triangles), double(gpu::kMinAutoCells) * gpu::kMinAutoCells));
            const double precise = magnitude > 0 ? extent / (gpu::kMinCellUlps * 0x1p-23 * magnitude) : INFINITY;
            double n = std::min({std::ceil(want), double(gpu::kMaxAutoCells), std::floor(budget)});
            n = std::max(n, double(gpu::kMinAutoCells));
            const bool rounding = precise < n;
            if (rounding) n = std::max(1.0, std::floor(precise));
            s.resolution = static_cast<std::uint32_t>(n);
            std::snprintf(buf, sizeof buf, "resolution %u cells (%.3g per typical edge %.4g across extent %.4g%s)", *s.resolution,
                          per_edge, typical_edge, extent,
                          rounding ? ", fewer: cells no finer than the coordinates' rounding this far from the origin"
                          : want > budget ? ", capped at 16 cells per triangle" : "");
            if (s.reliable.grid_tuning == GridTuning::On) tuned = grid.describe(step);
        } else if (extent > 0 && typical_edge > 0) {
            const double want = kPixelsPerEdge * extent / typical_edge;
            s.resolution = std::clamp(nextPowerOfTwo(want), kMinAutoResolution, kMaxAutoResolution);
            std::snprintf(buf, sizeof buf, "resolution %u (extent %.4g / typical edge %.4g x %.0f px per edge)", *s.resolution, extent,
                          typical_edge, kPixelsPerEdge);
        } else if (reliable && extent <= 0 && magnitude > 0) {
            // The scene collapsed to a point in float (features below the rounding this far
            // from the origin): finer cells would only repeat every footprint.
            s.resolution = 1;
            std::snprintf(buf, sizeof buf, "resolution 1 cell (the scene has no extent in float at magnitude %.3g)", magnitude);
        } else {
            s.resolution = reliable ? gpu::kFallbackCells : kFallbackResolution;
            std::snprintf(buf, sizeof buf, "resolution %u (no extent or typical edge length to measure)", *s.resolution);
        }
        append(why, buf);
        if (!tuned.empty()) append(why, tuned);
    }
    if (!s.peeling.open_epsilon) {
        s.peeling.open_epsilon = open_triangles > 0 ? static_cast<float>(kOpenEpsilonPerEdge * open_edge / open_triangles) : 0.0f;
        if (open_triangles > 0 && !reliable) append(why, "open epsilon half the open objects' typical edge");
    }
    if (s.peeling.coverage == Coverage::Best) {
        s.peeling.coverage = device.conservative_rasterization ? Coverage::Conservative : Coverage::Dilate;
        if (!reliable)
            append(why, s.peeling.coverage == Coverage::Conservative ? "coverage conservative (the device rasterises conservatively)"
                                                                     : "coverage dilate (no conservative rasterisation on this device)");
    }
    if (s.contacts.objects && !s.contacts.resolution) s.contacts.resolution = gpu::kDefaultContactResolution;
    if (note) *note = why;
    return s;
}

}  // namespace vkcollide
