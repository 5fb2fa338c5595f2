// The scene tests' view of a generated mesh: its statistics, required to be computable.
#pragma once

#include <catch2/catch.hpp>

#include <numbers>

#include "vkcollide/scene.hpp"

namespace vkcollide::test {

inline constexpr double kPi = std::numbers::pi;

inline MeshStats statsOf(const HostMesh& mesh) {
    const Result<MeshStats> stats = computeMeshStats(mesh);
    REQUIRE(stats);
    return *stats;
}

}  // namespace vkcollide::test
