#version 460
#extension GL_GOOGLE_include_directive : require
// Paper packing, moving: each row's packed run goes to its offset in the dense list.
#include "common/common.glsl.inc"
#include "record.glsl.inc"
layout(local_size_x = kPackRowWidth) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint row = groupIndex();
    uint k = gl_LocalInvocationIndex;
    UintsRef scratch = UintsRef(f.scratch);
    uint rows = f.pack_rows;
    if (row >= rows) return;  // past the last row
    uint count = scratch.v[row];
    if (k >= count) return;
    uint shifted = 2u * rows + rows * kPackRowWidth + row * kPackRowWidth;
    uint column = scratch.v[shifted + kPackRowWidth - count + k];
    writeRecord(f, scratch.v[rows + row] + k, row * kPackRowWidth + column);
}
