#!/usr/bin/env python3
"""compare_outputs.py A B: compare two output trees from tools/capture_outputs.sh file by file, byte
for byte except wall-time fields (JSON keys, CSV columns, timing cells of the seed tables)."""
import sys, os, re, json, csv, io
A, B = sys.argv[1], sys.argv[2]
TIME_KEYS = re.compile(r'wall_time|seconds|time_s$|elapsed')
def norm_json(o):
    if isinstance(o, dict):
        return {k: norm_json(v) for k, v in o.items() if not TIME_KEYS.search(k)}
    if isinstance(o, list):
        return [norm_json(v) for v in o]
    return o
def norm_csv(t):
    rows = list(csv.reader(io.StringIO(t)))
    if not rows: return rows
    keep = [i for i, h in enumerate(rows[0]) if not TIME_KEYS.search(h)]
    return [[r[i] for i in keep if i < len(r)] for r in rows]
def norm_text(t, name):
    t = re.sub(r'\d+(\.\d+)?(e-?\d+)? ?(s|ms|µs)\b', '<T>', t)
    t = t.replace(A, '<OUT>').replace(B, '<OUT>')
    if True:
        out = []
        for line in t.split('\n'):
            cells = line.split('|')
            if len(cells) == 9 and (cells[1].strip().isdigit() or cells[1].strip() == 'total'):
                cells[4] = '<T>'; cells[7] = '<T>'
            out.append('|'.join(cells))
        t = '\n'.join(out)
    return t
bad = 0; n = 0
for root, _, files in os.walk(A):
    for f in files:
        pa = os.path.join(root, f); pb = os.path.join(B, os.path.relpath(pa, A))
        n += 1
        if not os.path.exists(pb): print('missing', pb); bad += 1; continue
        ta, tb = open(pa, 'rb').read(), open(pb, 'rb').read()
        if ta == tb: continue
        ta, tb = ta.decode(errors='replace'), tb.decode(errors='replace')
        if f.endswith('.json'): same = norm_json(json.loads(ta)) == norm_json(json.loads(tb))
        elif f.endswith('.csv'): same = norm_csv(ta) == norm_csv(tb)
        else: same = norm_text(ta, f) == norm_text(tb, f)
        if not same: print('DIFFERS', pa); bad += 1
print(f'{n} files compared, {bad} differ beyond wall times')
sys.exit(1 if bad else 0)
