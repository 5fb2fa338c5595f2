#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "narrow/neighbours.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "vkcollide/thread_pool.hpp"
#include "narrow/triangle_intersection.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide {
namespace {

// Exact tests per task: large enough to amortise the hand-out, small enough to balance
// (a test costs about 0.1 to 1 microseconds, more when the exact fallback runs).
constexpr std::size_t kTestsPerTask = 512;

std::string describe(const CandidateTriangle& c) {
    return "object " + std::to_string(c.object) + " triangle " + std::to_string(c.triangle);
}

bool isFinite(const Float3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

Result<void> validateCandidates(std::span<const CandidateTriangle> in_candidates) {
    if (in_candidates.size() > std::numeric_limits<std::uint32_t>::max()) {
        return Error(ErrorCode::InvalidArgument, "runNarrowPhase: more than 2^32-1 candidates");
    }
    for (const CandidateTriangle& c : in_candidates) {
        for (const Float3& p : c.v) {
            if (!isFinite(p)) return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + describe(c) + " has a non-finite vertex");
        }
        const bool finite_box = std::isfinite(c.box[0]) && std::isfinite(c.box[1]) && std::isfinite(c.box[2]) &&
                                std::isfinite(c.box[3]) && std::isfinite(c.zmin) && std::isfinite(c.zmax);
        if (!finite_box) return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + describe(c) + " has a non-finite box or depth");
        if (!(c.box[0] <= c.box[2] && c.box[1] <= c.box[3] && c.zmin <= c.zmax)) {
            return Error(ErrorCode::InvalidArgument,
                         "runNarrowPhase: " + describe(c) + " has an empty box (needs x0 <= x1, y0 <= y1, zmin <= zmax)");
        }
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ids;
    ids.reserve(in_candidates.size());
    for (const CandidateTriangle& c : in_candidates) ids.emplace_back(c.object, c.triangle);
    std::sort(ids.begin(), ids.end());
    const auto dup = std::adjacent_find(ids.begin(), ids.end());
    if (dup != ids.end()) {
        return Error(ErrorCode::InvalidArgument, "runNarrowPhase: object " + std::to_string(dup->first) + " triangle " +
                                                     std::to_string(dup->second) + " appears more than once");
    }
    return {};
}

struct Vec3d {
    double x = 0, y = 0, z = 0;
};

Vec3d unitNormal(const CandidateTriangle& c) {
    const double ux = double(c.v[1].x) - c.v[0].x, uy = double(c.v[1].y) - c.v[0].y, uz = double(c.v[1].z) - c.v[0].z;
    const double vx = double(c.v[2].x) - c.v[0].x, vy = double(c.v[2].y) - c.v[0].y, vz = double(c.v[2].z) - c.v[0].z;
    const Vec3d n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(length > 0) || !std::isfinite(length)) return {};  // zero-area (or overflowing) triangle: no normal
    return {n.x / length, n.y / length, n.z / length};
}

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
}

