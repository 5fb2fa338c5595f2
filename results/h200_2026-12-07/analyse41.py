#!/usr/bin/env python3
"""Run 41: s69 (f942633) against s70 (a8c27fc: the clear and scan over the most cells of the last
32 runs within the band) on the deforming scenes: per scene, variant and build, the share of
frames >= 1 that submitted the command buffer again (detect,reused), the median `record` and
host total (ms), over rounds a and b.
    python3 analyse41.py   (from results/h200_2026-12-07: reads run41/)"""
import csv, gzip, statistics as st
from collections import defaultdict
d = defaultdict(lambda: defaultdict(list))
for b in ('s69', 's70'):
    for rnd in 'ab':
        for r in csv.DictReader(gzip.open(f'run41/{rnd}-{b}_profile.csv.gz', 'rt')):
            if int(r['frame']) >= 1 and (r['kind'], r['stage']) in (('detect', 'reused'), ('detect', 'record'), ('host', 'total'), ('host', 'start')):
                d[(r['scene'], r['variant'], b)][r['stage']].append(float(r['ms']))
print('| scene | variant | reused s69 -> s70 | record ms | start ms | host total ms |')
print('|---|---|---|---|---|---|')
for sc, v in sorted({(k[0], k[1]) for k in d}):
    a, b = d[(sc, v, 's69')], d[(sc, v, 's70')]
    f = lambda x, k, fn: f'{fn(x[k]):.3f}' if x.get(k) else '-'
    print(f"| {sc} | {v} | {f(a, 'reused', st.mean)} -> {f(b, 'reused', st.mean)} | {f(a, 'record', st.median)} -> {f(b, 'record', st.median)} | "
          f"{f(a, 'start', st.median)} -> {f(b, 'start', st.median)} | {f(a, 'total', st.median)} -> {f(b, 'total', st.median)} |")
