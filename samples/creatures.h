// Layouts shared by the creatures sample (C++) and its compute shader (GLSL, scalar).
#ifndef SAMPLES_CREATURES_H
#define SAMPLES_CREATURES_H

#ifdef __cplusplus
#include <cstdint>
namespace samples::gpu {
using uint = std::uint32_t;
struct vec3 { float x, y, z; };
#define CREATURES_REF(type) std::uint64_t
#else
#define CREATURES_REF(type) type
#endif

// One creature: a spherical body with `tentacle_count` tentacles.
struct Creature {
    vec3 centre;
    float radius;
};

// One tentacle: where it leaves the body, its wave phase and its current length as a
// share of the full length (the CPU shortens it after a collision: it retracts).
struct Tentacle {
    vec3 direction;  // unit, from the body centre
    float phase;
    float extent;    // (0, 1]: the share of the full length it has now
};

#ifndef __cplusplus
layout(buffer_reference, scalar) writeonly buffer Positions { float p[]; };
layout(buffer_reference, scalar) readonly buffer Creatures { Creature c[]; };
layout(buffer_reference, scalar) readonly buffer Tentacles { Tentacle t[]; };
#endif

// Vertex layout of one creature (the CPU builds the matching index buffer):
//   body: north pole, (body_rings - 1) rings of body_segments, south pole (y up);
//   then per tentacle: (tube_segments + 1) rings of tube_sides from root to tip, the
//   root cap's centre, the tip's point. A tentacle starts just outside the body.
struct CreaturesPush {
    CREATURES_REF(Positions) positions;   // x, y, z floats, 3 per vertex, creature after creature
    CREATURES_REF(Creatures) creatures;
    CREATURES_REF(Tentacles) tentacles;   // tentacle_count per creature
    uint creature_count, tentacle_count;
    uint body_segments, body_rings, tube_segments, tube_sides;
    float time, tentacle_length, tentacle_radius, wave;
};

#ifdef __cplusplus
}  // namespace samples::gpu
#endif

#endif
