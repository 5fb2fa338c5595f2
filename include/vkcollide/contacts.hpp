// vkcollide: object-level contacts (DetectSettings::contacts.objects; docs/contacts.md).
//
// For every pair of closed objects whose volumes overlap, what an engine's response needs:
// how much they overlap, along which direction to separate them, how far, and where.
// Estimated on the GPU from parallel rays over the region where the objects' boxes
// overlap: along every ray, the intervals inside both objects (from the depth-sorted hits,
// entering on front faces, leaving on back faces) are the samples of the intersection
// volume. Open objects (ObjectOptions::open) have no inside and get no contact; they keep
// the pair-only contract.
#pragma once

#include <cstdint>

#include "vkcollide/types.hpp"

namespace vkcollide {

// One pair of closed objects whose volumes overlap (or whose triangles intersect).
// World units throughout. Sorted by (object_a, object_b), object_a < object_b.
struct ObjectContact {
    std::uint32_t object_a = 0, object_b = 0;  // ObjectIds, a < b
    // Volume of the intersection: ray spacing^2 x overlap length, summed over the rays.
    // Error: about one ray spacing times the intersection's silhouette perimeter
    // (docs/contacts.md measures it against resolution).
    float volume = 0;
    // Unit contact normal, pointing from object_a into object_b: moving b along +normal
    // (or a along -normal) reduces the overlap fastest. It is the area-weighted normal of
    // the intersection volume's boundary (Faure et al. 2008, Allard et al. 2010): the part
    // of a's surface inside b minus the part of b's surface inside a. Zero when that
    // boundary sums to nothing (`contained`: one object wholly inside the other) or when no
    // ray sampled the overlap (volume 0).
    Float3 normal;
    // Extent of the intersection volume along `normal` (for two spheres r1 + r2 - d);
    // moving b by depth * normal separates the sampled overlap. 0 when normal is zero.
    // Error: up to about one ray spacing.
    float depth = 0;
    // Centroid of the intersection volume (world); with volume 0, the midpoint of the two
    // objects' box overlap.
    Float3 point;
    // The volumes overlap but no triangle of a intersects one of b: one object lies inside
    // the other. With DetectMethod::Peeling a triangle pair the broad phase missed can make
    // a touching pair look contained (the reliable method misses none).
    bool contained = false;
};

// Where two intersecting triangles meet (DetectSettings::contacts.geometry): one per
// DetectResult::pairs entry, at the same index. World units. Open surfaces included.
enum class ContactShape : std::uint8_t {
    Segment,   // the triangles cross (or touch along an edge): start..end is the intersection
    Point,     // they meet in one point (a vertex on a face, two edges crossing): start == end
    Coplanar,  // both lie in one plane and overlap: `area`, start..end the overlap's diameter
};
struct PairContact {
    // The intersection's end points, each coordinate the exact point's coordinate rounded
    // to the nearest float (ties to even): every end is a vertex, an edge of one triangle
    // crossing the other's plane, or (coplanar) an edge crossing an edge, constructed exactly
    // from the float world vertices; the exact test's signs decide the shape. Which points
    // are the ends is chosen on the rounded points, in double (docs/contacts.md). Not exact:
    // two zero-area triangles (segments or points) get their six vertices' centroid.
    Float3 start, end;
    // Unit normal(b) - normal(a), as TriangleResponse sums it: the direction that pushes
    // triangle a out of triangle b. Zero where the two normals are equal (coplanar and
    // facing the same way) or both triangles have zero area.
    Float3 normal;
    float area = 0;  // Coplanar: the overlap polygon's area; 0 otherwise
    ContactShape shape = ContactShape::Point;
};
// Per pair of objects with intersecting triangles, the sum of their pairs' contacts, sorted
// by (object_a, object_b); object_a == object_b for a self-colliding object.
struct ObjectPairContact {
    std::uint32_t object_a = 0, object_b = 0;  // ObjectIds, a <= b
    std::uint32_t pairs = 0;                    // triangle pairs (DetectResult::pairs) between them
    float length = 0;                           // total length of the Segment contacts: the intersection curve
    float area = 0;                             // total area of the Coplanar contacts
    Float3 normal;                              // unit sum of the pairs' normals, each pair once (zero when they sum to 0)
};

}  // namespace vkcollide
