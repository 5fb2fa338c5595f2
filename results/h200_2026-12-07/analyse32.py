#!/usr/bin/env python3
"""Run 32: per scene and variant, s59 against s60 (the clear and scan over the buffers'
cells): median host total and GPU span over frames >= 1 of both rounds, and from the
profiles the share of submissions made again (`detect,reused`) and `record` ms.
    python3 analyse32.py DIR   (DIR holds a-s59.csv, a-s60.csv, b-s60.csv, b-s59.csv and their _profile.csv.gz)"""
import csv, gzip, sys, os, statistics as st
from collections import defaultdict
d = sys.argv[1]
rows, prof = defaultdict(list), defaultdict(lambda: defaultdict(list))
for rnd in 'ab':
    for b in ('s59', 's60'):
        for r in csv.DictReader(open(os.path.join(d, f'{rnd}-{b}.csv'))):
            if int(r['frame']) >= 1:
                rows[(b, r['scene'], r['variant'])].append((float(r['total_ms']), float(r['gpu_span_ms']), float(r['recall']), float(r['precision'])))
        for r in csv.DictReader(gzip.open(os.path.join(d, f'{rnd}-{b}_profile.csv.gz'), 'rt')):
            if int(r['frame']) >= 1 and r['stage'] in ('reused', 'record'):
                prof[(b, r['scene'], r['variant'])][r['stage']].append(float(r['ms']))
print('| scene | variant | host total ms: s59 -> s60 | GPU span ms: s59 -> s60 | reused: s59 -> s60 | record ms: s59 -> s60 | recall, precision min |')
print('|---|---|---|---|---|---|---|')
for sc, v in sorted({(k[1], k[2]) for k in rows}):
    a, b = rows[('s59', sc, v)], rows[('s60', sc, v)]
    pa, pb = prof[('s59', sc, v)], prof[('s60', sc, v)]
    med = lambda x, i: st.median(t[i] for t in x)
    print(f"| {sc} | {v} | {med(a,0):.3f} -> {med(b,0):.3f} | {med(a,1):.3f} -> {med(b,1):.3f} | {st.mean(pa['reused']):.2f} -> {st.mean(pb['reused']):.2f} "
          f"| {st.median(pa['record']):.3f} -> {st.median(pb['record']):.3f} | {min(t[2] for t in a + b):.4f}, {min(t[3] for t in a + b):.4f} |")
