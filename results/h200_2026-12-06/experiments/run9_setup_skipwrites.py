# Run 9's "setup-skipwrites" (applied to 2e945b3's spirv/cells/cells_setup.glsl.inc, from
# the repository root): the setup stores a record only where the buffer does not hold it
# already. An experiment: in a rigid scene's later frames the pass then stores nothing.
p = 'spirv/cells/cells_setup.glsl.inc'
s = open(p).read()
old = '''        CellsGeometryRef(P.geometry).g[t] = geo;
'''
new = '''        {  // experiment: skip the store where the record holds these values already (a rigid scene's later frames)
            CellsGeometry was = CellsGeometryRef(P.geometry).g[t];
            bool same = true;
            for (uint q = 0u; q < 9u; ++q) same = same && floatBitsToUint(was.v[q]) == floatBitsToUint(geo.v[q]);
            same = same && floatBitsToUint(was.eps) == floatBitsToUint(geo.eps) && was.index[0] == geo.index[0] && was.index[1] == geo.index[1] && was.index[2] == geo.index[2];
            if (!same) CellsGeometryRef(P.geometry).g[t] = geo;
        }
'''
assert old in s
s = s.replace(old, new)
old = '''        CellsTrianglesRef(P.triangles).t[t] = tri;
'''
new = '''        {
            CellsTriangle was = CellsTrianglesRef(P.triangles).t[t];
            bool same = true;
            for (uint q = 0u; q < 3u; ++q)
                same = same && floatBitsToUint(was.x[q]) == floatBitsToUint(tri.x[q]) && floatBitsToUint(was.y[q]) == floatBitsToUint(tri.y[q]) &&
                       floatBitsToUint(was.z[q]) == floatBitsToUint(tri.z[q]);
            same = same && floatBitsToUint(was.pad) == floatBitsToUint(tri.pad) && floatBitsToUint(was.zmin) == floatBitsToUint(tri.zmin) &&
                   floatBitsToUint(was.zmax) == floatBitsToUint(tri.zmax) && floatBitsToUint(was.ez) == floatBitsToUint(tri.ez) &&
                   floatBitsToUint(was.gx) == floatBitsToUint(tri.gx) && floatBitsToUint(was.gy) == floatBitsToUint(tri.gy) &&
                   floatBitsToUint(was.egx) == floatBitsToUint(tri.egx) && floatBitsToUint(was.egy) == floatBitsToUint(tri.egy) &&
                   was.cells_lo == tri.cells_lo && was.cells_hi == tri.cells_hi && was.key == tri.key && was.mode == tri.mode;
            if (!same) CellsTrianglesRef(P.triangles).t[t] = tri;
        }
'''
assert old in s
s = s.replace(old, new)
open(p, 'w').write(s)
