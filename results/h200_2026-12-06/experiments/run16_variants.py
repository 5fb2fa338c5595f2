# Run 16's variant of the tiled shallow sweep (session 50): python3 run16_variants.py noindex
# from the repository root edits the shader in place: the vertex indices of self-testing
# entries read from the geometry records where needed (the owner's once, a partner's per
# pair of one object), as run 14 measured, instead of loaded with the tile (s_index).
import sys
v=sys.argv[1]
sh='spirv/cells/cells_sweep_shallow.glsl.inc'
H=open(sh).read()
def sub(old,new):
    global H
    assert old in H, old
    H=H.replace(old,new)
if v=='noindex':
    sub('''        s_index[x] = (triangleKeyOf(P, en.key) & kCellsKeySelf) != 0u ? triangleIndices(P, en.triangle) : uvec3(~0u);\n''','')
    sub('''    const uvec3 mine = s_index[a];''','''    const uvec3 mine = valid && (my_key & kCellsKeySelf) != 0u ? triangleIndices(P, my_triangle) : uvec3(~0u);''')
    sub('''o.triangle, s_index[b], cell''','''o.triangle, triangleKeyOf(P, o.key) == my_key ? triangleIndices(P, o.triangle) : uvec3(~0u), cell''')
else: raise SystemExit('unknown')
open(sh,'w').write(H)
