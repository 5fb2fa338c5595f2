#include "common/meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <meshoptimizer.h>
#include <unordered_map>
#include <vector>

#include "common/render.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

namespace samples {

using vkcollide::Float3;
using vkcollide::HostMesh;

namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; }

HostMesh lumpy(HostMesh mesh, Float3 scale) {
    for (Float3& p : mesh.positions) {
        const float bump = 1.0f + 0.10f * std::sin(3.1f * p.x + 0.4f) * std::sin(2.3f * p.y + 1.0f) * std::sin(2.7f * p.z + 0.3f);
        p = {p.x * bump * scale.x, p.y * bump * scale.y, p.z * bump * scale.z};
    }
    return mesh;
}

HostMesh standInMesh(StandIn kind) {
    auto need = [](vkcollide::Result<HostMesh> m) {
        if (!m) die(m.error().message());
        return std::move(*m);
    };
    switch (kind) {
        case StandIn::Blob: return lumpy(need(vkcollide::uvSphere(1.0f, 48, 24)), {1.0f, 0.9f, 1.0f});
        case StandIn::Long: return lumpy(need(vkcollide::uvSphere(1.0f, 64, 32)), {2.0f, 0.8f, 1.0f});
        case StandIn::Ring: return lumpy(need(vkcollide::torus(1.0f, 0.4f, 64, 24)), {1.0f, 1.0f, 1.0f});
    }
    return {};
}

}  // namespace

