#!/usr/bin/env python3
"""compare_columns.py A B: every file of A exists in B; CSV: every column of A (by header) equal in B
(rows by order; numbers to rel 1e-12); JSON: every key of A equal in B (recursively, numbers to
rel 1e-12, wall-time keys skipped). Other files: reported if they differ (not an error)."""
import sys, os, re, json, csv, io, math
A, B = sys.argv[1], sys.argv[2]
TK = re.compile(r'wall_time|seconds|time_s$|elapsed')
def num_eq(a, b):
    try: x, y = float(a), float(b)
    except: return a == b
    if math.isnan(x) and math.isnan(y): return True
    return abs(x - y) <= 1e-12 * max(abs(x), abs(y), 1e-300) or x == y
def jeq(a, b, path):
    if isinstance(a, dict):
        if not isinstance(b, dict): return [path]
        out = []
        for k, v in a.items():
            if TK.search(k): continue
            if k not in b: out.append(path + '/' + k + ' missing'); continue
            out += jeq(v, b[k], path + '/' + k)
        return out
    if isinstance(a, list):
        if not isinstance(b, list) or len(a) != len(b): return [path + ' len']
        out = []
        for i, (x, y) in enumerate(zip(a, b)): out += jeq(x, y, f'{path}[{i}]')
        return out
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return [] if num_eq(a, b) else [f'{path}: {a} vs {b}']
    return [] if a == b else [f'{path}: {a!r} vs {b!r}']
bad = 0; other = []
for root, _, files in os.walk(A):
    for f in files:
        pa = os.path.join(root, f); pb = os.path.join(B, os.path.relpath(pa, A))
        if not os.path.exists(pb): print('MISSING', pb); bad += 1; continue
        ta, tb = open(pa, 'rb').read(), open(pb, 'rb').read()
        if ta == tb: continue
        ta, tb = ta.decode(errors='replace'), tb.decode(errors='replace')
        if f.endswith('.json'):
            d = jeq(json.loads(ta), json.loads(tb), '')
            if d: print('JSON DIFFERS', pa, d[:5]); bad += 1
        elif f.endswith('.csv'):
            ra = list(csv.reader(io.StringIO(ta))); rb = list(csv.reader(io.StringIO(tb)))
            ha, hb = [h.strip() for h in ra[0]], [h.strip() for h in rb[0]]
            miss = [h for h in ha if h not in hb]
            if miss: print('CSV COLUMNS MISSING', pa, miss); bad += 1; continue
            if len(ra) != len(rb): print('CSV ROWS', pa, len(ra), len(rb)); bad += 1; continue
            diffs = []
            for i, h in enumerate(ha):
                if TK.search(h): continue
                j = hb.index(h)
                for r, (x, y) in enumerate(zip(ra[1:], rb[1:])):
                    if i < len(x) and j < len(y) and not num_eq(x[i].strip(), y[j].strip()):
                        diffs.append((h, r, x[i], y[j])); break
            if diffs: print('CSV DIFFERS', pa, diffs[:6]); bad += 1
        else: other.append(pa)
print('other files that differ (check by eye):', *other, sep='\n  ')
print('bad', bad); sys.exit(1 if bad else 0)
