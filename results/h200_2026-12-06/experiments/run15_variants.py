# Run 15's variants of the tiled shallow sweep (session 50): python3 run15_variants.py VARIANT
# from the repository root edits the shader in place; each does one piece twice, the second
# time into a never-true sink, so the pairs are unchanged and the pass grows by the piece; the
# copy starts from a zero the compiler cannot see (bit 31 of a tile position), so it keeps both.
import sys
v=sys.argv[1]
sh='spirv/cells/cells_sweep_shallow.glsl.inc'
H=open(sh).read()
sink='    if (sink == 0xFFFFFFFFu) atomicOr(cellsHeader(P).h.flags, 0x40000000u);\n'
if v=='rank2':  # each entry's rank in its cell counted twice
    old='''        s_order[first + rank] = x;
'''
    assert old in H
    H=H.replace(old,'''        uint sink = 0u;
        const float z2 = z + float(s_range[x] >> 31);
        for (uint y = first; y < end; ++y) sink += s_zlo[y] < z2 || (s_zlo[y] == z2 && y < x) ? 1u : 0u;
        if (sink == 0xFFFFFFFFu) s_order[0] = 0u;
'''+old)
elif v=='load2':  # the tile's load (entry, indices, cell search, offsets) done again for entry x ^ 1
    old='''        s_range[x] = (first - begin) | ((last - begin) << 16);
'''
    assert old in H
    H=H.replace(old,old+'''        {
            uint x2 = min(x ^ 1u, n - 1u);
            CellsEntry e2 = CellsEntriesRef(P.entries).e[begin + x2];
            uint c2 = cellOfEntry(P, begin + x2, entries);
            uvec3 i2 = (triangleKeyOf(P, e2.key) & kCellsKeySelf) != 0u ? triangleIndices(P, e2.triangle) : uvec3(~0u);
            uint sink = c2 + UintsRef(P.offsets).v[c2] + UintsRef(P.offsets).v[c2 + 1u] + e2.triangle + i2.x + i2.y;
'''+sink.replace('    ','            ',1)+'''        }
''')
elif v=='walk2':  # the first walk done twice
    old='''        candidate_cells += markCandidateCell(P, cell, count);
'''
    assert old in H
    H=H.replace(old,'''        uint sink = 0u, neighbours2 = 0u;
        for (uint q = p + 1u + (s_range[a] >> 31); walkGoesOn(q, end, zhi); ++q) {
            uint v = visit(P, my_key, my_box, mine, s_order[q], cell, dedupe, mine_t, neighbours2, partner);
            sink += v + partner;
        }
        sink += neighbours2;
'''+sink.replace('    ','        ',1)+old)
else: raise SystemExit('unknown')
open(sh,'w').write(H)
