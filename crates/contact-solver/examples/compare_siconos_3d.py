#!/usr/bin/python3
"""Siconos' fc3d solvers on the 3D problems written by `--example work_precision_3d`, side by
side with ours (issue 14).

Usage:
    cargo run --release -p contact-solver --example work_precision_3d -- OUT
    OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/compare_siconos_3d.py OUT \
        [--ours target/release/examples/work_precision_3d] [--tol 1e-8] [--repeat 3]

For each problem of OUT/problems.txt it reads OUT/NAME.json (`{"dim":3,"W":[flat],"q","mu"}`)
and our reaction OUT/NAME.ours.json, and, with `--ours BINARY`, first times ours again on that
problem (`BINARY OUT --only NAME`), so that our runs and Siconos' alternate on a shared
machine; otherwise it reads OUT/ours.csv. Then it runs FRICTION_3D_NSGS, NSN_AC (dense W, and
W in Siconos' compressed-column sparse storage) and PROX at `--tol` (median of `--repeat` runs, 1 when the first
takes over 5 s, at most --max-iter iterations (200 for NSN-AC, 1000 for PROX), cold start
r = 0).

Every answer, ours and theirs, is measured with one common residual: Siconos'
`fc3d_compute_error` (the natural map of De Saxce's modified velocity, ||q||-relative) on
u = W r + q, never a status alone. "dr" is max|r - r_ours| / ||r_ours||_inf and "dx" the same
for u = W r + q relative to ||q||_inf (on a rank-deficient W the reactions need not be unique,
the velocities are). Writes OUT/siconos.csv and prints a Markdown table.
Needs `apt-get install -y python3-siconos python3-scipy`; not part of CI.
"""
import argparse
import csv
import io
import json
import os
import subprocess
import sys
import time

import numpy as np

try:
    import siconos.numerics as sn
except ImportError:
    sys.exit("siconos is missing: apt-get install -y python3-siconos (run with /usr/bin/python3)")

SOLVERS = ["NSGS", "NSN_AC", "NSN_AC_SPARSE", "PROX"]
NEWTON_CAP = 200
PROX_CAP = 1000


def load(out, name):
    with open(os.path.join(out, name + ".json")) as f:
        d = json.load(f)
    q = np.asarray(d["q"], float)
    W = np.asarray(d["W"], float).reshape(len(q), len(q))
    with open(os.path.join(out, name + ".ours.json")) as f:
        ours = json.load(f)
    return W, q, np.asarray(d["mu"], float), np.asarray(ours["r"], float), ours


def common_error(prob, W, q, r, tol):
    """Siconos' own error measure of an answer r (||q||-relative natural map)."""
    so = sn.SolverOptions(sn.SICONOS_FRICTION_3D_NSGS)
    u = W @ r + q
    info, err = sn.fc3d_compute_error(prob, r, u, tol, so, float(np.linalg.norm(q)))
    return err


def sparse_problem(W, q, mu):
    """The same problem with W in Siconos' sparse (compressed-column) storage. (Its
    sparse-block storage is not reachable from this Python binding without a .dat file.)"""
    import scipy.sparse as sp
    a = sp.csc_matrix(W)
    a.indices = a.indices.astype(np.int64)
    a.indptr = a.indptr.astype(np.int64)
    return sn.FrictionContactProblem(3, len(mu), sn.NumericsMatrix(a), q, mu)


def run_siconos(prob, name, tol, max_iter, repeat, size):
    sid = getattr(sn, "SICONOS_FRICTION_3D_" + name.replace("_SPARSE", ""))
    # a dense Newton step costs an LU of W's size: cap them so that a stall (seen on
    # rank-deficient W) ends in minutes; PROX runs a Newton solve per outer iteration
    max_iter = min(max_iter, NEWTON_CAP if name.startswith("NSN") else PROX_CAP if name == "PROX"
                   else max_iter)
    times = []
    while len(times) < repeat:
        so = sn.SolverOptions(sid)
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_iter
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        r = np.zeros(size)
        u = np.zeros(size)
        t0 = time.perf_counter()
        info = sn.fc3d_driver(prob, r, u, so)
        times.append(time.perf_counter() - t0)
        if times[0] > 5.0:
            break
    return dict(status=info, iterations=so.iparam[sn.SICONOS_IPARAM_ITER_DONE],
                ms=1e3 * float(np.median(times)), runs=len(times), r=r)


