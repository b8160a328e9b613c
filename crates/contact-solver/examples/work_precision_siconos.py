#!/usr/bin/python3
"""Siconos' side of the local work-precision study (examples/work_precision_local.rs).

Usage (after the Rust example has written OUT/problems):
    OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/work_precision_siconos.py \
        [OUT] [--budget 120] [--max-nc 5000]
OUT defaults to target/work_precision_local. For every problem OUT/problems/NAME.meta.json
(+ NAME.W.f64, raw little-endian row-major W) it runs, with the tolerance swept from 1e-4 to
1e-12 (1e-10 first, then the others while the time spent on the (problem, solver) pair stays
under --budget seconds):
  - SICONOS_FRICTION_2D_NSGS   (fc2d_driver)
  - SICONOS_FRICTION_2D_LEMKE  (fc2d_driver; a pivoting method: its tolerance is not a
                                stopping rule, run once; n_c <= 1000)
  - SICONOS_FRICTION_3D_NSN_AC (fc3d_driver on the 2D problem embedded in 3D with a decoupled
                                second tangent, as ../shared/peers/siconos_fc.py does; n_c <= 1000)
and writes OUT/siconos.csv with the columns of OUT/ours.csv. The residual column is OUR
relative natural-map residual (docs/theory.md section 13) evaluated on Siconos' reaction, so
both sides are measured with one ruler; "error" is |r - r_ref|/|r_ref| with r_ref from
NAME.ref.json. Times: cold start, minimum over repetitions (at least 3, more while under 0.3 s,
at most 50; a single run when one takes over 20 s), time.perf_counter around the driver call (so they include the Python call overhead,
printed at the start: about a microsecond).
Needs apt-get install -y python3-siconos; not part of CI.
"""
import argparse, json, os, sys, time
import numpy as np

try:
    import siconos.numerics as sn
except ImportError:
    sys.exit("siconos is missing: apt-get install -y python3-siconos (and run with /usr/bin/python3)")

TOLERANCES = [1e-10, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-11, 1e-12]


def load(d, name):
    meta = json.load(open(os.path.join(d, name + ".meta.json")))
    q = np.asarray(meta["q"], float)
    mu = np.asarray(meta["mu"], float)
    m = len(q)
    W = np.fromfile(os.path.join(d, name + ".W.f64"), dtype="<f8").reshape(m, m)
    ref = json.load(open(os.path.join(d, name + ".ref.json")))["r"]
    return W, q, mu, np.asarray(ref, float)


def rho0(W):
    """1/lambda_max of each 2x2 diagonal block (uzawa.rs rho_of_block)."""
    a = np.diagonal(W)[0::2]; d = np.diagonal(W)[1::2]; b = np.diagonal(W, 1)[0::2]
    h = 0.5 * (a - d)
    return 1.0 / (0.5 * (a + d) + np.sqrt(h * h + b * b))


def natural_residual(W, q, mu, rho, r):
    """|r - P_K(r + rho v(W r + q))| / max(|r|, max(rho)|q|), De Saxce's v (reduced.rs)."""
    x = W @ r + q
    xn, xt = x[0::2], x[1::2]
    tn = r[0::2] + rho * (-(xn + mu * np.abs(xt)))
    tt = r[1::2] + rho * (-xt)
    att = np.abs(tt)
    sep = mu * att <= -tn
    stick = (~sep) & (att <= mu * tn)
    slip = ~(sep | stick)
    pn = np.where(sep, 0.0, np.where(stick, tn, (tn + mu * att) / (1 + mu * mu)))
    with np.errstate(invalid="ignore", divide="ignore"):
        pt = np.where(sep, 0.0, np.where(stick, tt, mu * pn * np.sign(tt)))
    d = np.concatenate([(r[0::2] - pn), (r[1::2] - pt)])
    denom = max(np.linalg.norm(r), rho.max() * np.linalg.norm(q), np.finfo(float).tiny)
    return np.linalg.norm(d) / denom


