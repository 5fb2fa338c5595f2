#version 460
#extension GL_GOOGLE_include_directive : require
// Paper packing, shifting, one invocation per row. Sweep left to right storing in each
// texel the column of the preceding non-empty texel (a next-pointer list, gather form);
// then sweep right to left for M steps, following the pointers, so the row's non-empty
// texels end up packed against its right end, in order.
#include "common/common.glsl.inc"
layout(local_size_x = 64) in;
#include "common/dispatch.glsl.inc"

const uint kNone = 0xFFFFFFFFu;

void main() {
    Frame f = frame();
    uint row = globalIndex();
    if (row >= f.pack_rows) return;
    UintsRef scratch = UintsRef(f.scratch);
    uint rows = f.pack_rows;
    uint pointers = 2u * rows + row * kPackRowWidth;
    uint shifted = 2u * rows + rows * kPackRowWidth + row * kPackRowWidth;
    Vec4sRef sparse = Vec4sRef(f.sparse);
    uint preceding = kNone;
    for (uint c = 0u; c < kPackRowWidth; ++c) {
        scratch.v[pointers + c] = preceding;
        uint t = row * kPackRowWidth + c;
        if (t < f.triangle_count && !boxEmpty(sparse.v[t])) preceding = c;
    }
    uint last = row * kPackRowWidth + kPackRowWidth - 1u;
    uint cursor = (last < f.triangle_count && !boxEmpty(sparse.v[last])) ? kPackRowWidth - 1u : scratch.v[pointers + kPackRowWidth - 1u];
    uint m = HeaderRef(f.header).h.max_row_count;
    for (uint k = 0u; k < m && cursor != kNone; ++k) {
        scratch.v[shifted + kPackRowWidth - 1u - k] = cursor;
        cursor = scratch.v[pointers + cursor];
    }
}
