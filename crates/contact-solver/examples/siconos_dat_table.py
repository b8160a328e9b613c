#!/usr/bin/python3
"""Siconos `.dat` problems solved by ours and by Siconos, judged by one residual computed
outside both (issue 37; the table of docs/benchmarks.md).

Usage:
    cargo build --release -p contact-solver --example siconos_dat_table
    OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/siconos_dat_table.py \
        OUT FILE.dat ... [--ours target/release/examples/siconos_dat_table] [--tol 1e-8] [--repeat 3]

For each file, first ours (the example, one process per file: every algorithm and Auto, timed
in-process, the read apart), then Siconos' solvers in this process (read with Siconos' own
reader, in-process times of the driver call, median of --repeat, one run when the first takes
over 2 s, cold start r = 0, at most 5000 iterations for the Gauss-Seidel and 500 for Newton):
local 3D: FRICTION_3D_NSGS, NSN_AC, NSN_FB; local 2D: FRICTION_2D_NSGS, LEMKE, CPG; global 3D:
GLOBAL_FRICTION_3D_NSGS_WR, NSN_AC_WR, NSN_AC.

The judge ("res"): on W, q read by Siconos (scipy, via NM_triplet; a global problem condensed
here, W = H^T M^-1 H, q = H^T M^-1 q_g + b, with scipy's sparse LU), u = W r + q and De Saxce's
modified velocity w = u + mu ||u_T|| e_N; res = ||r - P_K(r - w)||_2 / max(||q||_2, 1e-300), the
natural map of Siconos' fc3d_compute_error with rho = 1, the same number for every answer.
Solved: res <= 1e-6. Prints a Markdown table and writes OUT/table.json.
Needs python3-siconos, python3-scipy; not part of CI.
"""
import argparse
import json
import os
import subprocess
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.coo  # noqa: F401  (Siconos' NM_triplet needs it imported)
import scipy.sparse.linalg as spla
import siconos.numerics as sn

SOLVED = 1e-6


def project_cone(r, mu, dim):
    """P_K of one contact's (r_n, r_t): the second-order cone ||r_t|| <= mu r_n."""
    rn, rt = r[0], r[1:]
    nt = np.linalg.norm(rt)
    if nt <= mu * rn:
        return r.copy()
    if mu * nt <= -rn:
        return np.zeros(dim)
    a = (rn + mu * nt) / (1 + mu * mu)
    out = np.empty(dim)
    out[0] = a
    out[1:] = mu * a * rt / nt
    return out


def judge(W, q, mu, dim, r):
    u = W @ r + q
    f = np.empty_like(r)
    for c in range(len(mu)):
        s = slice(dim * c, dim * (c + 1))
        w = u[s].copy()
        w[0] += mu[c] * np.linalg.norm(u[s][1:])
        f[s] = r[s] - project_cone(r[s] - w, mu[c], dim)
    return float(np.linalg.norm(f) / max(np.linalg.norm(q), 1e-300))


def timed(run, repeat):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = run()
        times.append(1e3 * (time.perf_counter() - t0))
        if times[0] > 2000:
            break
    return float(np.median(times)), out


def options(solver, tol, cap):
    so = sn.SolverOptions(solver)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = cap
    so.dparam[sn.SICONOS_DPARAM_TOL] = tol
    return so


def siconos_local(path, tol, repeat):
    p = sn.frictionContact_new_from_filename(path)
    dim, nc = p.dimension, p.numberOfContacts
    m = dim * nc
    W = sn.NM_triplet(p.M).tocsr()
    q, mu = np.array(p.q, float), np.array(p.mu, float)
    if dim == 3:
        solvers = [("NSGS", sn.SICONOS_FRICTION_3D_NSGS, 5000, sn.fc3d_driver),
                   ("NSN-AC", sn.SICONOS_FRICTION_3D_NSN_AC, 500, sn.fc3d_driver),
                   ("NSN-FB", sn.SICONOS_FRICTION_3D_NSN_FB, 500, sn.fc3d_driver)]
    else:
        solvers = [("NSGS-2D", sn.SICONOS_FRICTION_2D_NSGS, 5000, sn.fc2d_driver),
                   ("Lemke-2D", sn.SICONOS_FRICTION_2D_LEMKE, 5000, sn.fc2d_driver),
                   ("CPG-2D", sn.SICONOS_FRICTION_2D_CPG, 5000, sn.fc2d_driver)]
    runs = []
    for name, solver, cap, driver in solvers:
        def run():
            r, u = np.zeros(m), np.zeros(m)
            info = driver(p, r, u, options(solver, tol, cap))
            return info, r
        ms, (info, r) = timed(run, repeat)
        runs.append({"solver": name, "ms": ms, "info": int(info), "r": r})
    return (W, q, mu, dim), runs


