#!/usr/bin/env python3
"""Runs 35 and 36: s63 (51a926d, before) against s64/s65 (the pairs named while the GPU computes
the responses; s65 = 9af9fce looks for the milestone where the timestamps put it) on the
scenes with many pairs. The H100 changed clock state between bench calls (every compute pass
up to 2-4x slower, the copies unchanged: run 36's s65 calls), so only frames in the fast state
are compared: per scene, frames whose cells-sweep pass is within 5 % of the fastest seen in
either run. Median host total (and n frames) per build and variant, frames >= 1.
    python3 analyse36.py   (from results/h200_2026-12-07: reads run35/ and run36/)"""
import csv, gzip, statistics as st
from collections import defaultdict
runs = (('run35', ('s63', 's64')), ('run36', ('s63', 's65')))
frames = []  # (scene, variant, build, total, sweep, milestone)
for run, builds in runs:
    for b in builds:
        for rnd in 'ab':
            per = defaultdict(dict)
            for r in csv.DictReader(gzip.open(f'{run}/{rnd}-{b}_profile.csv.gz', 'rt')):
                if int(r['frame']) >= 1:
                    per[(r['scene'], r['variant'], r['frame'])][(r['kind'], r['stage'])] = float(r['ms'])
            for (sc, v, f), x in per.items():
                frames.append((sc, v, 'before' if b == 's63' else 'after', x[('host', 'total')], x[('gpu', 'cells-sweep')],
                               x.get(('detect', 'milestone'), 0.0)))
fastest = defaultdict(lambda: 1e9)
for sc, v, b, t, sw, m in frames: fastest[sc] = min(fastest[sc], sw)
kept = defaultdict(list)
for sc, v, b, t, sw, m in frames:
    if sw <= 1.05 * fastest[sc]: kept[(sc, v, b)].append((t, m))
print('| scene | variant | host total ms, before (51a926d) | after (named during the GPU) | frames before / after | naming ms (after) |')
print('|---|---|---|---|---|---|')
for sc, v in sorted({(k[0], k[1]) for k in kept}):
    a, b = kept.get((sc, v, 'before'), []), kept.get((sc, v, 'after'), [])
    med = lambda x, i: f'{st.median(t[i] for t in x):.3f}' if x else '-'
    print(f'| {sc} | {v} | {med(a, 0)} | {med(b, 0)} | {len(a)} / {len(b)} | {med(b, 1)} |')
