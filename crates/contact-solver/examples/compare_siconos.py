#!/usr/bin/python3
"""Compare our reduced-solver reactions with Siconos' 2D NSGS, reaction by reaction.

Usage (after `cargo run --release -p contact-solver --example export_random -- DIR`):
    /usr/bin/python3 crates/contact-solver/examples/compare_siconos.py DIR/random_100.json
Reads DIR/random_<n>.solution.json (our r, x), solves the same problem with
SICONOS_FRICTION_2D_NSGS at tol 1e-10, and prints the relative differences.
Not part of CI (needs `apt-get install -y python3-siconos`).
"""
import json, sys
import numpy as np
import siconos.numerics as sn

path = sys.argv[1]
d = json.load(open(path))
q = np.asarray(d["q"], float); m = len(q); nc = m // 2
W = np.asarray(d["W"], float).reshape(m, m); mu = np.asarray(d["mu"], float)
ours = json.load(open(path.replace(".json", ".solution.json")))
r_ours = np.asarray(ours["r"]); x_ours = np.asarray(ours["x"])
p = sn.FrictionContactProblem(2, nc, W, q, mu)
so = sn.SolverOptions(sn.SICONOS_FRICTION_2D_NSGS)
so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
so.dparam[sn.SICONOS_DPARAM_TOL] = 1e-10
r = np.zeros(m); u = np.zeros(m)
info = sn.fc2d_driver(p, r, u, so)
rel = lambda a, b: np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300)
print(f"{path}: siconos status {info}, iters {so.iparam[sn.SICONOS_IPARAM_ITER_DONE]}")
print(f"  |r_ours - r_siconos|/|r_siconos| = {rel(r_ours, r):.2e}")
print(f"  max_i |r_ours_i - r_siconos_i|   = {np.max(np.abs(r_ours - r)):.2e}  (max |r_i| = {np.max(np.abs(r)):.3e})")
print(f"  |x_ours - u_siconos|/|u_siconos| = {rel(x_ours, u):.2e}")
st = lambda rr: ["sep" if np.hypot(*rr[2*i:2*i+2]) == 0 else ("slip" if abs(abs(rr[2*i+1]) - mu[i]*rr[2*i]) <= 1e-8*max(rr[2*i], 1e-300) else "stick") for i in range(nc)]
so_, ss = st(r_ours), st(r)
print(f"  statuses differ at {sum(a != b for a, b in zip(so_, ss))} of {nc} contacts; ours: "
      f"{so_.count('sep')} sep / {so_.count('stick')} stick / {so_.count('slip')} slip")
