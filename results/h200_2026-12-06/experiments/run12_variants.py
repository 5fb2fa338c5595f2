# Run 12's variants of the sweep (on 420c82f): python3 run12_variants.py VARIANT from the
# repository root edits the shaders in place.
import sys
v=sys.argv[1]
sw='spirv/cells/cells_sweep.glsl.inc'; sh='spirv/cells/cells_sweep_shallow.glsl.inc'
W=open(sw).read(); H=open(sh).read()
sink='    if (sink == 0xFFFFFFFFu) atomicOr(cellsHeader(P).h.flags, 0x40000000u);\n'
if v=='sweep-loop2':  # the first scan over the cell done twice (the second into a sink)
    old='''    subgroupCount(headerField(P, kHeaderNeighbours), neighbours);'''
    assert old in W
    W=W.replace(old,'''    uint sink = 0u, neighbours2 = 0u;
    for (uint j = begin; j < stop; ++j) {
        CellsEntry o = entries.e[j];
        bool unique;
        CellsEntry me2 = me;
        me2.zhi = me.zhi + 1.0;
        if (pairsWith(P, cell, e, me2, my_key, my_box, mine, j, o, neighbours2, unique)) sink += o.triangle;
    }
    sink += neighbours2;
'''+sink+old)
elif v=='sweep-counts2':  # four more same-address atomics per subgroup
    old='''    subgroupCount(headerField(P, kHeaderNeighbours), neighbours);'''
    W=W.replace(old,'''    if (subgroupElect()) {
        atomicAdd(UintsRef(headerField(P, kHeaderNeighbours)).v[0], 0u);
        atomicAdd(Uint64sRef(headerField(P, kHeaderRepeats)).v[0], 0ul);
        atomicAdd(UintsRef(headerField(P, kHeaderCandidateCells)).v[0], 0u);
        atomicAdd(Uint64sRef(headerField(P, kHeaderCandidates)).v[0], 0ul);
    }
'''+old)
elif v=='sweep-head2':  # the entry's cell search, offsets and record read again (entry e ^ 1)
    old='''    sweepEntry(P, cell, e, me, mine, begin, end, end - begin >= P.sweep_dedupe);'''
    assert old in H
    H=H.replace(old,'''    uint sink = 0u;
    uint e2 = min(e ^ 1u, total - 1u);
    if (e < total) {
        uint c2 = cellOfEntry(P, e2, entries);
        CellsEntry o2 = CellsEntriesRef(P.entries).e[e2];
        sink = c2 + UintsRef(P.offsets).v[c2] + UintsRef(P.offsets).v[c2 + 1u] + o2.triangle + o2.key;
    }
'''+sink+old)
else: raise SystemExit('unknown')
open(sw,'w').write(W); open(sh,'w').write(H)
