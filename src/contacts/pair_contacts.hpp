// Contact geometry of intersecting triangle pairs (DetectSettings::contacts.geometry): where
// two triangles meet — a segment, a point or a coplanar overlap — and a normal, and the sums
// per pair of objects (vkcollide/contacts.hpp). Host only: it runs after the narrow phase
// over the pairs it found.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <vector>

#include "vkcollide/contacts.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::contacts {

// Where the closed triangles a and b meet; they must intersect (trianglesIntersect: then the
// shape is exact). A pair that does not gives a Point at the midpoint of their closest
// vertices' centroids — never read as a contact.
PairContact pairContact(const std::array<Float3, 3>& a, const std::array<Float3, 3>& b) noexcept;

// One contact per pair (same order) and the per-object-pair sums, in parallel; the same for
// every thread count (sums in double over fixed chunks, merged in order). `triangle(object,
// triangle)` gives a triangle's world vertices.
using TriangleLookup = std::function<std::array<Float3, 3>(std::uint32_t object, std::uint32_t triangle)>;
void pairContacts(std::span<const TrianglePair> pairs, const TriangleLookup& triangle, Executor& executor,
                  std::vector<PairContact>& out_contacts, std::vector<ObjectPairContact>& out_totals);

}  // namespace vkcollide::contacts
