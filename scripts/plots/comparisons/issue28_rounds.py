#!/usr/bin/env python3
# Issue 28: the medians of docs/performance.md's "quarter checkerboard" table from the frame logs of
# docs/bench/issue28/quarter/ (KIND_BUILD_ROUND.csv with KIND drag or settle, and .load beside each).
# Held: the frames with grabbed = 1; after the drop: frames 2.. with simulated_s <= 20.
# fps = 1000 / the median frame. Usage: python3 issue28_rounds.py docs/bench/issue28/quarter
import csv, glob, os, statistics as st, sys

d = sys.argv[1]
res = {}
for f in sorted(glob.glob(os.path.join(d, '*_*_[0-9].csv'))):
    kind, build, rnd = os.path.basename(f)[:-4].split('_')
    rows = list(csv.DictReader(open(f)))
    sel = [x for x in rows if x['grabbed'] == '1'] if kind == 'drag' else \
          [x for x in rows[2:] if float(x['simulated_s']) <= 20]
    ms = [float(x['frame_ms']) for x in sel]
    if not ms:
        continue
    med = st.median(ms)
    trace = st.median([float(x['trace_ms']) for x in sel])
    physics = st.median([float(x['physics_ms']) for x in sel])
    load = open(f[:-4] + '.load').read().split('load average:')[1].split(',')[0].strip()
    res.setdefault((kind, build), []).append((1000 / med, trace, physics))
    print(f'{kind} {build} round {rnd}: {len(ms)} frames, fps {1000 / med:.2f}, trace {trace:.1f} ms, '
          f'physics {physics:.1f} ms, load {load}')
for (kind, build), v in sorted(res.items()):
    print(f'{kind} {build} median of rounds: fps {st.median(x[0] for x in v):.2f}, '
          f'trace {st.median(x[1] for x in v):.1f} ms, physics {st.median(x[2] for x in v):.1f} ms')
