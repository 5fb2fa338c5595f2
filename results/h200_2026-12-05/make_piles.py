#!/usr/bin/env python3
"""Writes the pathological scenes of docs/stability.md as OBJ files into a folder (argv[1]):
pile-N.obj (N copies of one triangle, each with its own vertices) with cross.obj (a triangle
through them), fan-300.obj (300 triangles crossing on one axis, turned onto (1, 2, 3))."""
import math, os, sys
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
for n in (2200, 3000):
    with open(f"{out}/pile-{n}.obj", "w") as f:
        for k in range(n):
            f.write("v -1 -1 0\nv 1 -1 0\nv 0 1 0\n")
        for k in range(n):
            f.write(f"f {3*k+1} {3*k+2} {3*k+3}\n")
with open(f"{out}/cross.obj", "w") as f:
    f.write("v -0.3 -0.2 -0.5\nv 0.3 -0.2 -0.5\nv 0 0.1 0.5\nf 1 2 3\n")
# 300 triangles whose bases pass through the origin and whose apexes lie on one axis, the
# axis turned from z onto (1, 2, 3)/|(1, 2, 3)|: any two meet along it.
a = [1 / math.sqrt(14), 2 / math.sqrt(14), 3 / math.sqrt(14)]
u = [2 / math.sqrt(5), -1 / math.sqrt(5), 0.0]
v = [a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2], a[0] * u[1] - a[1] * u[0]]
with open(f"{out}/fan-300.obj", "w") as f:
    for k in range(300):
        t = math.pi * k / 300
        x, y, h = math.cos(t), math.sin(t), 1 + k / 300
        for p in ((x, y, 0), (-x, -y, 0), (0, 0, h)):
            w = [p[0] * u[i] + p[1] * v[i] + p[2] * a[i] for i in range(3)]
            f.write("v %.9g %.9g %.9g\n" % tuple(w))
    for k in range(300):
        f.write(f"f {3*k+1} {3*k+2} {3*k+3}\n")
