#!/usr/bin/env python3
"""Run 31: per small scene and variant, s58 (before) against s59 (few decided pairs on the
calling thread): median host total, narrow phase and GPU span over frames >= 1 of both
rounds (a: s58 first, b: s59 first), the rounds' medians beside; then every scene at s59.
    python3 analyse31.py DIR   (DIR holds a-s58.csv, a-s59.csv, b-s59.csv, b-s58.csv, all.csv)"""
import csv, sys, os, statistics as st
from collections import defaultdict
d = sys.argv[1]
rows = defaultdict(list)  # (build, scene, variant) -> [(round, total, narrow, span, pairs, recall, precision, threads)]
for rnd in 'ab':
    for build in ('s58', 's59'):
        f = os.path.join(d, f'{rnd}-{build}.csv')
        if not os.path.exists(f): continue
        for r in csv.DictReader(open(f)):
            if int(r['frame']) < 1: continue
            rows[(build, r['scene'], r['variant'])].append((rnd, float(r['total_ms']), float(r['narrow_ms']), float(r['gpu_span_ms']),
                                                            int(r['pairs']), float(r['recall']), float(r['precision']), r['narrow_threads']))
med = lambda x, i, rr=None: st.median(t[i] for t in x if rr is None or t[0] == rr) if any(rr is None or t[0] == rr for t in x) else float('nan')
print('| scene | variant | pairs | host total ms: s58 -> s59 (a; b) | narrow ms: s58 -> s59 | GPU span: s58 / s59 | threads s59 | recall, precision min |')
print('|---|---|---|---|---|---|---|---|')
for sc, v in sorted({(k[1], k[2]) for k in rows}):
    a, b = rows.get(('s58', sc, v), []), rows.get(('s59', sc, v), [])
    if not a or not b: continue
    rec = min(t[5] for t in a + b); prec = min(t[6] for t in a + b)
    print(f'| {sc} | {v} | {b[0][4]} | {med(a,1):.3f} -> {med(b,1):.3f} ({med(a,1,"a"):.3f} -> {med(b,1,"a"):.3f}; {med(a,1,"b"):.3f} -> {med(b,1,"b"):.3f}) '
          f'| {med(a,2):.3f} -> {med(b,2):.3f} | {med(a,3):.3f} / {med(b,3):.3f} | {b[0][7]} | {rec:.4f}, {prec:.4f} |')
f = os.path.join(d, 'all.csv')
if os.path.exists(f):
    allrows = defaultdict(list)
    for r in csv.DictReader(open(f)):
        if int(r['frame']) < 1: continue
        allrows[(r['scene'], r['variant'])].append(r)
    print('\n| scene | set | pairs | detect() ms | detectInto() ms | GPU span ms | recall, precision min |')
    print('|---|---|---|---|---|---|---|')
    for sc in sorted({k[0] for k in allrows}, key=lambda s: -st.median(float(r['gpu_span_ms']) for r in allrows[(s, 'default')])):
        de, it = allrows[(sc, 'default')], allrows.get((sc, 'into'), [])
        g = lambda x, k: st.median(float(r[k]) for r in x) if x else float('nan')
        rec = min(float(r['recall']) for r in de + it); prec = min(float(r['precision']) for r in de + it)
        print(f"| {sc} | {de[0]['set']} | {de[0]['pairs']} | {g(de,'total_ms'):.2f} | {g(it,'total_ms'):.2f} | {g(de + it,'gpu_span_ms'):.2f} | {rec:.4f}, {prec:.4f} |")
