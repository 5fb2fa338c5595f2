// Proximity (DetectSettings::proximity, docs/proximity.md) on large scenes: a cloth folded
// onto itself (self-contact; one with about 391K edges as in Newton's published figure,
// one of 524K triangles) and a deforming pair of spheres pressed together, for distances of
// 0.1 to 1 typical edge length. Per (scene, d): detect() end to end, the GPU stages
// (footprints, pairing, filtering, the proximity pass), the pairs found, and with
// --reference a multithreaded CPU grid reference in double (its time and the pairs the GPU
// missed or added: added ones must be flagged kProximityInBand). One line per run on
// stdout, and a CSV.
//
//   vkcollide_bench_proximity [--scenes cloth-391k,cloth-524k,pair] [--factors 0.1,0.5,1]
//                             [--frames N] [--warmup-ms M] [--threads T] [--reference] [--csv FILE]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct Object {
    HostMesh mesh;
    bool self = false;
};
struct Scene {
    std::string name;
    std::vector<Object> objects;
    double edge = 0;        // typical edge length
    bool deforming = false;  // vertices change every frame
};

// A cloth of n x n squares folded almost onto itself about the y axis, sagging a little.
Scene foldedCloth(const char* name, std::uint32_t n) {
    auto cloth = clothGrid(2.0f, 2.0f, n, n, {.sag = 0.05f, .fold_angle = 3.05f});
    return {name, {{std::move(*cloth), true}}, 2.0 / n, false};
}

// Two spheres of 81,920 triangles each, pressed together; their surfaces wobble each frame.
Scene spherePair() {
    Scene s{"pair", {}, 0, true};
    auto a = icosphere(0.5f, 6), b = icosphere(0.5f, 6);
    for (Float3& p : b->positions) p.x += 0.98f;
    s.objects = {{std::move(*a), false}, {std::move(*b), false}};
    s.edge = 0.5 * 1.26 / 64;  // icosphere level 6: about 1.26 r / 2^6
    return s;
}

void deform(const HostMesh& rest, HostMesh& out, int frame, float amplitude) {
    out = rest;
    const float t = 0.3f * float(frame);
    for (Float3& p : out.positions) {
        const float w = amplitude * std::sin(9.0f * p.y + t) * std::cos(7.0f * p.z - t);
        p.x += w, p.y += 0.5f * w;
    }
}

// ---- CPU reference: a uniform grid of cells of side max(d, edge), in double ------------

struct Key {
    ProximityKind kind;
    std::uint32_t oa, a0, a1, ob, b0, b1;
    bool operator<(const Key& o) const {
        return std::tie(kind, oa, a0, a1, ob, b0, b1) < std::tie(o.kind, o.oa, o.a0, o.a1, o.ob, o.b0, o.b1);
    }
    bool operator==(const Key& o) const { return !(*this < o) && !(o < *this); }
};
struct RefPair {
    Key key;
    double distance;
};

using D3 = std::array<double, 3>;
D3 sub(D3 a, D3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(D3 a, D3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(D3 a, D3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
D3 lerp(D3 a, D3 b, double t) { return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])}; }
double dist2(D3 a, D3 b) { const D3 d = sub(a, b); return dot(d, d); }
double param(D3 p, D3 a, D3 b) {
    const D3 ab = sub(b, a);
    const double l = dot(ab, ab);
    return l > 0 ? std::clamp(dot(sub(p, a), ab) / l, 0.0, 1.0) : 0.0;
}
double pointSegment2(D3 p, D3 a, D3 b) { return dist2(p, lerp(a, b, param(p, a, b))); }
double pointTriangle2(D3 p, D3 a, D3 b, D3 c) {
    double best = std::min({pointSegment2(p, a, b), pointSegment2(p, b, c), pointSegment2(p, c, a)});
    const D3 n = cross(sub(b, a), sub(c, a));
    const double nn = dot(n, n);
    if (nn > 0) {
        const double h = dot(sub(p, a), n);
        const D3 q = sub(p, {h / nn * n[0], h / nn * n[1], h / nn * n[2]});
        if (dot(cross(sub(b, a), sub(q, a)), n) >= 0 && dot(cross(sub(c, b), sub(q, b)), n) >= 0 && dot(cross(sub(a, c), sub(q, c)), n) >= 0)
            best = std::min(best, h * h / nn);
    }
    return best;
}
double segmentSegment2(D3 p1, D3 q1, D3 p2, D3 q2) {
    double best = std::min({pointSegment2(p1, p2, q2), pointSegment2(q1, p2, q2), pointSegment2(p2, p1, q1), pointSegment2(q2, p1, q1)});
    const D3 d1 = sub(q1, p1), d2 = sub(q2, p2), r = sub(p1, p2);
    const double a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r), den = a * e - b * b;
    if (den > 1e-30 * a * e) {
        const double s = (b * f - c * e) / den, t = (a * f - b * c) / den;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = std::min(best, dist2(lerp(p1, q1, s), lerp(p2, q2, t)));
    }
    return best;
}