def ours_rows(out, name, binary):
    if binary:
        text = subprocess.run([binary, out, "--only", name], check=True, capture_output=True,
                              text=True).stdout
        header = "problem,contacts,algorithm,tol,converged,iterations,runs,ms,residual,norm_r\n"
        rows = list(csv.DictReader(io.StringIO(header + text)))
    else:
        with open(os.path.join(out, "ours.csv")) as f:
            rows = [r for r in csv.DictReader(f) if r["problem"] == name]
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--ours", help="the work_precision_3d binary: time ours again, alternating")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-iter", type=int, default=10000)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    with open(os.path.join(a.out, "problems.txt")) as f:
        listing = [line.split() for line in f if line.strip()]
    table = ["| problem | n_c | deficiency | solver | status | iters | runs | ms (median) | "
             "common error | dr | dx |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    records = []
    for name, nc, bodies, deficiency in listing:
        rows = ours_rows(a.out, name, a.ours)
        W, q, mu, r_ours, meta = load(a.out, name)
        prob = sn.FrictionContactProblem(3, len(mu), W, q, mu)
        scale_r = max(np.abs(r_ours).max(), 1e-300)
        scale_x = max(np.abs(q).max(), 1e-300)
        u_ours = W @ r_ours + q
        err_ours = common_error(prob, W, q, r_ours, a.tol)
        for row in rows:
            if float(row["tol"]) != a.tol:
                continue
            table.append(f"| {name} | {nc} | {deficiency} | ours {row['algorithm']} | "
                         f"{'ok' if row['converged'] == 'true' else 'NOT CONVERGED'} | "
                         f"{row['iterations']} | {row['runs']} | {float(row['ms']):.2f} | "
                         f"(own {float(row['residual']):.1e}) | | |")
        table.append(f"| {name} | {nc} | {deficiency} | ours, best answer ({meta['algorithm']} "
                     f"tol {meta['tol']:g}) | | | | | {err_ours:.1e} | 0 | 0 |")
        for solver in SOLVERS:
            try:
                p = sparse_problem(W, q, mu) if solver.endswith("_SPARSE") else prob
                res = run_siconos(p, solver, a.tol, a.max_iter, a.repeat, 3 * len(mu))
            except Exception as e:  # a solver or storage the installed Siconos lacks
                table.append(f"| {name} | {nc} | {deficiency} | Siconos {solver} | failed: {e} "
                             "| | | | | | |")
                continue
            r = res["r"]
            err = common_error(prob, W, q, r, a.tol)
            dr = np.abs(r - r_ours).max() / scale_r
            dx = np.abs(W @ r + q - u_ours).max() / scale_x
            table.append(f"| {name} | {nc} | {deficiency} | Siconos {solver} | {res['status']} | "
                         f"{res['iterations']} | {res['runs']} | {res['ms']:.2f} | {err:.1e} | "
                         f"{dr:.1e} | {dx:.1e} |")
            records.append(dict(problem=name, contacts=nc, solver=solver, status=res["status"],
                                iterations=res["iterations"], runs=res["runs"], ms=res["ms"],
                                error=err, dr=dr, dx=dx))
        print("\n".join(table[-(len(SOLVERS) + 1 + sum(float(r['tol']) == a.tol for r in rows)):]),
              flush=True)
    with open(os.path.join(a.out, "siconos.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(records[0].keys()) if records else ["problem"])
        w.writeheader()
        w.writerows(records)
    print()
    print("\n".join(table))


if __name__ == "__main__":
    main()
