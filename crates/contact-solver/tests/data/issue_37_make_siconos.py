#!/usr/bin/python3
"""Makes `issue_37_skew_3d.json` (a 3D reduced problem whose W is SPD plus a skew part of 1e-3 of
its scale, 20 contacts, Coulomb) and `issue_37_skew_3d_siconos.json` (Siconos' FRICTION_3D_NSGS
answer at tol 1e-12, and its time). Run with Debian's Python and python3-siconos:
    /usr/bin/python3 crates/contact-solver/tests/data/issue_37_make_siconos.py
"""
import json, os, time
import numpy as np
import siconos.numerics as sn

here = os.path.dirname(os.path.abspath(__file__))
g = np.random.default_rng(37)
nc, dim = 20, 3
m = dim * nc
a = g.uniform(-1, 1, (m, m)) / np.sqrt(m)
w = a @ a.T + 0.1 * np.eye(m)
u = g.uniform(-1, 1, (m, m))
w = w + 1e-3 * np.abs(w).max() * (u - u.T)
q = g.uniform(-1, 1, m)
q[0::3] = g.uniform(-1, 0.5, nc)
mu = g.uniform(0.1, 0.8, nc)
with open(os.path.join(here, "issue_37_skew_3d.json"), "w") as f:
    json.dump({"dim": 3, "W": w.tolist(), "q": q.tolist(), "mu": mu.tolist()}, f)
p = sn.FrictionContactProblem(3, nc, w, q, mu)
times = []
for _ in range(5):
    so = sn.SolverOptions(sn.SICONOS_FRICTION_3D_NSGS)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
    so.dparam[sn.SICONOS_DPARAM_TOL] = 1e-12
    r = np.zeros(m); v = np.zeros(m)
    t0 = time.perf_counter(); info = sn.fc3d_driver(p, r, v, so); times.append(time.perf_counter() - t0)
out = {"solver": "SICONOS_FRICTION_3D_NSGS", "tol": 1e-12, "status": int(info),
       "iterations": int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE]),
       "residual": float(so.dparam[sn.SICONOS_DPARAM_RESIDU]),
       "ms_median_of_5": 1e3 * float(np.median(times)), "r": r.tolist()}
with open(os.path.join(here, "issue_37_skew_3d_siconos.json"), "w") as f:
    json.dump(out, f)
print({k: v for k, v in out.items() if k != "r"})