def embed_2d_in_3d(W, q, nc):
    W3 = np.zeros((3 * nc, 3 * nc)); q3 = np.zeros(3 * nc)
    idx = np.array([[3 * c, 3 * c + 1] for c in range(nc)]).ravel()
    W3[np.ix_(idx, idx)] = W
    W3[np.arange(2, 3 * nc, 3), np.arange(2, 3 * nc, 3)] = 1.0
    q3[idx] = q
    return W3, q3, idx


def timed(solve, prob, sid, tol, size):
    times = []
    start = time.perf_counter()
    while True:
        elapsed, n = time.perf_counter() - start, len(times)
        if n >= 50 or (n >= 3 and elapsed >= 0.3) or (n >= 1 and elapsed > 20.0):
            break
        so = sn.SolverOptions(sid)
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 1000000
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        r = np.zeros(size); u = np.zeros(size)
        t = time.perf_counter(); info = solve(prob, r, u, so); times.append(time.perf_counter() - t)
    times.sort()
    return (info, so.iparam[sn.SICONOS_IPARAM_ITER_DONE], 1e3 * times[0],
            1e3 * times[len(times) // 2], r, time.perf_counter() - start)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out", nargs="?", default="target/work_precision_local")
    ap.add_argument("--budget", type=float, default=120.0)
    ap.add_argument("--max-nc", type=int, default=5000)
    a = ap.parse_args()
    d = os.path.join(a.out, "problems")
    names = sorted(f[:-len(".meta.json")] for f in os.listdir(d) if f.endswith(".meta.json"))
    # Python call overhead: the driver on a one-contact problem that is solved at once.
    p1 = sn.FrictionContactProblem(2, 1, np.eye(2), np.array([1.0, 0.0]), np.array([0.3]))
    _, _, overhead, _, _, _ = timed(sn.fc2d_driver, p1, sn.SICONOS_FRICTION_2D_NSGS, 1e-10, 2)
    print(f"# call overhead (fc2d NSGS on a separated single contact): {overhead * 1e3:.1f} us",
          file=sys.stderr)
    rows = ["source,problem,n_c,solver,tol,time_ms,median_ms,residual,error,iterations,converged"]
    for name in names:
        W, q, mu, ref = load(d, name)
        nc = len(mu)
        if nc > a.max_nc:
            continue
        rho = rho0(W)
        ref_norm = max(np.linalg.norm(ref), np.finfo(float).tiny)
        p2 = sn.FrictionContactProblem(2, nc, W, q, mu)
        solvers = [("NSGS", sn.fc2d_driver, p2, sn.SICONOS_FRICTION_2D_NSGS, 2 * nc, None, TOLERANCES)]
        if nc <= 1000:
            solvers.append(("LEMKE", sn.fc2d_driver, p2, sn.SICONOS_FRICTION_2D_LEMKE, 2 * nc, None, [1e-10]))
            W3, q3, idx = embed_2d_in_3d(W, q, nc)
            p3 = sn.FrictionContactProblem(3, nc, W3, q3, mu)
            solvers.append(("NSN_AC", sn.fc3d_driver, p3, sn.SICONOS_FRICTION_3D_NSN_AC, 3 * nc, idx, TOLERANCES))
        for label, solve, prob, sid, size, idx, tols in solvers:
            spent = 0.0
            for tol in tols:
                if spent > a.budget:
                    print(f"{name} {label}: budget spent, tol {tol:g} skipped", file=sys.stderr)
                    continue
                info, it, ms, med, r, took = timed(solve, prob, sid, tol, size)
                spent += took
                r2 = r[idx] if idx is not None else r
                res = natural_residual(W, q, mu, rho, r2)
                err = np.linalg.norm(r2 - ref) / ref_norm
                print(f"{name:18s} {label:7s} tol {tol:7.0e}: {ms:10.4f} ms (median {med:10.4f}) "
                      f"status {info} iters {it} residual {res:.2e} error {err:.1e}", file=sys.stderr)
                rows.append(f"siconos,{name},{nc},{label},{tol:e},{ms},{med},{res:e},{err:e},{it},{info == 0}")
            with open(os.path.join(a.out, "siconos.csv"), "w") as f:
                f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
