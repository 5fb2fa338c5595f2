// Generated scenes shared by the API tests, the recall guard and the tools: overlapping
// spheres, a torus threaded on a box, a self-intersecting twisted tube, a cloth falling
// through a sphere. Each object is a mesh in its own space plus a world transform.
#pragma once

#include <string>
#include <vector>

#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"
#include "support/exact_reference.hpp"

namespace vkcollide::test {

struct SceneObject {
    HostMesh mesh;
    ObjectOptions options;
};

struct TestScene {
    std::string name;
    std::vector<SceneObject> objects;

    // The same objects for computeReferencePairs (pointers into this scene).
    std::vector<ReferenceObject> reference() const;
};

// Appends `mesh` with `options`, or returns the generator's error.
Result<void> addObject(TestScene& s, Result<HostMesh> mesh, ObjectOptions options);

// `detail` scales the tessellation (1: a few thousand triangles per scene).
Result<TestScene> overlappingSpheres(float detail = 1.0f);
Result<TestScene> torusThroughBox(float detail = 1.0f);
Result<TestScene> selfIntersectingTube(float detail = 1.0f);
Result<TestScene> clothThroughSphere(float detail = 1.0f);
Result<std::vector<TestScene>> allTestScenes(float detail = 1.0f);
// Three copies of one open cells x cells grid in one plane: every triangle touches about a
// dozen of the other copies' (40 cells: more pairs than a first run's survivor capacity,
// so the reliable method runs again). Not in allTestScenes.
Result<TestScene> coincidentGrids(std::uint32_t cells);
// `n` coplanar equilateral triangles about one centre near (2.5, 0, 0), each turned a little
// further, each with its own vertices: every two overlap, n (n - 1) / 2 pairs where the
// object tests itself, every triangle with n - 1 partners.
HostMesh coplanarFan(std::uint32_t n);
// One large triangle in the plane z = 0 and `teeth` small triangles of another object, each
// crossing it: `teeth` pairs, one triangle with all of them as partners.
TestScene combScene(std::uint32_t teeth);

Transform3x4 rotationY(float angle, Float3 translation);

}  // namespace vkcollide::test
