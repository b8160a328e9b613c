#!/usr/bin/python3
"""Writes fclib_csc_h5py.hdf5: a 2-contact 2D FCLIB local problem as a third-party writer
(h5py) stores it, W in compressed columns (nz = -1), 64-bit integers, scalar datasets for
the sizes, no nzmax, and a solution group. tests/integration/fclib.rs reads it back.

Run (Debian: apt-get install -y python3-h5py):  /usr/bin/python3 make_fclib_csc.py
"""
import os
import h5py
import numpy as np

W = np.array([[2.0, 0.5, 0.25, 0.0],
              [0.5, 1.0, 0.0, 0.125],
              [0.25, 0.0, 3.0, -0.5],
              [0.0, 0.125, -0.5, 1.5]])
q = np.array([-1.0, 0.25, 0.5, -0.75])
mu = np.array([0.3, 0.6])
r = np.array([0.5, -0.125, 0.0, 0.0])

cols = [np.nonzero(W[:, c])[0] for c in range(4)]
p = np.concatenate([[0], np.cumsum([len(c) for c in cols])]).astype(np.int64)
i = np.concatenate(cols).astype(np.int64)
x = np.concatenate([W[c, k] for k, c in enumerate(cols)])

path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fclib_csc_h5py.hdf5")
with h5py.File(path, "w") as f:
    g = f.create_group("fclib_local")
    g["spacedim"] = np.int64(2)
    w = g.create_group("W")
    w["m"], w["n"], w["nz"] = np.int64(4), np.int64(4), np.int64(-1)
    w["p"], w["i"], w["x"] = p, i, x
    v = g.create_group("vectors")
    v["q"], v["mu"] = q, mu
    s = f.create_group("solution")
    s["r"] = r
