// The cloth sample's --ball mode (cloth_ball.cpp): a ball thrown onto a cloth pinned at
// its edges, both driven by proximity pairs.
#pragma once

#include <cstdint>

#include "common/options.hpp"

namespace samples {

struct BallScene {
    std::uint32_t cells = 32;     // cloth quads per side
    float size = 2.6f;            // cloth side; the border is pinned at y = 0
    float radius = 0.35f;         // the ball's
    float drop = 0.2f;            // the ball's lowest point above the cloth at the start
    float speed = 3;              // thrown straight down at this speed, m/s
    float ball_mass = 1, cloth_mass = 0.5f;  // kg
    std::uint32_t substeps = 4;
    float dt = 0.005f;            // simulated seconds per frame (one detection per frame)
};

// Runs the scene for common.frames frames; the program's exit status (1 when a frame had
// an intersecting pair, 3 on validation messages).
int runBall(CommonOptions& common, const BallScene& scene);

}  // namespace samples
