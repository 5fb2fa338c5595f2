// Contact points rounded from their exact construction (docs/contacts.md, "Where two
// triangles meet"). Every point a pair contact reports is an input vertex, an edge of one
// triangle crossing the other's plane, or (coplanar triangles) an edge of one crossing an
// edge's line of the other. pair_contacts.cpp rounds the candidate points it needs here:
// each coordinate the exact rational value rounded to the nearest float, ties to even.
#pragma once

#include <array>
#include <cstdint>

#include "narrow/expansion.hpp"
#include "vkcollide/mesh.hpp"

namespace vkcollide::contacts {

struct ExactPoint {
    enum class Kind : std::uint8_t {
        // p itself.
        Vertex,
        // Edge p..q crossing the plane through a, b, c (p, q strictly on opposite sides).
        PlaneCrossing,
        // Edge p..q crossing the line a..b, all in one plane; orientations taken in the two
        // coordinates other than `drop` (p, q strictly on opposite sides).
        LineCrossing,
    };
    Kind kind = Kind::Vertex;
    std::uint8_t drop = 0;
    Float3 p, q, a, b, c;
};

// The point, each coordinate correctly rounded from its exact value.
Float3 roundExact(const ExactPoint& point) noexcept;

// The PlaneCrossing point of edge p..q and `plane`, given the filter's determinants of p and
// q against it (narrow::orient3dEstimate: value and error bound), which the caller has
// already computed for the signs.
Float3 roundPlaneCrossing(const Float3& p, const Float3& q, const std::array<Float3, 3>& plane, double d_p, double e_p, double d_q,
                          double e_q) noexcept;

// numerator / denominator (denominator != 0, of sign denominator_sign) rounded to the nearest
// float, ties to even. Both operands are compressed in place (same values). Their components
// must be multiples of 2^-600 below 2^600 in magnitude, as the constructions' are, so that
// every product with a float midpoint is exact. Exposed for tests.
float roundQuotient(narrow::exact::Expansion<256>& io_numerator, narrow::exact::Expansion<128>& io_denominator,
                    int denominator_sign) noexcept;

}  // namespace vkcollide::contacts
