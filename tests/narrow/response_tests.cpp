#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "narrow/responses.hpp"
#include "narrow/workspace.hpp"
#include "vkcollide/thread_pool.hpp"

using vkcollide::NarrowResult;
using vkcollide::NarrowWorkspace;
using vkcollide::ThreadPool;
using vkcollide::TriangleResponse;
using vkcollide::narrow::Buffer;
using vkcollide::narrow::ResponseForm;

namespace {

struct ResponseScene {
    Buffer<vkcollide::narrow::SlotTag> tags;
    Buffer<vkcollide::narrow::SlotVertices> vertices;
    Buffer<std::uint64_t> colliding;  // (lower slot << 32) | higher slot, ascending, distinct
    std::size_t slot_count = 0;
};

// Random triangles (every 97th of zero area: no normal) and `pairs` random distinct slot
// pairs. With `hubs`, three slots of zero area in 3000 pairs each, runs longer than a task
// of the parallel loops: slot 1 as the lower end, slot_count - 2 as the higher end, the
// middle slot as either, half and half. The second half of each hub's partners are the
// first half turned over (the opposite normals, to the bit), so a hub's sum nearly cancels
// and the direction of what is left depends on the order of the terms.
ResponseScene makeScene(std::size_t slot_count, std::size_t pairs, std::uint32_t seed, bool hubs) {
    ResponseScene scene;
    scene.slot_count = slot_count;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    scene.tags.resize(slot_count);
    scene.vertices.resize(slot_count);
    for (std::size_t s = 0; s < slot_count; ++s) {
        scene.tags[s] = {static_cast<std::uint32_t>(s / 64), static_cast<std::uint32_t>(s % 64), {0, 1, 2}};
        for (vkcollide::Float3& v : scene.vertices[s].v) v = {coordinate(rng), coordinate(rng), coordinate(rng)};
        if (s % 97 == 0) scene.vertices[s].v[2] = scene.vertices[s].v[1] = scene.vertices[s].v[0];
    }
    const std::size_t middle = slot_count / 2;
    if (hubs) {
        const auto turnOver = [&](std::size_t to, std::size_t from) {
            const vkcollide::Float3* v = scene.vertices[from].v;
            scene.vertices[to] = {{v[0], v[2], v[1]}};
        };
        for (std::size_t i = 0; i < 1500; ++i) {
            turnOver(2 + 1500 + i, 2 + i);
            turnOver(middle + 1 + i, middle - 1500 + i);
            turnOver(slot_count - 1502 + i, slot_count - 3002 + i);
        }
        for (const std::size_t hub : {std::size_t{1}, middle, slot_count - 2}) {
            scene.vertices[hub].v[2] = scene.vertices[hub].v[1] = scene.vertices[hub].v[0];
        }
    }
    std::vector<std::uint64_t> keys;
    std::uniform_int_distribution<std::uint32_t> slot(0, static_cast<std::uint32_t>(slot_count - 1));
    for (std::size_t k = 0; k < pairs; ++k) {
        const std::uint32_t a = slot(rng), b = slot(rng);
        const bool hub = hubs && (a == 1 || b == 1 || a == middle || b == middle || a == slot_count - 2 || b == slot_count - 2);
        if (a != b && !hub) keys.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
    if (hubs) {
        for (std::uint64_t k = 0; k < 3000; ++k) {
            keys.push_back((std::uint64_t{1} << 32) | (2 + k));
            keys.push_back(((slot_count - 3002 + k) << 32) | (slot_count - 2));
        }
        for (std::uint64_t k = 1; k <= 1500; ++k) {
            keys.push_back(((middle - k) << 32) | middle);
            keys.push_back((std::uint64_t{middle} << 32) | (middle + k));
        }
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    scene.colliding.resize(keys.size());
    std::copy(keys.begin(), keys.end(), scene.colliding.begin());
    return scene;
}

struct Normal {
    double x = 0, y = 0, z = 0;
};

Normal unitNormal(const vkcollide::narrow::SlotVertices& t) {
    const vkcollide::Float3* v = t.v;
    const double ux = double(v[1].x) - v[0].x, uy = double(v[1].y) - v[0].y, uz = double(v[1].z) - v[0].z;
    const double vx = double(v[2].x) - v[0].x, vy = double(v[2].y) - v[0].y, vz = double(v[2].z) - v[0].z;
    const Normal n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(length > 0) || !std::isfinite(length)) return {};
    return {n.x / length, n.y / length, n.z / length};
}

// The definition (TriangleResponse): each slot's partners in pair order, terms summed in that order.
std::vector<TriangleResponse> reference(const ResponseScene& scene) {
    std::vector<std::vector<std::uint32_t>> partners(scene.slot_count);
    for (const std::uint64_t key : scene.colliding) {
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        partners[a].push_back(b);
        partners[b].push_back(a);
    }
    std::vector<TriangleResponse> out;
    for (std::size_t s = 0; s < scene.slot_count; ++s) {
        if (partners[s].empty()) continue;
        const Normal n = unitNormal(scene.vertices[s]);
        Normal sum;
        for (const std::uint32_t p : partners[s]) {
            const Normal m = unitNormal(scene.vertices[p]);
            sum.x += m.x - n.x;
            sum.y += m.y - n.y;
            sum.z += m.z - n.z;
        }
        TriangleResponse r{};
        r.object = scene.tags[s].object;
        r.triangle = scene.tags[s].triangle;
        r.partner_count = static_cast<std::uint32_t>(partners[s].size());
        const double length = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
        if (length > 0) r.direction = {float(sum.x / length), float(sum.y / length), float(sum.z / length)};
        out.push_back(r);
    }
    return out;
}

void requireSame(const std::vector<TriangleResponse>& got, const std::vector<TriangleResponse>& expected) {
    REQUIRE(got.size() == expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        const TriangleResponse &g = got[i], &e = expected[i];
        INFO("response " << i);
        REQUIRE((g.object == e.object && g.triangle == e.triangle && g.partner_count == e.partner_count));
        REQUIRE(std::memcmp(&g.direction, &e.direction, sizeof(g.direction)) == 0);
    }
}

}  // namespace

TEST_CASE("Responses: every form equals the definition to the bit on any thread count", "[narrow][response][threads]") {
    // Dense slots with many pairs (Automatic: Serial on one or two threads, Grouped on
    // four), with hub slots whose runs cross task boundaries; sparse slots with few
    // pairs (Automatic: Sorted); few pairs; none. One workspace throughout, so buffers
    // are reused at other sizes.
    const std::vector<ResponseScene> scenes = [] {
        std::vector<ResponseScene> s;
        s.push_back(makeScene(12000, 20000, 1, true));
        s.push_back(makeScene(200000, 3000, 2, false));
        s.push_back(makeScene(500, 700, 3, false));
        s.push_back(makeScene(300, 0, 4, false));
        s.push_back(makeScene(14000, 30000, 5, true));
        return s;
    }();
    REQUIRE(scenes[0].colliding.size() > std::size_t{1} << 13);
    ThreadPool one(1), two(2), four(4);
    NarrowWorkspace workspace;
    for (const ResponseScene& scene : scenes) {
        const std::vector<TriangleResponse> expected = reference(scene);
        const vkcollide::narrow::SlotData slots = vkcollide::narrow::slotView(scene.tags, scene.vertices);
        for (ThreadPool* pool : {&one, &two, &four}) {
            for (const ResponseForm form : {ResponseForm::Automatic, ResponseForm::Serial, ResponseForm::Grouped, ResponseForm::Sorted}) {
                INFO("slots " << scene.slot_count << ", pairs " << scene.colliding.size() << ", threads " << pool->threadCount()
                              << ", form " << static_cast<int>(form));
                NarrowResult result;
                vkcollide::narrow::respond(scene.colliding, slots, scene.slot_count, form, *pool, workspace.impl(), result);
                requireSame(result.responses, expected);
            }
        }
    }
}
