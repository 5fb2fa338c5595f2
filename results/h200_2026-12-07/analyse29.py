#!/usr/bin/env python3
"""Run 29 part A: per scene and variant, the mean GPU span and host total (frames >= 1) of
each configuration, rounds a and b pooled, and each round alone.
    python3 analyse29.py DIR   (DIR holds a1-late.csv ... b4-late-span.csv)"""
import csv, sys, glob, os, statistics as st
from collections import defaultdict
d = sys.argv[1]
rows = defaultdict(list)  # (config, scene, variant) -> [(round, span, total, narrow, pairs, recall)]
for f in sorted(glob.glob(os.path.join(d, '[ab][0-9]-*.csv'))):
    name = os.path.basename(f)[:-4]
    rnd, config = name[0], name[3:]
    for r in csv.DictReader(open(f)):
        if int(r['frame']) < 1: continue
        rows[(config, r['scene'], r['variant'])].append((rnd, float(r['gpu_span_ms']), float(r['total_ms']),
                                                        float(r['narrow_ms']), int(r['pairs']), float(r['recall'])))
configs = sorted({k[0] for k in rows}, key=lambda c: ['late', 'sort', 'sort-span', 'late-span'].index(c) if c in ['late', 'sort', 'sort-span', 'late-span'] else 9)
scenes = sorted({(k[1], k[2]) for k in rows})
print('scene variant | ' + ' | '.join(f'{c}: span / total (a; b)' for c in configs) + ' | recall min')
for sc, v in scenes:
    cells, rec = [], 1.0
    for c in configs:
        x = rows.get((c, sc, v), [])
        if not x: cells.append('-'); continue
        rec = min(rec, min(t[5] for t in x))
        m = lambda i, rr=None: st.mean(t[i] for t in x if rr is None or t[0] == rr) if any(rr is None or t[0] == rr for t in x) else float('nan')
        cells.append(f'{m(1):.3f} / {m(2):.3f} ({m(1,"a"):.3f},{m(2,"a"):.3f}; {m(1,"b"):.3f},{m(2,"b"):.3f})')
    print(f'{sc} {v} | ' + ' | '.join(cells) + f' | {rec:.4f}')
