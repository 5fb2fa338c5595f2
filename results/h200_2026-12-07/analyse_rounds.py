#!/usr/bin/env python3
"""Runs 34 and 35 (session 59): per scene and variant, each build's median host total, GPU span,
narrow phase and the detect() profile's prepare, wait and milestone (the naming during the
GPU), over frames >= 1 of rounds a and b; recall and precision minimum over all.
    python3 analyse_rounds.py RUN BUILD...   (from results/h200_2026-12-07)
    e.g. python3 analyse_rounds.py run34 s60 s63; python3 analyse_rounds.py run35 s63 s64"""
import csv, gzip, sys, os, statistics as st
from collections import defaultdict
d = sys.argv[1]
builds = tuple(sys.argv[2:])
rows, prof = defaultdict(list), defaultdict(lambda: defaultdict(list))
for rnd in 'ab':
    for b in builds:
        f = os.path.join(d, f'{rnd}-{b}.csv')
        if not os.path.exists(f): continue
        for r in csv.DictReader(open(f)):
            if int(r['frame']) >= 1:
                rows[(b, r['scene'], r['variant'])].append((float(r['total_ms']), float(r['gpu_span_ms']), float(r['narrow_ms']),
                                                            float(r['recall']), float(r['precision']), int(r['pairs'])))
        for r in csv.DictReader(gzip.open(os.path.join(d, f'{rnd}-{b}_profile.csv.gz'), 'rt')):
            if int(r['frame']) >= 1 and (r['kind'], r['stage']) in (('detect', 'prepare'), ('detect', 'wait'), ('detect', 'milestone'), ('gpu', 'pairs-to-host'),
                                                                      ('gpu', 'responses-to-host'), ('host', 'start')):
                prof[(b, r['scene'], r['variant'])][r['stage']].append(float(r['ms']))
med = lambda x, i: st.median(t[i] for t in x) if x else float('nan')
pm = lambda p, k: st.median(p[k]) if p.get(k) else float('nan')
print(f'| scene | variant | pairs | host total ms: {" / ".join(builds)} | GPU span ms | narrow ms | prepare ms | wait ms | milestone ms | recall, precision min |')
print('|---|---|---|---|---|---|---|---|---|---|')
for sc, v in sorted({(k[1], k[2]) for k in rows}):
    rs = [rows.get((b, sc, v), []) for b in builds]
    ps = [prof[(b, sc, v)] for b in builds]
    allr = sum(rs, [])
    j = lambda i: ' / '.join(f'{med(r, i):.3f}' for r in rs)
    jp = lambda k: ' / '.join(f'{pm(p, k):.3f}' for p in ps)
    print(f"| {sc} | {v} | {allr[0][5]} | {j(0)} | {j(1)} | {j(2)} | {jp('prepare')} | {jp('wait')} | {jp('milestone')} | {min(t[3] for t in allr):.4f}, {min(t[4] for t in allr):.4f} |")