void normalizeMesh(HostMesh& m, float size) {
    Float3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
    Float3 hi{-lo.x, -lo.y, -lo.z};
    for (const Float3& p : m.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Float3 c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const float s = extent > 0 ? size / extent : 1.0f;
    for (Float3& p : m.positions) p = {(p.x - c.x) * s, (p.y - c.y) * s, (p.z - c.z) * s};
}

void turnMesh(HostMesh& m, Float3 from, Float3 to) {
    auto unit = [](Float3 v) {
        const float l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        return Float3{v.x / l, v.y / l, v.z / l};
    };
    const Float3 a = unit(from), b = unit(to);
    // Rodrigues' rotation about a x b by the angle between them.
    const Float3 k{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    const float sin_angle = std::sqrt(k.x * k.x + k.y * k.y + k.z * k.z), cos_angle = a.x * b.x + a.y * b.y + a.z * b.z;
    if (sin_angle < 1e-7f) return;  // already along it (turning half round is never asked)
    const Float3 axis{k.x / sin_angle, k.y / sin_angle, k.z / sin_angle};
    for (Float3& p : m.positions) {
        const Float3 c{axis.y * p.z - axis.z * p.y, axis.z * p.x - axis.x * p.z, axis.x * p.y - axis.y * p.x};
        const float d = (axis.x * p.x + axis.y * p.y + axis.z * p.z) * (1 - cos_angle);
        p = {p.x * cos_angle + c.x * sin_angle + axis.x * d, p.y * cos_angle + c.y * sin_angle + axis.y * d,
             p.z * cos_angle + c.z * sin_angle + axis.z * d};
    }
}

HostMesh loadSceneMesh(const CommonOptions& options, const std::string& file, StandIn stand_in, float size, Float3 file_up) {
    HostMesh mesh;
    const std::string path = options.stand_ins ? std::string() : findDataMesh(options, file);
    if (path.empty()) {
        if (!options.stand_ins)
            std::fprintf(stderr, "note: %s not found (run tools/fetch_cgal_data.sh, or --data DIR); using a generated stand-in\n",
                         file.c_str());
        mesh = standInMesh(stand_in);
        mesh.name = file.substr(0, file.find('.')) + " (stand-in)";
    } else {
        auto meshes = vkcollide::readMeshFile(path);
        if (!meshes) die(meshes.error().message());
        mesh = std::move(meshes->front());
        turnMesh(mesh, file_up, {0, 1, 0});
    }
    normalizeMesh(mesh, size);
    return mesh;
}

HostMesh simplifyMesh(const HostMesh& mesh, std::size_t target_triangles) {
    if (mesh.triangleCount() <= target_triangles) return mesh;
    std::vector<std::uint32_t> indices(mesh.indices.size());
    // No error limit: the triangle count is the target (the samples want a budget).
    const std::size_t n = meshopt_simplify(indices.data(), mesh.indices.data(), mesh.indices.size(), &mesh.positions[0].x,
                                           mesh.positions.size(), sizeof(Float3), target_triangles * 3, 1.0f, 0, nullptr);
    indices.resize(n);
    HostMesh out;
    out.name = mesh.name;
    std::vector<std::uint32_t> remap(mesh.positions.size(), ~0u);
    for (std::uint32_t& i : indices) {
        if (remap[i] == ~0u) {
            remap[i] = static_cast<std::uint32_t>(out.positions.size());
            out.positions.push_back(mesh.positions[i]);
        }
        i = remap[i];
    }
    out.indices = std::move(indices);
    return out;
}

HostMesh subdivideLoop(const HostMesh& mesh) {
    const std::size_t nv = mesh.positions.size(), nt = mesh.triangleCount();
    // Directed edge -> the vertex opposite it in its triangle.
    std::unordered_map<std::uint64_t, std::uint32_t> opposite;
    opposite.reserve(nt * 3);
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            opposite[edgeKey(mesh.indices[t * 3 + k], mesh.indices[t * 3 + (k + 1) % 3])] = mesh.indices[t * 3 + (k + 2) % 3];

    HostMesh out;
    out.name = mesh.name;
    out.positions.resize(nv);
    // Even (old) vertices: Loop's weights over the one-ring; boundary vertices stay put.
    std::vector<Float3> ring_sum(nv);
    std::vector<std::uint32_t> valence(nv, 0);
    std::vector<bool> boundary(nv, false);
    for (const auto& [key, opp] : opposite) {
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        (void)opp;
        const Float3 pb = mesh.positions[b];
        ring_sum[a] = {ring_sum[a].x + pb.x, ring_sum[a].y + pb.y, ring_sum[a].z + pb.z};
        ++valence[a];
        if (!opposite.count(edgeKey(b, a))) boundary[a] = boundary[b] = true;
    }
    for (std::size_t v = 0; v < nv; ++v) {
        const Float3 p = mesh.positions[v];
        const float n = static_cast<float>(valence[v]);
        if (boundary[v] || valence[v] < 3) {
            out.positions[v] = p;
            continue;
        }
        const float beta = valence[v] == 3 ? 3.0f / 16.0f : 3.0f / (8.0f * n);
        const Float3 s = ring_sum[v];
        out.positions[v] = {p.x * (1 - n * beta) + s.x * beta, p.y * (1 - n * beta) + s.y * beta, p.z * (1 - n * beta) + s.z * beta};
    }
    // Odd (edge) vertices, one per undirected edge.
    std::unordered_map<std::uint64_t, std::uint32_t> edge_vertex;
    edge_vertex.reserve(nt * 2);
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint64_t key = edgeKey(std::min(a, b), std::max(a, b));
        auto [it, fresh] = edge_vertex.try_emplace(key, static_cast<std::uint32_t>(out.positions.size()));
        if (!fresh) return it->second;
        const Float3 pa = mesh.positions[a], pb = mesh.positions[b];
        auto c = opposite.find(edgeKey(a, b)), d = opposite.find(edgeKey(b, a));
        if (c == opposite.end() || d == opposite.end()) {
            out.positions.push_back({(pa.x + pb.x) / 2, (pa.y + pb.y) / 2, (pa.z + pb.z) / 2});
        } else {
            const Float3 pc = mesh.positions[c->second], pd = mesh.positions[d->second];
            out.positions.push_back({0.375f * (pa.x + pb.x) + 0.125f * (pc.x + pd.x), 0.375f * (pa.y + pb.y) + 0.125f * (pc.y + pd.y),
                                     0.375f * (pa.z + pb.z) + 0.125f * (pc.z + pd.z)});
        }
        return it->second;
    };
    out.indices.reserve(nt * 12);
    for (std::size_t t = 0; t < nt; ++t) {
        const std::uint32_t a = mesh.indices[t * 3], b = mesh.indices[t * 3 + 1], c = mesh.indices[t * 3 + 2];
        const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        for (std::uint32_t i : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) out.indices.push_back(i);
    }
    return out;
}

HostMesh subdivideSqrt3(const HostMesh& mesh) {
    const std::size_t nv = mesh.positions.size(), nt = mesh.triangleCount();
    // Directed edge -> its triangle.
    std::unordered_map<std::uint64_t, std::uint32_t> face_of;
    face_of.reserve(nt * 3);
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            face_of[edgeKey(mesh.indices[t * 3 + k], mesh.indices[t * 3 + (k + 1) % 3])] = static_cast<std::uint32_t>(t);

    HostMesh out;
    out.name = mesh.name;
    out.positions.resize(nv + nt);
    // Old vertices relax towards their one-ring: alpha_n = (4 - 2 cos(2 pi / n)) / 9.
    std::vector<Float3> ring_sum(nv);
    std::vector<std::uint32_t> valence(nv, 0);
    std::vector<bool> boundary(nv, false);
    for (const auto& [key, face] : face_of) {
        (void)face;
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        const Float3 pb = mesh.positions[b];
        ring_sum[a] = {ring_sum[a].x + pb.x, ring_sum[a].y + pb.y, ring_sum[a].z + pb.z};
        ++valence[a];
        if (!face_of.count(edgeKey(b, a))) boundary[a] = boundary[b] = true;
    }
    for (std::size_t v = 0; v < nv; ++v) {
        const Float3 p = mesh.positions[v];
        if (boundary[v] || valence[v] < 3) {
            out.positions[v] = p;
            continue;
        }
        const float n = static_cast<float>(valence[v]);
        const float alpha = (4.0f - 2.0f * std::cos(2.0f * 3.14159265f / n)) / 9.0f;
        const Float3 s = ring_sum[v];
        out.positions[v] = {p.x * (1 - alpha) + s.x * alpha / n, p.y * (1 - alpha) + s.y * alpha / n, p.z * (1 - alpha) + s.z * alpha / n};
    }
    // A new vertex at each face's centroid; each old edge is flipped to join the two
    // centroids beside it: half-edge a->b of face f with twin face g gives (a, c_g, c_f).
    for (std::size_t t = 0; t < nt; ++t) {
        Float3 c{};
        for (int k = 0; k < 3; ++k) {
            const Float3 p = mesh.positions[mesh.indices[t * 3 + k]];
            c = {c.x + p.x / 3, c.y + p.y / 3, c.z + p.z / 3};
        }
        out.positions[nv + t] = c;
    }
    out.indices.reserve(nt * 9);
    for (std::size_t t = 0; t < nt; ++t) {
        const auto cf = static_cast<std::uint32_t>(nv + t);
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = mesh.indices[t * 3 + k], b = mesh.indices[t * 3 + (k + 1) % 3];
            auto twin = face_of.find(edgeKey(b, a));
            if (twin == face_of.end()) {
                for (std::uint32_t i : {a, b, cf}) out.indices.push_back(i);  // boundary edge: not flipped
            } else {
                for (std::uint32_t i : {a, static_cast<std::uint32_t>(nv + twin->second), cf}) out.indices.push_back(i);
            }
        }
    }
    return out;
}

