# Run 8's variants of the setup and fill passes (on 2e945b3 with 653be64's bounds pass):
# python3 run8_variants.py VARIANT from the repository root edits the shaders in place.
import sys
v=sys.argv[1]
setup='spirv/cells/cells_setup.glsl.inc'; fill='spirv/cells/cells_fill.comp.glsl'
S=open(setup).read(); F=open(fill).read()
sinkS='        if (sink == 0xFFFFFFFFu) atomicOr(cellsHeader(P).h.flags, 0x40000000u);\n'
if v=='setup-fetch2':  # a neighbour's indices and positions fetched too
    old='        if (bad != 0u) p[0] = p[1] = p[2] = vec3(0.0);\n'
    assert old in S
    S=S.replace(old, old+'''        uint sink = 0u;
        uint other = min(t ^ 1u, P.triangle_count - 1u) - obj.triangle_base;
        for (uint k = 0u; k < 3u; ++k) {
            uint raw2 = min(fetchRawIndex(obj, 3u * other + k), obj.vertex_count - 1u);
            vec3 q = fetchPosition(obj, raw2);
            sink += floatBitsToUint(q.x) ^ floatBitsToUint(q.y) ^ floatBitsToUint(q.z);
        }
'''+sinkS)
elif v=='setup-fp64-2':  # the double-precision world transform twice
    old='        CellsGeometry geo;\n'
    assert old in S
    S=S.replace(old, '''#ifndef CELLS_NO_FLOAT64
        uint sink = 0u;
        for (uint k = 0u; k < 3u; ++k) {
            vec3 q = cpuWorldOf(obj, p[k] + vec3(1.0));
            sink += floatBitsToUint(q.x) ^ floatBitsToUint(q.y) ^ floatBitsToUint(q.z);
        }
'''+sinkS+'#endif\n'+old)
elif v=='setup-sample2':  # the sampling coordinates and their bounds twice
    old='        tri.pad = pad;\n'
    assert old in S
    S=S.replace(old, '''        uint sink = 0u;
        for (uint k = 0u; k < 3u; ++k) {
            vec3 q = w[k] + vec3(1.0);
            precise float sx = affineRow(pr.row[0], q), sy = affineRow(pr.row[1], q), sz = affineRow(pr.row[2], q);
            float ex = affineError(pr.row[0], q, eps_s), ey = affineError(pr.row[1], q, eps_s), ezz = affineError(pr.row[2], q, eps_s);
            sink += floatBitsToUint(sx) ^ floatBitsToUint(sy) ^ floatBitsToUint(sz) ^ floatBitsToUint(ex + ey + ezz);
        }
'''+sinkS+old)
elif v=='fill-tri2':  # a neighbour's triangle record read too
    old='    uvec4 r = cellsRange(tri);\n'
    assert old in F
    F=F.replace(old, old+'''    CellsTriangle tri2 = CellsTrianglesRef(P.triangles).t[min(t ^ 1u, P.triangle_count - 1u)];
    uint sink = floatBitsToUint(tri2.x[0] + tri2.y[1] + tri2.z[2] + tri2.pad + tri2.gx + tri2.egy) ^ tri2.cells_lo ^ tri2.key;
'''+sinkS.replace('        ','    '))
elif v=='fill-offsets2':  # each covered cell's offsets read again (the next row's)
    old='''        for (uint i = r.x; i <= r.z; ++i) fillCell(P, tri, box, t, i, j);
}'''
    assert old in F
    F=F.replace(old, old[:-2]+'''
    uint sink = 0u;
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i) {
            uint cell = min((j + 1u) * P.resolution + i, P.cell_count - 1u);
            sink += UintsRef(P.offsets).v[cell] ^ UintsRef(P.offsets).v[cell + 1u];
        }
'''+sinkS.replace('        ','    ')+'}')
else: raise SystemExit('unknown')
open(setup,'w').write(S); open(fill,'w').write(F)
