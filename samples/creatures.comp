#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#include "creatures.h"

// Animates the creatures on the GPU: one invocation per vertex writes its position.
// The CPU only sets the parameters (creature centres, tentacle lengths, time) and never
// sees the vertices; vkcollide reads them from the same buffer (addGpuMesh).
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { CreaturesPush pc; };

const float kPi = 3.14159265;

// The tentacle's centre line at u in [0, 1]: from just outside the body (body and
// tentacles are separate closed surfaces that never touch) along its direction, waving
// more towards the tip.
vec3 centreLine(vec3 centre, float radius, Tentacle t, vec3 e1, vec3 e2, float u) {
    float len = t.extent * pc.tentacle_length;
    vec3 p = centre + t.direction * (1.04 * radius + u * len);
    float a = pc.wave * len * u * u;
    p += a * (e1 * sin(2.0 * pc.time + t.phase + 3.0 * u) + 0.6 * e2 * cos(1.3 * pc.time + 1.7 * t.phase + 2.5 * u));
    return p;
}

void main() {
    uint body_vertices = pc.body_segments * (pc.body_rings - 1) + 2;
    uint ring = pc.tube_sides;
    uint tentacle_vertices = (pc.tube_segments + 1) * ring + 2;
    uint per_creature = body_vertices + pc.tentacle_count * tentacle_vertices;
    uint id = gl_GlobalInvocationID.x;
    if (id >= pc.creature_count * per_creature) return;
    uint c = id / per_creature, local = id % per_creature;
    Creature cr = pc.creatures.c[c];
    vec3 p;
    if (local < body_vertices) {
        if (local == 0) {
            p = cr.centre + vec3(0, cr.radius, 0);
        } else if (local == body_vertices - 1) {
            p = cr.centre - vec3(0, cr.radius, 0);
        } else {
            uint r = (local - 1) / pc.body_segments + 1, s = (local - 1) % pc.body_segments;
            float theta = kPi * float(r) / float(pc.body_rings), phi = 2.0 * kPi * float(s) / float(pc.body_segments);
            p = cr.centre + cr.radius * vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
        }
    } else {
        local -= body_vertices;
        uint ti = local / tentacle_vertices, v = local % tentacle_vertices;
        Tentacle t = pc.tentacles.t[c * pc.tentacle_count + ti];
        vec3 e1 = normalize(cross(t.direction, abs(t.direction.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0)));
        vec3 e2 = cross(t.direction, e1);
        float u = v < (pc.tube_segments + 1) * ring ? float(v / ring) / float(pc.tube_segments) : (v == (pc.tube_segments + 1) * ring ? 0.0 : 1.0);
        vec3 line = centreLine(cr.centre, cr.radius, t, e1, e2, u);
        vec3 tangent = normalize(centreLine(cr.centre, cr.radius, t, e1, e2, u + 0.01) - centreLine(cr.centre, cr.radius, t, e1, e2, u - 0.01));
        float tube = pc.tentacle_radius * (1.0 - 0.75 * u);
        if (v < (pc.tube_segments + 1) * ring) {
            // A ring around the centre line; N x B = tangent keeps the winding outward.
            vec3 n = normalize(cross(tangent, e1));
            vec3 b = cross(tangent, n);
            float alpha = 2.0 * kPi * float(v % ring) / float(ring);
            p = line + tube * (cos(alpha) * n + sin(alpha) * b);
        } else if (v == (pc.tube_segments + 1) * ring) {
            p = line;  // the root cap, facing the body
        } else {
            p = line + tangent * tube;  // the rounded tip
        }
    }
    pc.positions.p[id * 3] = p.x;
    pc.positions.p[id * 3 + 1] = p.y;
    pc.positions.p[id * 3 + 2] = p.z;
}
