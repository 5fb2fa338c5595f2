// Scenes an adversary would feed the GPU passes: one triangle repeated past the
// deepest peeled ray, a face of many repeated corners, a contact under thousands of thin
// slabs, many mutually crossing triangles, many objects, coordinates at the ends of the
// float range. Shared by tests/stability/pathological_tests.cpp (small sizes, CI) and
// tools/stability/pathological_report.cpp (the sizes docs/stability.md quotes).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "support/test_scenes.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {

// A scene, the settings it is run with, and the exact pairs where they are known. The
// cases stress the peeling method's passes (fragment counts, peeling depth, backends), so
// their settings name it.
struct PathologicalCase {
    std::string name;
    TestScene scene;
    DetectSettings settings{.method = DetectMethod::Peeling};
    std::optional<std::vector<TrianglePair>> reference;
};

// `copies` copies of one triangle (indices 0 1 2 repeated: neighbours of each other) in
// object 0, self-collision on, and a triangle that crosses it (object 1): the pairs are
// exactly (copy k, the crossing triangle) for every k. Every ray through the copies has
// `copies` fragments.
Result<PathologicalCase> repeatedTriangle(std::uint32_t copies);

// `copies` copies of one triangle in object 0, each with its own three vertices (bit-
// identical positions: neighbours of each other under the narrow phase's rule, so no
// pair among them), self-collision on, and the triangle of repeatedTriangle crossing
// them (object 1): the pairs are (copy k, the crossing triangle). Every cell the copies
// cover holds all of them, so each of their k (k - 1) / 2 overlapping pairs repeats in
// every such cell unless the sweep drops the repeats.
Result<PathologicalCase> copiesWithOwnVertices(std::uint32_t copies);

// The OBJ text of three vertices and one face of `corners` corners cycling through them
// ("f 1 2 3 1 2 3 ..."): the reader fans it into corners - 2 triangles, a third of them
// copies of (1 2 3) and the rest zero-area, all in one place. No pair can collide (every
// triangle shares its corners with every other).
std::string repeatedCornerFace(std::uint32_t corners);

// Two overlapping tetrahedra (object 0 and 1) under `slabs` thin closed slabs stacked along
// the direction (object 2, 12 triangles each), sampled in a fixed region at 16 rays: every
// ray through the contact crosses 2 * slabs + 4 or more surfaces. Reference: the
// tetrahedra's pairs (the slabs touch nothing); without `with_reference` none (computing
// it takes seconds for tens of thousands of slabs).
Result<PathologicalCase> slabsOverContact(std::uint32_t slabs, bool with_reference = true);

// `count` triangles in one self-colliding object, each in its own plane through the z axis
// and each containing a piece of that axis from the origin up: every two intersect, so
// there are count * (count - 1) / 2 pairs (not listed in `reference` above 2,000).
Result<PathologicalCase> crossingTriangles(std::uint32_t count);

// `count` tetrahedra, one object each, on a grid where each overlaps its +x neighbour.
Result<PathologicalCase> manyObjects(std::uint32_t count);

// Two triangles that cross each other (one pair), as two host meshes whose coordinates are
// scaled by `scale`; reference: that pair.
Result<PathologicalCase> scaledCrossing(float scale);

}  // namespace vkcollide::test
