#!/usr/bin/python3
"""Read an FCLIB file written by `--example fclib_export` with h5py (the layout of fclib.h,
independently of our reader), solve it with Siconos' NSGS (FRICTION_2D_NSGS or, for
spacedim 3, FRICTION_3D_NSGS), and compare with our reaction
stored in solution/r.

Usage:  /usr/bin/python3 crates/contact-solver/examples/compare_siconos_fclib.py FILE.hdf5 [--tol 1e-12]
Not part of CI (needs `apt-get install -y python3-siconos python3-h5py`).
"""
import argparse
import h5py
import numpy as np
import siconos.numerics as sn


def one(d):
    return int(np.array(d).ravel()[0])


def dense(g):
    m, n, nz = one(g["m"]), one(g["n"]), one(g["nz"])
    p, i, x = (np.array(g[k]).ravel() for k in ("p", "i", "x"))
    a = np.zeros((m, n))
    if nz == -1:    # compressed columns
        for c in range(n):
            for k in range(p[c], p[c + 1]):
                a[i[k], c] += x[k]
    elif nz == -2:  # compressed rows
        for r in range(m):
            for k in range(p[r], p[r + 1]):
                a[r, i[k]] += x[k]
    else:           # triplets: i rows, p columns (CSparse)
        for k in range(nz):
            a[i[k], p[k]] += x[k]
    return a


ap = argparse.ArgumentParser()
ap.add_argument("file")
ap.add_argument("--tol", type=float, default=1e-12)
a = ap.parse_args()
with h5py.File(a.file, "r") as f:
    g = f["fclib_local"]
    dim = one(g["spacedim"])
    W = dense(g["W"])
    q = np.array(g["vectors/q"]).ravel()
    mu = np.array(g["vectors/mu"]).ravel()
    r_ours = np.array(f["solution/r"]).ravel()
    u_ours = np.array(f["solution/u"]).ravel()
nc = len(mu)
assert dim in (2, 3) and W.shape == (dim * nc, dim * nc)
assert np.allclose(u_ours, W @ r_ours + q, rtol=0, atol=1e-12 * max(1.0, abs(q).max()))
prob = sn.FrictionContactProblem(dim, nc, W, q, mu)
so = sn.SolverOptions(sn.SICONOS_FRICTION_2D_NSGS if dim == 2 else sn.SICONOS_FRICTION_3D_NSGS)
so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
so.dparam[sn.SICONOS_DPARAM_TOL] = a.tol
r = np.zeros(dim * nc); u = np.zeros(dim * nc)
info = (sn.fc2d_driver if dim == 2 else sn.fc3d_driver)(prob, r, u, so)
diff = np.abs(r - r_ours).max()
print(f"{a.file}: n_c={nc} siconos {dim}D NSGS info={info} iters={so.iparam[sn.SICONOS_IPARAM_ITER_DONE]} "
      f"|r|={np.linalg.norm(r):.6e}  max|r_siconos - r_ours|={diff:.2e}  "
      f"relative={diff / max(np.abs(r).max(), 1e-300):.2e}")