bool keyLess(const CandidateTriangle& a, const CandidateTriangle& b) {
    return a.object != b.object ? a.object < b.object : a.triangle < b.triangle;
}

}  // namespace

Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    ThreadPool& pool) {
    const Clock::time_point t_start = Clock::now();
    if (Result<void> valid = validateCandidates(in_candidates); !valid) return valid.error();

    NarrowResult result;
    NarrowStats& stats = result.stats;
    NarrowTimings& timings = result.timings;
    Clock::time_point t_mark = Clock::now();
    timings.validate_ms = msBetween(t_start, t_mark);
    const auto lap = [&](double& out_ms) {
        const Clock::time_point now = Clock::now();
        out_ms = msBetween(t_mark, now);
        t_mark = now;
    };
    stats.candidates = in_candidates.size();

    // Phase 1 (calling thread): sweep and prune, then the cheap filters. The user's
    // may_collide callback therefore never runs concurrently.
    std::vector<char> potentially_colliding(in_candidates.size(), 0);
    std::vector<narrow::IndexPair> tests;
    narrow::sweepAndPrune(in_candidates, [&](std::uint32_t i, std::uint32_t j) {
        ++stats.sap_pairs;
        potentially_colliding[i] = potentially_colliding[j] = 1;
        const CandidateTriangle& a = in_candidates[i];
        const CandidateTriangle& b = in_candidates[j];
        if (a.object == b.object) {
            if (!options.selfCollides(a.object)) {
                ++stats.filtered_pairs;
                return;
            }
            if (narrow::areNeighbours(a.vertex_index, a.v, b.vertex_index, b.v)) {
                ++stats.neighbour_pairs;
                return;
            }
        } else if (options.may_collide &&
                   !options.may_collide(std::min(a.object, b.object), std::max(a.object, b.object))) {
            ++stats.filtered_pairs;
            return;
        }
        tests.push_back({i, j});
    });
    stats.potentially_colliding_triangles =
        static_cast<std::size_t>(std::count(potentially_colliding.begin(), potentially_colliding.end(), 1));
    stats.triangle_tests = tests.size();
    lap(timings.sweep_ms);

    // Phase 2 (workers): exact tests. Each writes only its own slot, so the outcome does
    // not depend on scheduling.
    std::vector<char> hit(tests.size(), 0);
    pool.parallelFor(tests.size(), kTestsPerTask, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            hit[k] = narrow::trianglesIntersect(in_candidates[tests[k].i].v, in_candidates[tests[k].j].v) ? 1 : 0;
        }
    });
    lap(timings.test_ms);

    // Phase 3: pairs in canonical order.
    std::vector<narrow::IndexPair> colliding;  // (lower key, higher key) candidate indices
    for (std::size_t k = 0; k < tests.size(); ++k) {
        if (!hit[k]) continue;
        narrow::IndexPair p = tests[k];
        if (keyLess(in_candidates[p.j], in_candidates[p.i])) std::swap(p.i, p.j);
        colliding.push_back(p);
    }
    const auto pair_of = [&](const narrow::IndexPair& p) {
        const CandidateTriangle& a = in_candidates[p.i];
        const CandidateTriangle& b = in_candidates[p.j];
        return TrianglePair{a.object, a.triangle, b.object, b.triangle};
    };
    std::sort(colliding.begin(), colliding.end(),
              [&](const narrow::IndexPair& x, const narrow::IndexPair& y) { return pair_of(x) < pair_of(y); });
    result.pairs.reserve(colliding.size());
    for (const narrow::IndexPair& p : colliding) result.pairs.push_back(pair_of(p));
    stats.positive_tests = result.pairs.size();
    lap(timings.sort_ms);

    // Phase 4: responses, summed in the order of the sorted pairs.
    std::vector<Vec3d> sum(in_candidates.size());
    std::vector<std::uint32_t> partners(in_candidates.size(), 0);
    std::vector<Vec3d> normal(in_candidates.size());
    for (const narrow::IndexPair& p : colliding) {
        for (std::uint32_t idx : {p.i, p.j}) {
            if (partners[idx] == 0) normal[idx] = unitNormal(in_candidates[idx]);
        }
        ++partners[p.i];
        ++partners[p.j];
    }
    for (const narrow::IndexPair& p : colliding) {
        const Vec3d &ni = normal[p.i], &nj = normal[p.j];
        sum[p.i].x += nj.x - ni.x; sum[p.i].y += nj.y - ni.y; sum[p.i].z += nj.z - ni.z;
        sum[p.j].x += ni.x - nj.x; sum[p.j].y += ni.y - nj.y; sum[p.j].z += ni.z - nj.z;
    }
    std::vector<std::uint32_t> responders;
    for (std::uint32_t idx = 0; idx < in_candidates.size(); ++idx) {
        if (partners[idx] > 0) responders.push_back(idx);
    }
    std::sort(responders.begin(), responders.end(),
              [&](std::uint32_t x, std::uint32_t y) { return keyLess(in_candidates[x], in_candidates[y]); });
    result.responses.reserve(responders.size());
    for (std::uint32_t idx : responders) {
        const Vec3d& s = sum[idx];
        const double length = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
        TriangleResponse r;
        r.object = in_candidates[idx].object;
        r.triangle = in_candidates[idx].triangle;
        r.partner_count = partners[idx];
        if (length > 0) {
            r.direction = {static_cast<float>(s.x / length), static_cast<float>(s.y / length),
                           static_cast<float>(s.z / length)};
        }
        result.responses.push_back(r);
    }
    lap(timings.response_ms);
    timings.total_ms = msBetween(t_start, t_mark);
    return result;
}

}  // namespace vkcollide
