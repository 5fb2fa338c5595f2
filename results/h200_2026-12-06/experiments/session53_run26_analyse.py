# Reads the output folder of run27.sh (once session53_run26.sh; python3 session53_run26_analyse.py DIR): the
# prepare trace per array, the grid invocations beside the sampled clocks, the tuner against
# the fixed grid per scene.
import sys, csv, gzip, glob, os, re, collections, statistics as st, datetime
d = sys.argv[1]
def prof(path):
    out = collections.defaultdict(dict)
    op = gzip.open if path.endswith('.gz') else open
    for r in csv.reader(op(path, 'rt')):
        if r[0] == 'device': continue
        out[(r[1], r[2], int(r[3]))][(r[4], r[5])] = float(r[6])
    return out
print('== (1) prepare trace')
for m in ['huge', 'nohuge']:
    f = os.path.join(d, f'prep-{m}.trace')
    if not os.path.exists(f): continue
    rows = collections.defaultdict(list)
    for line in open(f):
        x = re.match(r'prepare (\d+) B warm (\d) mmapped (\d) alloc ([\d.]+) advise ([\d.]+) touch ([\d.]+) resize ([\d.]+) swap\+free ([\d.]+)', line)
        if x: rows[int(x.group(1))].append([float(x.group(i)) for i in range(4, 9)] + [int(x.group(3))])
    for b in sorted(rows):
        v = rows[b]
        med = [st.median([r[i] for r in v]) for i in range(5)]
        print(f'  {m:7s} {b/1e6:7.1f} MB n={len(v):3d} mmapped={sum(r[5] for r in v)} alloc {med[0]:.3f} advise {med[1]:.3f} touch {med[2]:.3f} resize {med[3]:.3f} free {med[4]:.3f}  (touch range {min(r[2] for r in v):.2f}-{max(r[2] for r in v):.2f}, resize {min(r[3] for r in v):.2f}-{max(r[3] for r in v):.2f})')
    pf = glob.glob(os.path.join(d, f'prep-{m}_profile.csv*'))
    if pf:
        p = prof(pf[0])
        agg = collections.defaultdict(lambda: collections.defaultdict(list))
        for (sc, var, fr), kv in p.items():
            if fr < 1: continue
            for k in [('detect','prepare'), ('detect','gpu-span'), ('host','total'), ('host','collect'), ('narrow','validate')]:
                if k in kv: agg[(sc, var)][k[1]].append(kv[k])
        for k, v in sorted(agg.items()):
            print('   ', k, ' '.join(f'{n}={st.mean(x):.2f}' for n, x in v.items()))
print('== (2) grid')
stamps = {}
sf = os.path.join(d, 'stamps.txt')
if os.path.exists(sf):
    for line in open(sf):
        n, what, t = line.split()
        stamps[(n, what)] = float(t)
clocks = []
cf = os.path.join(d, 'clocks.csv')
if os.path.exists(cf):
    for r in csv.reader(open(cf)):
        try:
            t = datetime.datetime.strptime(r[0].strip(), '%Y/%m/%d %H:%M:%S.%f').timestamp()
            clocks.append((t, float(r[1].split()[0]), r[4].strip(), r[5].strip()))
        except Exception: pass
for f in sorted(glob.glob(os.path.join(d, 'grid-*.csv'))):
    n = os.path.basename(f)[:-4]
    rows = list(csv.DictReader(open(f)))
    spans = [float(r['gpu_span_ms']) for r in rows]
    res = [r['resolution'] for r in rows]
    tb, te = stamps.get((n, 'begin')), stamps.get((n, 'end'))
    cl = [c[1] for c in clocks if tb and tb <= c[0] <= te]
    # clocks are in UTC local? print range
    print(f'  {n:45s} span mean(fr>=1) {st.mean(spans[1:]):.3f} min {min(spans):.3f} max {max(spans):.3f} res {collections.Counter(res).most_common(3)} sm MHz {min(cl) if cl else "-"}-{max(cl) if cl else "-"} median {st.median(cl) if cl else "-"}')
    print('     ', ' '.join(f'{r["resolution"]}:{float(r["gpu_span_ms"]):.2f}' for r in rows))
print('== (3) tuner')
f = os.path.join(d, 'tuner.csv')
if os.path.exists(f):
    agg = collections.defaultdict(lambda: collections.defaultdict(list))
    notes = {}
    for r in csv.DictReader(open(f)):
        if int(r['frame']) < 1: continue
        agg[(r['set'], r['scene'])][r['variant']].append((float(r['gpu_span_ms']), float(r['total_ms']), r['resolution'], float(r['recall']), float(r['precision'])))
        if r['variant'] == 'grid-tuned': notes[r['scene']] = r['settings_note'][r['settings_note'].find('grid tuned'):][:70]
    worse = 0
    for k in sorted(agg):
        a, b = agg[k].get('default'), agg[k].get('grid-tuned')
        if not a or not b: continue
        sa, sb = st.mean(x[0] for x in a), st.mean(x[0] for x in b)
        ta, tb_ = st.mean(x[1] for x in a), st.mean(x[1] for x in b)
        rec = min(x[3] for x in a + b), min(x[4] for x in a + b)
        worse += sb > sa * 1.015
        print(f'  {k[0]:8s} {k[1]:24s} span {sa:7.3f} -> {sb:7.3f} ({100*(sb/sa-1):+5.1f} %) total {ta:7.3f} -> {tb_:7.3f} res {a[-1][2]}->{",".join(sorted(set(x[2] for x in b)))} recall/prec {rec} {notes.get(k[1],"")}')
    print('  worse by > 1.5 %:', worse)
print("== (0) builds: new (84dd7c3), p1 (637f007: two arrays side by side), s54 (b06bbed: 8-byte host pairs)")
for b in ['new', 'p1', 's54']:
    for pf in glob.glob(os.path.join(d, f'1-{b}_profile.csv*')):
        agg = collections.defaultdict(lambda: collections.defaultdict(list))
        for (sc, var, fr), kv in prof(pf).items():
            if fr < 1: continue
            for k in [('gpu', 'pairs-to-host'), ('gpu', 'pairs-sort'), ('detect', 'gpu-span'), ('detect', 'prepare'), ('host', 'total'), ('narrow', 'validate')]:
                if k in kv: agg[(sc, var)][k[1]].append(kv[k])
        for k, v in sorted(agg.items()):
            print(f'  {b:4s}', k, ' '.join(f'{n}={st.mean(x):.3f}' for n, x in v.items()))
