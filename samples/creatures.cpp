// GPU objects (paper section 8, Figure 9): creatures with a spherical body and waving
// tentacles, animated by a compute shader (creatures.comp), about 320K triangles; rigid
// ships fly through. A tentacle that touches another creature or a ship retracts and
// grows again.
//
// What it shows: geometry that exists only on the GPU. The engine's compute shader writes
// the vertices into its own buffer every frame and addGpuMesh registers that buffer: the
// CPU never holds those vertices. From a detection it needs only the pairs: a creature's
// triangle index says which tentacle was hit (the engine built the index buffer, so it
// knows the topology), and the CPU answers by changing shader parameters (the tentacle's
// length). The ships are host meshes moved by setTransform and deflected by their
// response vectors.
//
//   vkcollide_creatures [--frames 240] [--creatures 16] [--tentacles 16] [--out creatures] (--help)
#include "render/vk.hpp"  // first: the samples call Vulkan themselves

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "common/lent_device.hpp"
#include "common/options.hpp"
#include "common/physics.hpp"
#include "common/picture.hpp"
#include "common/render.hpp"
#include "creatures.h"
#include "creatures_comp.h"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace samples;

namespace {

// The index buffer of one creature, matching the vertex layout the shader writes
// (creatures.h): the topology is the engine's own, only the positions live on the GPU.
std::vector<std::uint32_t> creatureIndices(const gpu::CreaturesPush& l) {
    std::vector<std::uint32_t> out;
    auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { out.insert(out.end(), {a, b, c}); };
    const std::uint32_t bs = l.body_segments, br = l.body_rings;
    const std::uint32_t body_vertices = bs * (br - 1) + 2, south = body_vertices - 1;
    auto ring = [&](std::uint32_t r, std::uint32_t s) { return 1 + (r - 1) * bs + s % bs; };
    for (std::uint32_t s = 0; s < bs; ++s) tri(0, ring(1, s + 1), ring(1, s));  // counter-clockwise from outside
    for (std::uint32_t r = 1; r + 1 < br; ++r)
        for (std::uint32_t s = 0; s < bs; ++s) {
            tri(ring(r, s), ring(r, s + 1), ring(r + 1, s));
            tri(ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s));
        }
    for (std::uint32_t s = 0; s < bs; ++s) tri(south, ring(br - 1, s), ring(br - 1, s + 1));
    const std::uint32_t k = l.tube_sides, segs = l.tube_segments, per_tentacle = (segs + 1) * k + 2;
    for (std::uint32_t t = 0; t < l.tentacle_count; ++t) {
        const std::uint32_t base = body_vertices + t * per_tentacle;
        auto at = [&](std::uint32_t u, std::uint32_t i) { return base + u * k + i % k; };
        for (std::uint32_t u = 0; u < segs; ++u)
            for (std::uint32_t i = 0; i < k; ++i) {
                tri(at(u, i), at(u, i + 1), at(u + 1, i));
                tri(at(u, i + 1), at(u + 1, i + 1), at(u + 1, i));
            }
        const std::uint32_t root = base + (segs + 1) * k, tip = root + 1;
        for (std::uint32_t i = 0; i < k; ++i) {
            tri(root, at(0, i + 1), at(0, i));
            tri(tip, at(segs, i), at(segs, i + 1));
        }
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    CommonOptions common;
    common.frames = 240;
    // 16 creatures x (960 body + 16 tentacles x 1,176) = 316K triangles, plus the ships.
    std::uint32_t creatures = 16, tentacles = 16, segments = 48, sides = 12, ships = 3;
    float spacing = 3.0f;  // between creature centres; a tentacle reaches about 2.1
    float dt = 1.0f / 60.0f;
    Args args("vkcollide_creatures", "GPU-animated creatures and rigid ships (paper section 8, Figure 9)");
    args.option("creatures", creatures, "number of creatures (on a square grid)");
    args.option("tentacles", tentacles, "tentacles per creature");
    args.option("segments", segments, "rings along a tentacle");
    args.option("sides", sides, "vertices around a tentacle");
    args.option("ships", ships, "number of ships");
    args.option("spacing", spacing, "distance between neighbouring creatures");
    args.option("dt", dt, "simulated seconds per frame");
    addCommonOptions(args, common);
    args.parse(argc, argv);
    finishCommonOptions(args, common, "creatures");
    if (creatures < 1 || tentacles < 1 || segments < 2 || sides < 3) die("needs --creatures >= 1, --tentacles >= 1, --segments >= 2, --sides >= 3");

    // The engine's device, lent to vkcollide.
    LentDevice lent;
    if (int status = lendDevice(common, lent)) return status;
    auto& [engine, context, world] = lent;
    Renderer renderer(*engine, common.width, common.height);

    // --- The engine's GPU geometry: parameters the CPU writes, vertices the GPU writes. ---
    constexpr float kBodyRadius = 0.5f, kTentacleLength = 1.4f, kTentacleRadius = 0.07f;
    gpu::CreaturesPush push{};
    push.creature_count = creatures;
    push.tentacle_count = tentacles;
    push.body_segments = 32;
    push.body_rings = 16;
    push.tube_segments = segments;
    push.tube_sides = sides;
    push.tentacle_length = kTentacleLength;
    push.tentacle_radius = kTentacleRadius;
    push.wave = 0.45f;
    const std::uint32_t body_vertices = push.body_segments * (push.body_rings - 1) + 2;
    const std::uint32_t vertices = body_vertices + tentacles * ((segments + 1) * sides + 2);
    const std::vector<std::uint32_t> indices = creatureIndices(push);
    const auto triangles = static_cast<std::uint32_t>(indices.size() / 3);
    const std::uint32_t body_triangles = 2 * push.body_segments * (push.body_rings - 1);
    const std::uint32_t tentacle_triangles = (triangles - body_triangles) / tentacles;

    Buffer positions = engine->createBuffer(VkDeviceSize{creatures} * vertices * 12, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Device);
    Buffer index_buffer = engine->createBuffer(indices.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Device);
    engine->upload(index_buffer, indices.data(), indices.size() * 4);
    Buffer creature_params = engine->createBuffer(creatures * sizeof(gpu::Creature), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
    Buffer tentacle_params = engine->createBuffer(VkDeviceSize{creatures} * tentacles * sizeof(gpu::Tentacle),
                                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Host);
    push.positions = positions.address;
    push.creatures = creature_params.address;
    push.tentacles = tentacle_params.address;
    Engine::ComputePipeline animate = engine->createComputePipeline(kCreaturesComp, sizeof(push));

    // Creatures on a square grid; tentacle roots spread evenly over each body.
    const auto columns = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(creatures))));
    std::vector<Vec3> homes;
    auto* tentacle = static_cast<gpu::Tentacle*>(tentacle_params.mapped);
    for (std::uint32_t c = 0; c < creatures; ++c) {
        homes.emplace_back((float(c % columns) - float(columns - 1) / 2) * spacing, 0.0f,
                           (float(c / columns) - float(columns - 1) / 2) * spacing);
        for (std::uint32_t t = 0; t < tentacles; ++t) {
            const float y = 1.0f - 2.0f * (float(t) + 0.5f) / float(tentacles), r = std::sqrt(1 - y * y);
            const float a = 2.39996323f * float(t) + float(c);  // golden angle
            tentacle[c * tentacles + t] = {{r * std::cos(a), y, r * std::sin(a)}, float(c * 7 + t), 1.0f};
        }
    }

    // Each creature is one object on the GPU buffers: its slice of the vertex buffer and
    // the shared index buffer (indices are local to a creature).
    std::vector<ObjectId> creature_ids;
    std::vector<DrawId> creature_draws;
    for (std::uint32_t c = 0; c < creatures; ++c) {
        GpuMeshDesc desc;
        desc.vertex_buffer = positions.buffer;
        desc.vertex_buffer_size = positions.size;
        desc.vertex_offset = VkDeviceSize{c} * vertices * 12;
        desc.vertex_stride = 12;
        desc.vertex_count = vertices;
        desc.index_buffer = index_buffer.buffer;
        desc.index_buffer_size = index_buffer.size;
        desc.index_count = static_cast<std::uint32_t>(indices.size());
        const float edge = 2 * 3.14159265f * kTentacleRadius / float(sides);
        auto id = world->addGpuMesh(desc, {.name = "creature " + std::to_string(c), .typical_edge_length = edge});
        if (!id) return fail(id.error());
        creature_ids.push_back(*id);
        creature_draws.push_back(renderer.addGpuMesh(positions, desc.vertex_offset, 12, index_buffer, 0, triangles, objectColour(c % 5)));
    }

    // The ships: rigid host meshes that fly across the field, between rows of creatures.
    auto hull = uvSphere(1.0f, 24, 12);
    if (!hull) return fail(hull.error());
    for (Float3& p : hull->positions) p = {p.x * 0.8f, p.y * 0.18f, p.z * 0.3f};
    const float field = float(columns) * spacing;
    struct Ship {
        RigidBody body;
        ObjectId id;
        DrawId draw;
    };
    std::vector<Ship> fleet;
    for (std::uint32_t s = 0; s < ships; ++s) {
        Ship ship;
        ship.body.position = Vec3(-field / 2 - 1.0f - 2.0f * float(s), 0.4f * float(s % 3) - 0.4f,
                                  (float(s % columns) - float(columns) / 2 + 1.0f) * spacing - spacing / 2);
        ship.body.velocity = Vec3(1.6f, 0, 0);
        auto id = world->addMesh(*hull, {.name = "ship " + std::to_string(s), .transform = ship.body.transform()});
        if (!id) return fail(id.error());
        ship.id = *id;
        ship.draw = renderer.addMesh(*hull, {0.92f, 0.92f, 0.95f});
        fleet.push_back(ship);
    }
    std::printf("scene: %zu triangles (%u creatures x %u, %u ships)\n", world->triangleCount(), creatures, triangles, ships);
    Picture picture(renderer, common, "creatures",
                    Camera{.eye = {0.3f * field, 0.6f * field + 1.0f, 0.8f * field + 2.0f}, .target = {0, -0.3f, 0}}, 1.2f);

    // Per tentacle: retracting after a hit, or growing back.
    std::vector<bool> retracting(std::size_t{creatures} * tentacles, false);
    // vkcollide measures host meshes itself but knows nothing of where GPU vertices are:
    // the engine does, so it says which box to sample (creatures and the ships' paths).
    // That box also sets the automatic resolution.
    DetectSettings settings = common.detectSettings();
    const float reach = kBodyRadius * 1.04f + kTentacleLength + kTentacleRadius + 0.3f;
    settings.region = std::array<float, 6>{-field / 2 - 3.0f, -reach - 1.0f, -field / 2 - reach, field / 2 + 3.0f, reach + 1.0f, field / 2 + reach};
    // The detection's pipelines compiled at load time, not inside the first frame's detect()
    // (where its timeout cannot bound them).
    auto prepared = world->preparePipelines(settings);
    if (!prepared) return fail(prepared.error());
    std::printf("pipelines: %u compiled at load in %.0f ms\n", prepared->created, prepared->ms);
    FrameLog log(common.out + "/frames.csv", {"tentacle_pairs", "ship_pairs", "retracting", "new_retractions", "shortest_tentacle"},
                 common.frames, common.quiet);
    for (int frame = 0; frame < common.frames; ++frame) {
        const auto sim_start = std::chrono::steady_clock::now();
        // Shader parameters: the bodies bob, tentacles retract or grow.
        push.time = float(frame) * dt;
        auto* body = static_cast<gpu::Creature*>(creature_params.mapped);
        for (std::uint32_t c = 0; c < creatures; ++c) {
            const Vec3 at = homes[c] + Vec3(0, 0.25f * std::sin(0.7f * push.time + float(c)), 0);
            body[c] = {{at.x(), at.y(), at.z()}, kBodyRadius};
        }
        float shortest = 1.0f;
        int retracting_now = 0;
        for (std::size_t t = 0; t < retracting.size(); ++t) {
            float& extent = tentacle[t].extent;
            if (retracting[t]) {
                extent = std::max(0.12f, extent - 2.5f * dt);
                if (extent <= 0.12f) retracting[t] = false;  // fully in: grow again
            } else {
                extent = std::min(1.0f, extent + 0.35f * dt);
            }
            shortest = std::min(shortest, extent);
            retracting_now += retracting[t];
        }
        // The GPU animates the vertices (before the detection reads them, same queue).
        engine->submit([&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, animate.pipeline);
            vkCmdPushConstants(cmd, animate.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, (creatures * vertices + 63) / 64, 1, 1);
        });
        for (Ship& s : fleet) {
            s.body.integrate(dt, Vec3::Zero(), 0.0f);
            if (s.body.position.x() > field / 2 + 2.0f) s.body.position.x() = -field / 2 - 2.0f;  // round again
            if (auto ok = world->setTransform(s.id, s.body.transform()); !ok) return fail(ok.error());
            renderer.setTransform(s.draw, s.body.transform());
        }
        double sim_ms = msSince(sim_start);

        auto hits = world->detect(settings);
        if (!hits) return fail(hits.error());

        // What was hit: a tentacle (from the triangle index) retracts; a ship turns away
        // along its response vectors.
        const auto response_start = std::chrono::steady_clock::now();
        auto creatureOf = [&](ObjectId id) -> int {
            auto it = std::find(creature_ids.begin(), creature_ids.end(), id);
            return it == creature_ids.end() ? -1 : int(it - creature_ids.begin());
        };
        int tentacle_pairs = 0, ship_pairs = 0, new_retractions = 0;
        renderer.clearHighlights();
        for (const TrianglePair& p : hits->pairs) {
            bool tentacle_hit = false, ship_hit = false;
            for (auto [object, triangle] : {std::pair{p.object_a, p.triangle_a}, std::pair{p.object_b, p.triangle_b}}) {
                const int c = creatureOf(object);
                if (c < 0) {
                    for (const Ship& s : fleet)
                        if (s.id == object) renderer.highlight(s.draw, triangle);
                    ship_hit = true;
                    continue;
                }
                renderer.highlight(creature_draws[c], triangle);
                if (triangle < body_triangles) continue;
                tentacle_hit = true;
                const std::size_t t = std::size_t(c) * tentacles + (triangle - body_triangles) / tentacle_triangles;
                if (!retracting[t] && tentacle[t].extent > 0.5f) {
                    retracting[t] = true;
                    ++new_retractions;
                }
            }
            tentacle_pairs += tentacle_hit;
            ship_pairs += ship_hit;
        }
        for (Ship& s : fleet) {
            Vec3 away = Vec3::Zero();
            for (const TriangleResponse& r : hits->responses)
                if (r.object == s.id) away += toVec(r.direction);
            if (away.norm() > 0) {
                const float speed = s.body.velocity.norm();
                s.body.velocity = (s.body.velocity + 0.3f * away.normalized()).normalized() * speed;
            }
            s.body.velocity.y() *= 0.98f;  // level off again
        }
        sim_ms += msSince(response_start);

        const auto render_start = std::chrono::steady_clock::now();
        picture.write(frame, *hits,
                      std::to_string(retracting_now) + " tentacles retracting, " + std::to_string(ship_pairs) + " ship pairs");
        const double values[] = {double(tentacle_pairs), double(ship_pairs), double(retracting_now), double(new_retractions),
                                 double(shortest)};
        log.record(frame, *hits, values, sim_ms, msSince(render_start));
    }
    log.finish("creatures");
    engine->destroy(animate);
    for (Buffer* b : {&positions, &index_buffer, &creature_params, &tentacle_params}) engine->destroy(*b);
    return exitStatus(*engine);
}