struct Prim {
    std::uint32_t object, v[3];  // triangle: 3 vertices; edge: 2 (v[2] unused)
};

std::vector<RefPair> cpuReference(const std::vector<Object>& objects, double d, double cell, unsigned threads) {
    std::vector<std::vector<D3>> world(objects.size());
    std::vector<Prim> tris, edges;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> verts;  // (object, vertex)
    for (std::uint32_t o = 0; o < objects.size(); ++o) {
        const HostMesh& m = objects[o].mesh;
        for (const Float3& p : m.positions) world[o].push_back({p.x, p.y, p.z});
        std::vector<std::pair<std::uint32_t, std::uint32_t>> e;
        std::vector<char> used(m.positions.size(), 0);
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            tris.push_back({o, {m.indices[t], m.indices[t + 1], m.indices[t + 2]}});
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t x = m.indices[t + k], y = m.indices[t + (k + 1) % 3];
                e.emplace_back(std::min(x, y), std::max(x, y));
                used[x] = 1;
            }
        }
        std::sort(e.begin(), e.end());
        e.erase(std::unique(e.begin(), e.end()), e.end());
        for (auto [x, y] : e) edges.push_back({o, {x, y, 0}});
        for (std::uint32_t v = 0; v < used.size(); ++v)
            if (used[v]) verts.emplace_back(o, v);
    }
    auto cellOf = [cell](double x) { return static_cast<std::int64_t>(std::floor(x / cell)); };
    auto hash = [](std::int64_t i, std::int64_t j, std::int64_t k) {
        return static_cast<std::uint64_t>((i * 73856093) ^ (j * 19349663) ^ (k * 83492791));
    };
    // Primitives into every cell their box grown by d meets.
    auto index = [&](const std::vector<Prim>& prims, int nv) {
        std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
        for (std::uint32_t i = 0; i < prims.size(); ++i) {
            D3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
            for (int k = 0; k < nv; ++k)
                for (int a = 0; a < 3; ++a)
                    lo[a] = std::min(lo[a], world[prims[i].object][prims[i].v[k]][a]), hi[a] = std::max(hi[a], world[prims[i].object][prims[i].v[k]][a]);
            for (std::int64_t x = cellOf(lo[0] - d); x <= cellOf(hi[0] + d); ++x)
                for (std::int64_t y = cellOf(lo[1] - d); y <= cellOf(hi[1] + d); ++y)
                    for (std::int64_t z = cellOf(lo[2] - d); z <= cellOf(hi[2] + d); ++z) grid[hash(x, y, z)].push_back(i);
        }
        return grid;
    };
    const auto tri_grid = index(tris, 3), edge_grid = index(edges, 2);
    auto self = [&](std::uint32_t o) { return objects[o].self; };
    auto sameBits = [&](std::uint32_t o1, std::uint32_t v1, std::uint32_t o2, std::uint32_t v2) {
        const Float3 &a = objects[o1].mesh.positions[v1], &b = objects[o2].mesh.positions[v2];
        return std::memcmp(&a, &b, sizeof a) == 0;
    };
    std::vector<std::vector<RefPair>> found(threads);
    std::atomic<std::size_t> next{0};
    const std::size_t jobs = verts.size() + edges.size();
    auto work = [&](unsigned w) {
        std::vector<std::uint32_t> seen;
        for (;;) {
            const std::size_t begin = next.fetch_add(1024);
            if (begin >= jobs) return;
            for (std::size_t j = begin; j < std::min(jobs, begin + 1024); ++j) {
                if (j < verts.size()) {
                    const auto [o, v] = verts[j];
                    const D3 p = world[o][v];
                    auto it = tri_grid.find(hash(cellOf(p[0]), cellOf(p[1]), cellOf(p[2])));
                    if (it == tri_grid.end()) continue;
                    for (std::uint32_t t : it->second) {
                        const Prim& tr = tris[t];
                        if (tr.object == o && !self(o)) continue;
                        if (tr.object == o && (tr.v[0] == v || tr.v[1] == v || tr.v[2] == v || sameBits(o, v, o, tr.v[0]) ||
                                               sameBits(o, v, o, tr.v[1]) || sameBits(o, v, o, tr.v[2])))
                            continue;
                        const auto& wt = world[tr.object];
                        const double d2 = pointTriangle2(p, wt[tr.v[0]], wt[tr.v[1]], wt[tr.v[2]]);
                        if (d2 <= d * d) {
                            // The GPU's triangle index within its object.
                            std::uint32_t local = t;
                            for (std::uint32_t k = 0; k < tr.object; ++k) local -= std::uint32_t(objects[k].mesh.indices.size() / 3);
                            found[w].push_back({{ProximityKind::VertexTriangle, o, v, kNoPrimitive, tr.object, local, kNoPrimitive}, std::sqrt(d2)});
                        }
                    }
                } else {
                    const std::uint32_t e = static_cast<std::uint32_t>(j - verts.size());
                    const Prim& ea = edges[e];
                    const auto& wa = world[ea.object];
                    seen.clear();
                    D3 lo, hi;
                    for (int a = 0; a < 3; ++a) lo[a] = std::min(wa[ea.v[0]][a], wa[ea.v[1]][a]), hi[a] = std::max(wa[ea.v[0]][a], wa[ea.v[1]][a]);
                    for (std::int64_t x = cellOf(lo[0]); x <= cellOf(hi[0]); ++x)
                        for (std::int64_t y = cellOf(lo[1]); y <= cellOf(hi[1]); ++y)
                            for (std::int64_t z = cellOf(lo[2]); z <= cellOf(hi[2]); ++z)
                                if (auto it = edge_grid.find(hash(x, y, z)); it != edge_grid.end())
                                    for (std::uint32_t f : it->second)
                                        if (f > e) seen.push_back(f);
                    std::sort(seen.begin(), seen.end());
                    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
                    for (std::uint32_t f : seen) {
                        const Prim& eb = edges[f];
                        if (eb.object == ea.object && !self(ea.object)) continue;
                        if (eb.object == ea.object &&
                            (ea.v[0] == eb.v[0] || ea.v[0] == eb.v[1] || ea.v[1] == eb.v[0] || ea.v[1] == eb.v[1] ||
                             sameBits(ea.object, ea.v[0], eb.object, eb.v[0]) || sameBits(ea.object, ea.v[0], eb.object, eb.v[1]) ||
                             sameBits(ea.object, ea.v[1], eb.object, eb.v[0]) || sameBits(ea.object, ea.v[1], eb.object, eb.v[1])))
                            continue;
                        const auto& wb = world[eb.object];
                        const double d2 = segmentSegment2(wa[ea.v[0]], wa[ea.v[1]], wb[eb.v[0]], wb[eb.v[1]]);
                        if (d2 <= d * d)
                            found[w].push_back({{ProximityKind::EdgeEdge, ea.object, ea.v[0], ea.v[1], eb.object, eb.v[0], eb.v[1]}, std::sqrt(d2)});
                    }
                }
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < threads; ++w) pool.emplace_back(work, w);
    for (auto& t : pool) t.join();
    std::vector<RefPair> out;
    for (auto& f : found) out.insert(out.end(), f.begin(), f.end());
    std::sort(out.begin(), out.end(), [](const RefPair& a, const RefPair& b) { return a.key < b.key; });
    return out;
}

Key keyOf(const ProximityPair& p) { return {p.kind, p.object_a, p.a0, p.a1, p.object_b, p.b0, p.b1}; }

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string part; std::getline(in, part, ',');) out.push_back(part);
    return out;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenes = "cloth-391k,cloth-524k,pair", factors = "0.1,0.5,1", csv_path = "bench_proximity.csv";
    int frames = 10;
    double warmup_ms = 300;
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    bool reference = false, passes = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--scenes") scenes = value();
        else if (a == "--factors") factors = value();
        else if (a == "--frames") frames = std::max(1, std::atoi(value().c_str()));
        else if (a == "--warmup-ms") warmup_ms = std::atof(value().c_str());
        else if (a == "--threads") threads = std::max(1, std::atoi(value().c_str()));
        else if (a == "--reference") reference = true;
        else if (a == "--passes") passes = true;
        else if (a == "--csv") csv_path = value();
        else {
            std::fprintf(stderr,
                         "usage: vkcollide_bench_proximity [--scenes cloth-391k,cloth-524k,pair] [--factors 0.1,0.5,1] [--frames N] "
                         "[--warmup-ms M] [--threads T] [--reference] [--passes] [--csv FILE]\n"
                         "  --passes: also the median GPU time of every pass, with and without proximity\n");
            return a == "--help" ? 0 : 2;
        }
    }
    auto ctx = Context::create();
    if (!ctx) return std::fprintf(stderr, "vkcollide_bench_proximity: %s\n", ctx.error().message().c_str()), 1;
    std::ofstream csv(csv_path);
    csv << "device,scene,triangles,edges,d_over_edge,d,frames,detect_ms,gpu_span_ms,footprints_ms,pairing_ms,filtering_ms,proximity_ms,"
           "host_sort_ms,proximity_pairs_pass_ms,proximity_sort_pass_ms,pairs,vertex_triangle,edge_edge,in_band,triangle_pairs,distances,intersecting_pairs,baseline_detect_ms,"
           "baseline_gpu_span_ms,cpu_reference_ms,reference_pairs,missing,added_unflagged\n";
    std::printf("%-11s %8s %5s %9s %9s %9s %9s %9s %9s %9s %9s %10s %8s %9s %8s %8s\n", "scene", "tris", "d/e", "detect", "span", "footpr.",
                "pairing", "filter", "prox", "pass", "sort", "pairs", "in band", "base det.", "cpu ref", "missing");
    for (const std::string& name : split(scenes)) {
        Scene scene = name == "cloth-391k" ? foldedCloth("cloth-391k", 361)
                      : name == "cloth-524k" ? foldedCloth("cloth-524k", 512)
                      : name == "pair"       ? spherePair()
                                             : Scene{};
        if (scene.objects.empty()) return std::fprintf(stderr, "unknown scene %s\n", name.c_str()), 2;
        std::size_t triangles = 0, edge_count = 0;
        for (const Object& o : scene.objects) {
            triangles += o.mesh.indices.size() / 3;
            edge_count += (o.mesh.indices.size() / 3) * 3 / 2;  // closed: each edge twice; open grids slightly more
        }
        for (const std::string& f : split(factors)) {
            const double d = std::atof(f.c_str()) * scene.edge;
            auto world = CollisionWorld::create(**ctx, {.threads = threads});
            if (!world) return std::fprintf(stderr, "%s\n", world.error().message().c_str()), 1;
            std::vector<ObjectId> ids;
            for (const Object& o : scene.objects) ids.push_back(*(*world)->addMesh(o.mesh, {.self_collision = o.self, .open = true}));
            std::vector<HostMesh> shown(scene.objects.size());
            for (std::size_t i = 0; i < shown.size(); ++i) shown[i] = scene.objects[i].mesh;
            auto step = [&](int frame) {
                if (!scene.deforming) return;
                for (std::size_t i = 0; i < ids.size(); ++i) {
                    deform(scene.objects[i].mesh, shown[i], frame, 0.3f * float(scene.edge));
                    (void)(*world)->updateVertices(ids[i], shown[i].positions);
                }
            };
            DetectSettings plain, near;
            near.proximity.distance = d;
            // Warm-up: allocations, pipelines, GPU clocks.
            for (const auto t0 = Clock::now(); msSince(t0) < warmup_ms;) {
                if (!(*world)->detect(near)) break;
            }
            std::vector<double> det, span, fp, pr, fi, px, hs, base_det, base_span, pass_pairs, pass_sort;
            std::map<std::string, std::vector<double>> pass_near, pass_plain;  // --passes
            DetectResult last;
            for (int k = 0; k < frames; ++k) {
                step(k);
                auto b = (*world)->detect(plain);
                if (!b) return std::fprintf(stderr, "%s: %s\n", name.c_str(), b.error().message().c_str()), 1;
                base_det.push_back(b->stats.total_ms);
                base_span.push_back(b->stats.gpu_span_ms);
                for (const PassTime& t : b->stats.gpu_passes) pass_plain[t.name].push_back(t.gpu_ms);
                auto r = (*world)->detect(near);
                if (!r) return std::fprintf(stderr, "%s: %s\n", name.c_str(), r.error().message().c_str()), 1;
                det.push_back(r->stats.total_ms);
                span.push_back(r->stats.gpu_span_ms);
                fp.push_back(r->stats.reliable.footprints_ms);
                pr.push_back(r->stats.reliable.pairing_ms);
                fi.push_back(r->stats.reliable.filtering_ms);
                px.push_back(r->stats.proximity.gpu_ms);
                hs.push_back(r->stats.proximity.host_ms);
                double pairs_ms = 0, sort_ms = 0;
                for (const PassTime& t : r->stats.gpu_passes) {
                    pass_near[t.name].push_back(t.gpu_ms);
                    if (t.name == "proximity-pairs") pairs_ms += t.gpu_ms;
                    if (t.name == "proximity-sort") sort_ms += t.gpu_ms;
                }
                pass_pairs.push_back(pairs_ms);
                pass_sort.push_back(sort_ms);
                last = std::move(*r);
            }
            double ref_ms = 0;
            std::size_t ref_pairs = 0, missing = 0, added = 0;
            if (reference) {
                std::vector<Object> now(scene.objects.size());
                for (std::size_t i = 0; i < now.size(); ++i) now[i] = {shown[i], scene.objects[i].self};
                const auto t0 = Clock::now();
                const auto ref = cpuReference(now, d, std::max(d, scene.edge), threads);
                ref_ms = msSince(t0);
                ref_pairs = ref.size();
                // Objects: ids are 0.. in order in a fresh world.
                for (const RefPair& p : ref) {
                    const auto it = std::lower_bound(last.proximity.begin(), last.proximity.end(), p.key,
                                                     [](const ProximityPair& a, const Key& k) { return keyOf(a) < k; });
                    if (it == last.proximity.end() || !(keyOf(*it) == p.key)) ++missing;
                }
                for (const ProximityPair& q : last.proximity) {
                    const auto it = std::lower_bound(ref.begin(), ref.end(), keyOf(q), [](const RefPair& a, const Key& k) { return a.key < k; });
                    if ((it == ref.end() || !(it->key == keyOf(q))) && !(q.flags & kProximityInBand)) ++added;
                }
            }
            const ProximityStats& ps = last.stats.proximity;
            std::printf("%-11s %8zu %5s %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %10llu %8llu %9.3f %8.1f %8zu\n", name.c_str(), triangles,
                        f.c_str(), median(det), median(span), median(fp), median(pr), median(fi), median(px), median(pass_pairs), median(pass_sort),
                        (unsigned long long)ps.pairs,
                        (unsigned long long)ps.in_band, median(base_det), ref_ms, missing);
            csv << (*ctx)->deviceInfo().name << "," << name << "," << triangles << "," << edge_count << "," << f << "," << d << "," << frames << ","
                << median(det) << "," << median(span) << "," << median(fp) << "," << median(pr) << "," << median(fi) << "," << median(px)
                << "," << median(hs) << "," << median(pass_pairs) << "," << median(pass_sort) << "," << ps.pairs << "," << ps.vertex_triangle << "," << ps.edge_edge << "," << ps.in_band << ","
                << ps.triangle_pairs << "," << ps.distances << "," << last.pairs.size() << "," << median(base_det) << ","
                << median(base_span) << "," << ref_ms << "," << ref_pairs << "," << missing << "," << added << "\n";
            if (passes) {
                std::printf("  %-28s %10s %10s\n", "pass (median ms)", "proximity", "plain");
                for (auto& [pass_name, times] : pass_near)
                    std::printf("  %-28s %10.4f %10.4f\n", pass_name.c_str(), median(times),
                                pass_plain.count(pass_name) ? median(pass_plain[pass_name]) : 0.0);
                std::printf("  candidates %llu, triangle pairs examined %llu, distances %llu\n",
                            (unsigned long long)last.stats.cells.candidates, (unsigned long long)ps.triangle_pairs,
                            (unsigned long long)ps.distances);
            }
            std::fflush(stdout);
        }
    }
    return 0;
}
