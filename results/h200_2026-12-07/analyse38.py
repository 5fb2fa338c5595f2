#!/usr/bin/env python3
"""Run 38: s66 (66811c2) against s67 = b15f809 (the naming during the GPU only from 32,768 pairs, the responses made fresh beside
the pages' touching) on the scenes with many pairs, rounds a, b, c. As analyse36.py: only frames in the H100's fast clock state (per scene,
cells-sweep within 5 % of the fastest seen in the run), median host total per build and
variant, frames >= 1, with the naming done during the GPU (detect,milestone).
    python3 analyse38.py   (from results/h200_2026-12-07: reads run38/)"""
import csv, gzip, os, statistics as st
from collections import defaultdict
frames = []
for b in ('s66', 's67'):
    for rnd in 'abc':
        f = f'run38/{rnd}-{b}_profile.csv.gz'
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
print('| scene | variant | host total ms, s66 | s67 | frames s66 / s67 | naming ms (s67) | GPU span s66 / s67 |')
print('|---|---|---|---|---|---|---|')
for sc, v in sorted({(k[0], k[1]) for k in kept}):
    a, b = kept.get((sc, v, 's66'), []), kept.get((sc, v, 's67'), [])
    med = lambda x, i: f'{st.median(t[i] for t in x):.3f}' if x else '-'
    print(f'| {sc} | {v} | {med(a, 0)} | {med(b, 0)} | {len(a)} / {len(b)} | {med(b, 1)} | {med(a, 2)} / {med(b, 2)} |')
