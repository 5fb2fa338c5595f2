#!/usr/bin/env python3
"""Runs 37-39 (session 59): build BEFORE against build AFTER on the scenes with many pairs, rounds
a, b, c of one run. The H100 changed compute clock state between bench calls, so only frames in
the fast state count (per scene, cells-sweep within 5 % of the fastest seen in the run); median
host total per build and variant over frames >= 1, the naming done during the GPU
(detect,milestone) and the GPU span.
    python3 analyse_fast.py RUN BEFORE AFTER   (from results/h200_2026-12-07)
    e.g. python3 analyse_fast.py run37 s63 s66; run38 s66 s67; run39 s66 s68"""
import csv, gzip, os, statistics as st, sys
from collections import defaultdict
run, before, after = sys.argv[1:4]
frames = []
for b in (before, after):
    for rnd in 'abc':
        f = f'{run}/{rnd}-{b}_profile.csv.gz'
        if not os.path.exists(f): continue
        per = defaultdict(dict)
        for r in csv.DictReader(gzip.open(f, 'rt')):
            if int(r['frame']) >= 1:
                per[(r['scene'], r['variant'], r['frame'])][(r['kind'], r['stage'])] = float(r['ms'])
        for (sc, v, fr), x in per.items():
            frames.append((sc, v, b, x[('host', 'total')], x[('gpu', 'cells-sweep')], x.get(('detect', 'milestone'), 0.0),
                           x[('detect', 'gpu-span')]))
fastest = defaultdict(lambda: 1e9)
for sc, v, b, t, sw, m, span in frames: fastest[sc] = min(fastest[sc], sw)
kept = defaultdict(list)
for sc, v, b, t, sw, m, span in frames:
    if sw <= 1.05 * fastest[sc]: kept[(sc, v, b)].append((t, m, span))
print(f'| scene | variant | host total ms, {before} | {after} | frames {before} / {after} | naming ms ({after}) | GPU span {before} / {after} |')
print('|---|---|---|---|---|---|---|')
for sc, v in sorted({(k[0], k[1]) for k in kept}):
    a, b = kept.get((sc, v, before), []), kept.get((sc, v, after), [])
    med = lambda x, i: f'{st.median(t[i] for t in x):.3f}' if x else '-'
    print(f'| {sc} | {v} | {med(a, 0)} | {med(b, 0)} | {len(a)} / {len(b)} | {med(b, 1)} | {med(a, 2)} / {med(b, 2)} |')
