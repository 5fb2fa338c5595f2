# Run 7's variants of the setup and fill passes (on 2e945b3 with 653be64's bounds pass):
# python3 run7_variants.py VARIANT from the repository root edits the shaders in place.
import sys
v=sys.argv[1]
setup='spirv/cells/cells_setup.glsl.inc'; fill='spirv/cells/cells_fill.comp.glsl'
S=open(setup).read(); F=open(fill).read()
count_loop='''            if (cellsCovers(tri, i, j, P.resolution)) atomicAdd(counts.v[j * P.resolution + i], 1u);
}'''
assert count_loop in S
sink='    if (sink == 0xFFFFFFFFu) atomicOr(cellsHeader(P).h.flags, 0x40000000u);\n'
if v=='setup-atomics2':   # the count loop's atomics twice (adding 0)
    S=S.replace(count_loop, count_loop[:-2]+'''
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j, P.resolution)) atomicAdd(counts.v[j * P.resolution + i], 0u);
}''')
elif v=='setup-covers2':  # the covers tests twice (one row down), into a sink
    S=S.replace(count_loop, count_loop[:-2]+'''
    uint sink = 0u;
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j + 1u, P.resolution)) sink += i;
'''+sink+'}')
elif v=='setup-header2':  # the per-subgroup 64-bit budget atomic twice
    old='''        uint64_t before = atomicAdd(Uint64sRef(headerField(P, kHeaderBoxCells)).v[0], boxes);'''
    assert old in S
    S=S.replace(old, old+'''
        atomicAdd(Uint64sRef(headerField(P, kHeaderBoxCells)).v[1], 0ul);''')
elif v=='fill-atomics2':  # the fill's slot atomics twice (adding 0, result into a sink)
    old='''        for (uint i = r.x; i <= r.z; ++i) fillCell(P, tri, box, t, i, j);
}'''
    assert old in F
    F=F.replace(old, old[:-2]+'''
    uint sink = 0u;
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j, P.resolution)) sink += atomicAdd(UintsRef(P.counts).v[j * P.resolution + i], 0u);
'''+sink+'}')
elif v=='fill-compute2':  # the fill's covers, depth and key twice (one row down), into a sink
    old='''        for (uint i = r.x; i <= r.z; ++i) fillCell(P, tri, box, t, i, j);
}'''
    F=F.replace(old, old[:-2]+'''
    uint sink = 0u;
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j + 1u, P.resolution)) {
                vec2 z = cellsDepth(tri, i, j + 1u, P.resolution);
                sink += floatBitsToUint(z.x) ^ floatBitsToUint(z.y) ^ entryKey(P, tri.key, cellsSubBox(tri, box, i, j + 1u));
            }
'''+sink+'}')
else: raise SystemExit('unknown')
open(setup,'w').write(S); open(fill,'w').write(F)