HostMesh subdivideTo(const HostMesh& mesh, std::size_t target, std::string* steps) {
    const double base = static_cast<double>(mesh.triangleCount());
    int best_loop = 0, best_sqrt3 = 0;
    double best = std::abs(std::log(base / static_cast<double>(std::max<std::size_t>(target, 1))));
    for (int l = 0; l <= 6; ++l)
        for (int s = 0; s <= 6; ++s) {
            const double count = base * std::pow(4.0, l) * std::pow(3.0, s);
            const double miss = std::abs(std::log(count / static_cast<double>(std::max<std::size_t>(target, 1))));
            if (miss < best - 1e-9) {
                best = miss;
                best_loop = l;
                best_sqrt3 = s;
            }
        }
    HostMesh out = mesh;
    std::string done;
    for (int i = 0; i < best_loop; ++i, done += done.empty() ? "loop" : ", loop") out = subdivideLoop(out);
    for (int i = 0; i < best_sqrt3; ++i, done += done.empty() ? "sqrt3" : ", sqrt3") out = subdivideSqrt3(out);
    if (steps) *steps = done.empty() ? "none" : done;
    return out;
}

std::size_t closeHoles(HostMesh& m) {
    std::unordered_map<std::uint64_t, bool> directed;
    const std::size_t nt = m.triangleCount();
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) directed[edgeKey(m.indices[t * 3 + k], m.indices[t * 3 + (k + 1) % 3])] = true;
    // A boundary half-edge a->b has no twin b->a; the hole's fill runs b->a, so walk
    // from each vertex to the start of the boundary half-edge that ends there.
    std::unordered_map<std::uint32_t, std::uint32_t> previous;
    for (const auto& [key, used] : directed) {
        (void)used;
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        if (!directed.count(edgeKey(b, a))) previous[b] = a;
    }
    std::size_t holes = 0;
    while (!previous.empty()) {
        std::vector<std::uint32_t> loop{previous.begin()->first};
        bool closed = false;
        for (std::size_t guard = 0; guard <= previous.size(); ++guard) {
            auto next = previous.find(loop.back());
            if (next == previous.end()) break;
            if (next->second == loop.front()) {
                closed = true;
                break;
            }
            loop.push_back(next->second);
        }
        for (std::uint32_t v : loop) previous.erase(v);
        if (!closed || loop.size() < 3) continue;  // not a simple loop: leave it
        Float3 c{};
        for (std::uint32_t v : loop) {
            const Float3 p = m.positions[v];
            c = {c.x + p.x, c.y + p.y, c.z + p.z};
        }
        const float n = static_cast<float>(loop.size());
        m.positions.push_back({c.x / n, c.y / n, c.z / n});
        const auto centre = static_cast<std::uint32_t>(m.positions.size() - 1);
        for (std::size_t i = 0; i < loop.size(); ++i)
            for (std::uint32_t v : {loop[i], loop[(i + 1) % loop.size()], centre}) m.indices.push_back(v);
        ++holes;
    }
    return holes;
}

void appendMesh(HostMesh& m, const HostMesh& part) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), part.positions.begin(), part.positions.end());
    for (std::uint32_t i : part.indices) m.indices.push_back(base + i);
}

}  // namespace samples
