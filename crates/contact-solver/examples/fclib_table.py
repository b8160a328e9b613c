#!/usr/bin/python3
"""Siconos' FCLIB files solved by ours and by Siconos, judged by one residual computed outside
both (issue 37; the table "Siconos' FCLIB files (issue 37)" of docs/benchmarks.md).

Usage:
    cargo build --release -p contact-solver --features fclib --example fclib_table
    OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/fclib_table.py \
        OUT FILE.hdf5 ... [--ours $CARGO_TARGET_DIR/release/examples/fclib_table] \
        [--tol 1e-8] [--repeat 3] [--cap 60]

Every run is its own process, ended after --cap seconds (the per-problem time cap, per
solver): ours once per algorithm (the example `fclib_table`: the read and condensation timed
apart, the solve timed in-process, median of --repeat), then each Siconos solver (this script
with --siconos: the file read with h5py, the problem handed to Siconos as sparse matrices, the
in-process time of the driver call, median of --repeat, one run when the first takes over
2 s; cold start r = 0; at most 5000 iterations for the Gauss-Seidel and ADMM, 500 for Newton):
local 3D: FRICTION_3D_NSGS, NSN_AC, NSN_FB; global 3D: GLOBAL_FRICTION_3D_NSGS_WR, NSN_AC_WR,
NSN_AC, ADMM.

The judge ("res"): the file read here with h5py (every FCLIB storage form: compressed columns
nz = -1, compressed rows nz = -2, nz triplets with i and x of nz or nzmax entries), a global
problem condensed here with scipy's sparse LU (W = H^T M^-1 H, q = H^T M^-1 f + w);
u = W r + q and De Saxce's modified velocity w = u + mu ||u_T|| e_N;
res = ||r - P_K(r - w)||_2 / max(||q||_2, 1e-300), the natural map of Siconos'
fc3d_compute_error with rho = 1, the same number for every answer. Solved: res <= 1e-6.
Prints a Markdown table and writes OUT/table.json.
Needs python3-siconos, python3-h5py, python3-scipy; not part of CI.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

SOLVED = 1e-6
OURS = ["Uzawa", "GaussSeidel", "ClassicRccm", "AndersonGaussSeidel", "AndersonUzawa",
        "Newton", "Auto"]
SHORT = ["Uzawa", "GS", "Classic", "AGS", "AU", "Newton", "Auto"]
LOCAL = [("NSGS", "SICONOS_FRICTION_3D_NSGS", 5000), ("NSN-AC", "SICONOS_FRICTION_3D_NSN_AC", 500),
         ("NSN-FB", "SICONOS_FRICTION_3D_NSN_FB", 500)]
GLOBAL = [("NSGS-WR", "SICONOS_GLOBAL_FRICTION_3D_NSGS_WR", 5000),
          ("NSN-AC-WR", "SICONOS_GLOBAL_FRICTION_3D_NSN_AC_WR", 500),
          ("NSN-AC", "SICONOS_GLOBAL_FRICTION_3D_NSN_AC", 500),
          ("ADMM", "SICONOS_GLOBAL_FRICTION_3D_ADMM", 5000)]


def one(d):
    return int(np.array(d).ravel()[0])


def matrix(g):
    """An FCLIB sparse matrix group as scipy CSC, from any storage form."""
    m, n, nz = one(g["m"]), one(g["n"]), one(g["nz"])
    p, i = (np.array(g[k]).ravel().astype(np.int64) for k in ("p", "i"))
    x = np.array(g["x"]).ravel().astype(float)
    if nz == -1:  # compressed columns: p column pointers, i row indices
        used = p[n]
        return sp.csc_matrix((x[:used], i[:used], p), shape=(m, n))
    if nz == -2:  # compressed rows: p row pointers, i column indices
        used = p[m]
        return sp.csr_matrix((x[:used], i[:used], p), shape=(m, n)).tocsc()
    # nz triplets: i rows, p columns (duplicates summed)
    return sp.coo_matrix((x[:nz], (i[:nz], p[:nz])), shape=(m, n)).tocsc()


def read(path):
    """(kind, dim, pieces) of an FCLIB file: local (W, q, mu) or global (M, H, f, w, mu)."""
    with h5py.File(path, "r") as f:
        if "fclib_local" in f:
            g = f["fclib_local"]
            v = g["vectors"]
            return "local", one(g["spacedim"]), (matrix(g["W"]), np.array(v["q"]).ravel(),
                                                np.array(v["mu"]).ravel())
        g = f["fclib_global"]
        v = g["vectors"]
        return "global", one(g["spacedim"]), (matrix(g["M"]), matrix(g["H"]),
                                              np.array(v["f"]).ravel(), np.array(v["w"]).ravel(),
                                              np.array(v["mu"]).ravel())


def condensed(kind, pieces):
    """The local problem (W, q, mu) of the file, a global one condensed with scipy."""
    if kind == "local":
        return pieces
    M, H, f, w, mu = pieces
    lu = spla.splu(M.tocsc())
    X = lu.solve(H.toarray())
    return sp.csr_matrix(H.T @ X), H.T @ lu.solve(f) + w, mu


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


def siconos_one(path, solver, cap, tol, repeat):
    """One Siconos solver on one file, in this process; prints JSON (ms, info, r)."""
    import siconos.numerics as sn
    kind, dim, pieces = read(path)
    times, info, r = [], None, None
    for _ in range(repeat):
        so = sn.SolverOptions(getattr(sn, solver))
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = cap
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        if kind == "local":
            W, q, mu = pieces
            m = len(q)
            p = sn.FrictionContactProblem(dim, len(mu), W.tocsc(), q, mu)
            r, u = np.zeros(m), np.zeros(m)
            t0 = time.perf_counter()
            info = sn.fc3d_driver(p, r, u, so)
        else:
            M, H, f, w, mu = pieces
            p = sn.GlobalFrictionContactProblem()
            p.dimension, p.numberOfContacts = dim, len(mu)
            p.M, p.H, p.q, p.b, p.mu = M.tocsc(), H.tocsc(), f, w, mu
            r, u, v = np.zeros(len(w)), np.zeros(len(w)), np.zeros(len(f))
            t0 = time.perf_counter()
            info = sn.gfc3d_driver(p, r, u, v, so)
        times.append(1e3 * (time.perf_counter() - t0))
        if times[0] > 2000:
            break
    print(json.dumps({"ms": float(np.median(times)), "info": int(info), "r": list(map(float, r))}))


def capped(cmd, cap):
    """stdout of `cmd`, or None and why when it fails or runs past `cap` seconds."""
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, timeout=cap)
    except subprocess.TimeoutExpired:
        return None, f"over the {cap:g} s cap"
    if res.returncode != 0:
        lines = (res.stderr.strip() or res.stdout.strip() or "failed").splitlines()
        return None, lines[-1]
    return res.stdout, None


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--siconos":
        path, solver, cap, tol, repeat = sys.argv[2:7]
        siconos_one(path, solver, int(cap), float(tol), int(repeat))
        return
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("files", nargs="+")
    ap.add_argument("--ours", default=os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"),
                                                   "release/examples/fclib_table"))
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cap", type=float, default=60.0)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for path in a.files:
        stem = os.path.splitext(os.path.basename(path))[0]
        kind, dim, pieces = read(path)
        W, q, mu = condensed(kind, pieces)
        row = {"file": stem, "kind": kind, "dim": dim, "contacts": len(mu), "ours": [],
               "siconos": []}
        if kind == "global":
            row["dofs"] = pieces[0].shape[0]
        for alg in OURS:
            _, why = capped([a.ours, a.out, path, alg, "--tol", str(a.tol), "--repeat",
                             str(a.repeat)], a.cap)
            rr = {"algorithm": alg}
            if why is not None:
                rr["error"] = why
            else:
                with open(os.path.join(a.out, f"{stem}.{alg}.json")) as f:
                    run = json.load(f)
                row["read_ms"] = run["read_ms"]
                row["sparse"] = run["sparse"]
                rr["ms"] = run["ms"]
                if "r" in run:
                    rr.update(res=judge(W, q, mu, dim, np.array(run["r"])), picked=run["picked"],
                              iterations=run["iterations"], ours_res=run["residual"])
                else:
                    rr["error"] = run["error"]
            row["ours"].append(rr)
            print(stem, rr.get("algorithm"), rr.get("ms"), rr.get("res"), rr.get("error", ""),
                  file=sys.stderr, flush=True)
        for name, solver, cap in (LOCAL if kind == "local" else GLOBAL):
            out, why = capped([sys.executable, __file__, "--siconos", path, solver, str(cap),
                               str(a.tol), str(a.repeat)], a.cap)
            rs = {"solver": name}
            if why is not None:
                rs["error"] = why
            else:
                run = json.loads(out.strip().splitlines()[-1])
                rs.update(ms=run["ms"], info=run["info"], res=judge(W, q, mu, dim, np.array(run["r"])))
            row["siconos"].append(rs)
            print(stem, name, rs.get("ms"), rs.get("res"), rs.get("error", ""), file=sys.stderr,
                  flush=True)
        rows.append(row)
    with open(os.path.join(a.out, "table.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print_table(rows)


def cell(r):
    if "error" in r:
        return r["error"] if "cap" in r["error"] else "error"
    ms, res = r["ms"], r["res"]
    return f"{ms:.3g} ({res:.0e})" if res <= SOLVED else f"({ms:.3g}, res {res:.1e})"


def print_table(rows):
    print("| problem | kind | n_c | read ms | " + " | ".join(SHORT) + " | Auto / best | "
          "Siconos (ms (res), best first) | Siconos best / Auto |")
    print("|---|---|---|---|" + "---|" * (len(SHORT) + 3))
    for row in rows:
        by = {r["algorithm"]: r for r in row["ours"]}
        best = min((r["ms"] for a, r in by.items()
                    if a != "Auto" and r.get("res", 1.0) <= SOLVED), default=None)
        auto = by["Auto"]
        auto_ok = auto.get("res", 1.0) <= SOLVED
        ratio = f"{auto['ms'] / best:.2f}" if auto_ok and best else "-"
        sic = sorted(row["siconos"], key=lambda s: (s.get("res", 1.0) > SOLVED, s.get("ms", 1e99)))
        sic_txt = ", ".join(f"{s['solver']} {cell(s)}" for s in sic)
        sbest = [s["ms"] for s in sic if s.get("res", 1.0) <= SOLVED]
        vs = f"{min(sbest) / auto['ms']:.2f}" if sbest and auto_ok else "-"
        kind = row["kind"] + (f" ({row['dofs']} dofs)" if "dofs" in row else "")
        read_ms = f"{row['read_ms']:.3g}" if "read_ms" in row else "-"
        print(f"| {row['file']} | {kind} | {row['contacts']} | {read_ms} | "
              + " | ".join(cell(by[a]) for a in OURS) + f" | {ratio} | {sic_txt} | {vs} |")


if __name__ == "__main__":
    main()
