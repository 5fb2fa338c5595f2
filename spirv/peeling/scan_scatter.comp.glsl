#version 460
#extension GL_GOOGLE_include_directive : require
// Scan compaction, step 3: each block scans its survivors in shared memory and writes
// them at its offset (from scan_counts), keeping triangle order.
#include "common/common.glsl.inc"
#include "record.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint t = globalIndex();
    bool keep = t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t]);
    uint inclusive = groupInclusiveScan(keep ? 1u : 0u);
    if (!keep) return;
    uint offset = UintsRef(f.scratch).v[f.pack_blocks + groupIndex()];
    writeRecord(f, offset + inclusive - 1u, t);
}
