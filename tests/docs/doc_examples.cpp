// The C++ examples of README.md and docs/api.md, compiled: each region between a
// "doc example" line and "end of doc example" is, character for character, a ```cpp block of
// those pages (doc_examples_tests.cpp checks it), so an example that stops compiling fails
// the build. Compiled only, never run: the engine around it is declared, not made.
#include "vkcollide/world.hpp"  // first: the example's own #include is then a no-op

#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace doc_examples {

// What the engine around the examples has.
int log(const std::string& message) {
    std::fprintf(stderr, "%s\n", message.c_str());
    return 1;
}

int readmeUsingIt([[maybe_unused]] const vkcollide::AdoptedDevice& engine_device, [[maybe_unused]] const vkcollide::HostMesh& ball_mesh,
                  [[maybe_unused]] const vkcollide::GpuMeshDesc& cloth_buffers,
                  [[maybe_unused]] const vkcollide::Transform3x4& model_matrix_3x4) {
    // clang-format off
// doc example: README.md
#include <vkcollide/world.hpp>

// Every call returns a [[nodiscard]] Result: test it, read error().message() when it fails.
// The engine's buffers (addGpuMesh) live on the engine's device: vkcollide adopts it
// (context.hpp: AdoptedDevice). With host meshes only, Context::create() makes its own.
auto ctx = vkcollide::Context::adopt(engine_device);
if (!ctx) return log(ctx.error().message());
auto world = vkcollide::CollisionWorld::create(**ctx);
if (!world) return log(world.error().message());
auto ball = (*world)->addMesh(ball_mesh, {.name = "ball"});           // host arrays, uploaded once
auto cloth = (*world)->addGpuMesh(cloth_buffers,                       // the engine's VkBuffers
                                  {.name = "cloth", .self_collision = true, .open = true});
if (!ball || !cloth) return log((ball ? cloth : ball).error().message());
// every frame
if (auto moved = (*world)->setTransform(*ball, model_matrix_3x4); !moved) log(moved.error().message());
auto hits = (*world)->detect();       // or submit() now, collect() later
if (hits)
    for (const vkcollide::TrianglePair& p : hits->pairs)  // (object, triangle) x (object, triangle)
        log("object " + std::to_string(p.object_a) + " hits object " + std::to_string(p.object_b));
// end of doc example
    // clang-format on
    return 0;
}

vkcollide::Result<void> apiDetectInto(std::unique_ptr<vkcollide::CollisionWorld>& world, std::size_t& total_pairs) {
    // clang-format off
// doc example: docs/api.md
// One result kept across frames: no fresh pages once it has grown to the scene.
vkcollide::DetectResult frame_result;
for (int frame = 0; frame < 3; ++frame) {
    if (auto ok = world->detectInto(frame_result); !ok) return ok.error();
    total_pairs += frame_result.pairs.size();
}
// end of doc example
    // clang-format on
    return {};
}

// A cloth solver, as docs/api.md's proximity loop uses it.
struct Solver {
    std::vector<vkcollide::Float3> points;
    void step() {}
    std::span<const vkcollide::Float3> positions() const { return points; }
    void addContact(const vkcollide::ProximityPair&, float) {}
};

int apiProximityLoop(vkcollide::CollisionWorld& world, vkcollide::ObjectId cloth, Solver& solver, float thickness, int frames) {
    // clang-format off
// doc example: docs/api.md
vkcollide::DetectSettings s;
s.proximity.distance = 2 * thickness;                                // world units
for (int frame = 0; frame < frames; ++frame) {
    solver.step();                                                   // positions move
    if (auto ok = world.updateVertices(cloth, solver.positions()); !ok) return log(ok.error().message());
    auto r = world.detect(s);
    if (!r) return log(r.error().message());
    for (const vkcollide::ProximityPair& p : r->proximity)           // or on the GPU: r->device_proximity
        solver.addContact(p, thickness);
    // r->pairs (intersecting) stays empty while the contacts hold
}
// end of doc example
    // clang-format on
    return 0;
}

}  // namespace doc_examples
