# Run 10's "fill-skipcells" (on f13377a, from the repository root): the fill stores an entry's
# cell only where the buffer does not hold it already.
p='spirv/cells/cells_fill.glsl.inc'
s=open(p).read()
old='''    UintsRef(P.entry_cells).v[begin + slot] = cell;'''
assert old in s
s=s.replace(old,'''    // experiment: in a rigid scene's later frames every slot keeps its cell (the atomics only
    // permute a cell's own footprints), so this store is skipped there
    if (UintsRef(P.entry_cells).v[begin + slot] != cell) UintsRef(P.entry_cells).v[begin + slot] = cell;''')
open(p,'w').write(s)
