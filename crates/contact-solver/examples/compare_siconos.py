#!/usr/bin/python3
"""Compare our reduced-solver reactions with Siconos' 2D NSGS, reaction by reaction.

Usage:
    /usr/bin/python3 crates/contact-solver/examples/compare_siconos.py PROBLEM.json [OURS.json]
        [--tol 1e-10] [--repeat 5]
PROBLEM.json is a reduced problem {"dim": 2, "W", "q", "mu"} (normal first per contact).
OURS.json holds our {"r": [...]} (and optionally "x") in the same order; by default
PROBLEM.solution.json (written by `--example export_random -- DIR`) or, if that does not
exist, PROBLEM_ours.json (written by `--example hertz_export -- PROBLEM.json`).
Solves the same problem with SICONOS_FRICTION_2D_NSGS at --tol (cold start, --repeat runs,
median wall time) and prints the differences.
Not part of CI (needs `apt-get install -y python3-siconos`).
"""
import argparse, json, os, time
import numpy as np
import siconos.numerics as sn

ap = argparse.ArgumentParser()
ap.add_argument("problem")
ap.add_argument("ours", nargs="?")
ap.add_argument("--tol", type=float, default=1e-10)
ap.add_argument("--repeat", type=int, default=5)
args = ap.parse_args()
path = args.problem
ours_path = args.ours
if ours_path is None:
    ours_path = path.replace(".json", ".solution.json")
    if not os.path.exists(ours_path):
        ours_path = path.replace(".json", "_ours.json")

d = json.load(open(path))
q = np.asarray(d["q"], float); m = len(q); nc = m // 2
W = np.asarray(d["W"], float).reshape(m, m); mu = np.asarray(d["mu"], float)
ours = json.load(open(ours_path))
r_ours = np.asarray(ours["r"], float)
x_ours = np.asarray(ours["x"], float) if "x" in ours else W @ r_ours + q
p = sn.FrictionContactProblem(2, nc, W, q, mu)
times = []
for _ in range(max(args.repeat, 1)):
    so = sn.SolverOptions(sn.SICONOS_FRICTION_2D_NSGS)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
    so.dparam[sn.SICONOS_DPARAM_TOL] = args.tol
    r = np.zeros(m); u = np.zeros(m)
    t = time.perf_counter()
    info = sn.fc2d_driver(p, r, u, so)
    times.append(1e3 * (time.perf_counter() - t))
rel = lambda a, b: np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300)
print(f"{path} ({nc} contacts) vs {ours_path}")
print(f"  siconos FRICTION_2D_NSGS tol {args.tol:g}: status {info}, iters "
      f"{so.iparam[sn.SICONOS_IPARAM_ITER_DONE]}, residual {so.dparam[sn.SICONOS_DPARAM_RESIDU]:.1e}, "
      f"{np.median(times):.3f} ms (median of {len(times)})")
print(f"  |r_ours - r_siconos|/|r_siconos| = {rel(r_ours, r):.2e}")
print(f"  max_i |r_ours_i - r_siconos_i|   = {np.max(np.abs(r_ours - r)):.2e}  (max |r_i| = {np.max(np.abs(r)):.3e})")
print(f"  max_i |r_ours_i - r_siconos_i| / max_i |r_siconos_i| = {np.max(np.abs(r_ours - r)) / max(np.max(np.abs(r)), 1e-300):.2e}")
print(f"  |x_ours - u_siconos|/|u_siconos| = {rel(x_ours, u):.2e}")
st = lambda rr: ["sep" if np.hypot(*rr[2*i:2*i+2]) == 0 else ("slip" if mu[i] > 0 and abs(abs(rr[2*i+1]) - mu[i]*rr[2*i]) <= 1e-8*max(rr[2*i], 1e-300) else "stick") for i in range(nc)]
so_, ss = st(r_ours), st(r)
print(f"  statuses differ at {sum(a != b for a, b in zip(so_, ss))} of {nc} contacts; ours: "
      f"{so_.count('sep')} sep / {so_.count('stick')} stick / {so_.count('slip')} slip")
