// The scenes where image-space detection or floating-point triangle tests are known to
// fail, each small enough for lavapipe, and the runner that measures a
// detection against the exact CPU reference. Shared by tests/stability and
// tools/stability/stability_report (which prints the numbers docs/stability.md quotes).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "support/exact_reference.hpp"
#include "support/test_scenes.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {

// Most cases sample this box at this resolution, so the pixel grid is known exactly:
// pixel corners at -1.5 + k * 3/64 (0 and +-0.75 are corners), centres between them.
inline constexpr float kRegionHalf = 1.5f;
inline constexpr std::uint32_t kCaseResolution = 64;
inline constexpr float kPixel = 2 * kRegionHalf / kCaseResolution;  // world size of a pixel

// One edge case: a scene, the settings the paper's method (DetectMethod::Peeling) would use on it, and the
// reference pairs it is measured against (usually the scene's own; the far-from-origin
// case measures against the same geometry placed at the origin).
struct StabilityCase {
    std::string name;
    TestScene scene;
    DetectSettings settings;
    std::vector<TrianglePair> reference;
    float pixel = kPixel;  // world size of one pixel under `settings` (for epsilons in pixels)
};

// Builders; each fails only if a generator does.
Result<StabilityCase> subPixelTriangles();        // a sphere 0.3 px in radius on a box face
Result<StabilityCase> edgeOnOverlap();            // boxes overlapping by 0.2 px, the overlap seen edge-on
Result<StabilityCase> coplanarOpenQuads(bool edge_on);  // two overlapping open quads in one plane
Result<StabilityCase> edgeEdgeTouch();            // two tetrahedra whose edges cross in one point
Result<StabilityCase> vertexFaceTouch();          // a tetrahedron standing on its apex on a box face
Result<StabilityCase> needleSliver();             // a needle 0.4 px thick through a box face
Result<StabilityCase> zeroAreaTriangle();         // a degenerate triangle (a segment) through a box face
Result<StabilityCase> deepStack(std::uint32_t layer_cap);  // 4 plates (8 layers) and a sphere through the top one
Result<StabilityCase> nestedSpheres();            // a sphere inside another, surfaces apart
Result<StabilityCase> invertedSphere();           // two overlapping spheres, one wound inside out
Result<StabilityCase> openClothAsClosed(bool declared_open);  // a cloth through a sphere, open flag on or off
Result<StabilityCase> nonManifoldFin();           // a box with a fin on one edge (3 triangles per edge), a sphere through both
Result<StabilityCase> farFromOrigin(float distance);  // 1e-3 features at `distance`, against the same at 0
Result<StabilityCase> thinWall(bool with_sphere); // a closed wall 2e-8 thick, a sphere through it
Result<StabilityCase> farObject(bool with_region);  // overlapping spheres and a box 1000 units away
Result<StabilityCase> exactlyTouching(bool face_on);  // two boxes sharing a face plane

// Every case under its base settings, for the report tool.
Result<std::vector<StabilityCase>> allStabilityCases();

struct Measured {
    PairComparison cmp;
    DetectStats stats;
    std::size_t reference = 0;
    std::vector<ExcludedObject> excluded;
};

// Adds the scene's objects to a fresh world on `context`, detects `runs` times with
// `settings`, compares the last run; stats.total_ms is the fastest run after the first
// (which also creates pipelines and buffers).
Result<Measured> measureCase(Context& context, const StabilityCase& c, const DetectSettings& settings, int runs = 1);
// The same for scene and reference given apart.
Result<Measured> measureScene(Context& context, const TestScene& scene, const std::vector<TrianglePair>& reference,
                              const DetectSettings& settings, int runs = 1);

// One line: case, variant, recall (found of reference), precision, collision rays,
// triangles downloaded, exact tests, host wall time, sampling backend.
std::string describe(const std::string& case_name, const std::string& variant, const Measured& m);

// The variants every case is measured under: the paper, then each mitigation alone, then all
// (all with the paper's separation: DetectSettings::peeling.depth_aware off).
struct Variant {
    std::string name;
    std::function<void(DetectSettings&, const StabilityCase&)> apply;
};
std::vector<Variant> mitigationVariants();
// The reliable method on the case's grid (its resolution as cells per side, direction and
// region), then with every setting automatic.
std::vector<Variant> reliableVariants();

}  // namespace vkcollide::test
