// Orientation signs in exact big-integer arithmetic: an evaluation independent of the
// library's predicates (narrow/exact_predicates.hpp), for the tests that check them.
// Compiled in the test support library, at the build's optimisation: the tests' own
// sources compile at -O0 in the sanitized build, where this arithmetic took 20 s a test.
#pragma once

#include "narrow/exact_predicates.hpp"

namespace vkcollide::test {

// The sign of the 3x3 determinant of (b - a, c - a, d - a): +1, -1 or 0, exact for every
// finite float (subnormals included).
int bigOrient3d(const Float3& a, const Float3& b, const Float3& c, const Float3& d);
// The sign of the 2x2 determinant of (b - a, c - a).
int bigOrient2d(const narrow::Float2& a, const narrow::Float2& b, const narrow::Float2& c);

}  // namespace vkcollide::test