def siconos_global(path, tol, repeat):
    p = sn.globalFrictionContact_new_from_filename(path)
    dim, nc = p.dimension, p.numberOfContacts
    m = dim * nc
    M = sn.NM_triplet(p.M).tocsc()
    H = sn.NM_triplet(p.H).tocsc()
    qg, b, mu = np.array(p.q, float), np.array(p.b, float), np.array(p.mu, float)
    n = M.shape[0]
    lu = spla.splu(M)
    X = lu.solve(H.toarray())
    W = sp.csr_matrix(H.T @ X)
    q = H.T @ lu.solve(qg) + b
    runs = []
    for name, solver, cap in [("NSGS-WR", sn.SICONOS_GLOBAL_FRICTION_3D_NSGS_WR, 5000),
                              ("NSN-AC-WR", sn.SICONOS_GLOBAL_FRICTION_3D_NSN_AC_WR, 500),
                              ("NSN-AC (global)", sn.SICONOS_GLOBAL_FRICTION_3D_NSN_AC, 500)]:
        def run():
            r, u, v = np.zeros(m), np.zeros(m), np.zeros(n)
            info = sn.gfc3d_driver(p, r, u, v, options(solver, tol, cap))
            return info, r
        ms, (info, r) = timed(run, repeat)
        runs.append({"solver": name, "ms": ms, "info": int(info), "r": r})
    return (W, q, mu, dim), runs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("files", nargs="+")
    ap.add_argument("--ours", default="target/release/examples/siconos_dat_table")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    rows = []
    for path in a.files:
        stem = os.path.splitext(os.path.basename(path))[0]
        res = subprocess.run([a.ours, a.out, path, "--tol", str(a.tol), "--repeat", str(a.repeat)],
                             capture_output=True, text=True)
        if res.returncode != 0:
            rows.append({"file": stem, "refused": res.stderr.strip().splitlines()[-1]})
            continue
        with open(os.path.join(a.out, stem + ".ours.json")) as f:
            ours = json.load(f)
        glob = ours["source"].startswith("global")
        (W, q, mu, dim), theirs = (siconos_global if glob else siconos_local)(path, a.tol, a.repeat)
        row = {"file": stem, "source": ours["source"], "dim": dim, "contacts": len(mu),
               "read_ms": ours["read_ms"], "ours": [], "siconos": []}
        for run in ours["runs"]:
            rr = {"algorithm": run["algorithm"], "ms": run["ms"]}
            if "r" in run:
                rr.update(res=judge(W, q, mu, dim, np.array(run["r"])), picked=run["picked"],
                          iterations=run["iterations"])
            else:
                rr["error"] = run["error"]
            row["ours"].append(rr)
        for run in theirs:
            row["siconos"].append({"solver": run["solver"], "ms": run["ms"], "info": run["info"],
                                   "res": judge(W, q, mu, dim, run["r"])})
        rows.append(row)
    with open(os.path.join(a.out, "table.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print_table(rows)


def cell(ms, res):
    return f"{ms:.3g}" if res <= SOLVED else f"({ms:.3g}, res {res:.1e})"


def print_table(rows):
    algs = ["Uzawa", "GaussSeidel", "ClassicRccm", "AndersonGaussSeidel", "AndersonUzawa",
            "Newton", "Auto"]
    short = ["Uzawa", "GS", "Classic", "AGS", "AU", "Newton", "Auto"]
    print("| problem | n_c | " + " | ".join(short) + " | Auto / best | Siconos (ms, best first) | "
          "Siconos best / Auto |")
    print("|---|---|" + "---|" * (len(algs) + 3))
    for row in rows:
        if "refused" in row:
            print(f"| {row['file']} | refused: {row['refused']} |")
            continue
        by = {r["algorithm"]: r for r in row["ours"]}
        cells, best = [], None
        for alg in algs:
            r = by.get(alg)
            if r is None or "error" in r:
                cells.append("error")
                continue
            cells.append(cell(r["ms"], r["res"]))
            if alg != "Auto" and r["res"] <= SOLVED and (best is None or r["ms"] < best):
                best = r["ms"]
        auto = by.get("Auto", {})
        auto_ok = "res" in auto and auto["res"] <= SOLVED
        ratio = f"{auto['ms'] / best:.2f}" if auto_ok and best else "-"
        sic = sorted(row["siconos"], key=lambda s: (s["res"] > SOLVED, s["ms"]))
        sic_txt = ", ".join(f"{s['solver']} {cell(s['ms'], s['res'])}" for s in sic)
        sbest = [s["ms"] for s in sic if s["res"] <= SOLVED]
        vs = f"{min(sbest) / auto['ms']:.2f}" if sbest and auto_ok else "-"
        name = f"{row['file']} ({row['source']}, {row['dim']}D)"
        print(f"| {name} | {row['contacts']} | " + " | ".join(cells)
              + f" | {ratio} | {sic_txt} | {vs} |")


if __name__ == "__main__":
    main()
