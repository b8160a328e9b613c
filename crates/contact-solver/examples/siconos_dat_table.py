#!/usr/bin/python3
"""Siconos `.dat` problems solved by ours and by Siconos, judged by one residual computed
outside both (issue 37; the table of docs/benchmarks.md).

Usage:
    cargo build --release -p contact-solver --example siconos_dat_table
    OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/siconos_dat_table.py \
        OUT FILE.dat|DIR ... [--ours target/release/examples/siconos_dat_table] [--tol 1e-8] [--repeat 3]
        [--timeout 60] [--before OTHER_BUILD]

For each file (folders: every .dat in them; smallest first), first ours (the example, one
process per algorithm and one for Auto, timed
in-process, the read apart), then Siconos' solvers in this process (read with Siconos' own
reader, in-process times of the driver call, median of --repeat, one run when the first takes
over 2 s, cold start r = 0, at most 10000 iterations for the Gauss-Seidel and 1000 for Newton,
as in Siconos' own tests; every run, ours and theirs, killed after --timeout seconds):
local 3D: FRICTION_3D_NSGS, NSN_AC, NSN_FB; local 2D: FRICTION_2D_NSGS, LEMKE, CPG; global 3D:
GLOBAL_FRICTION_3D_NSGS_WR, NSN_AC_WR, NSN_AC.

The judge ("res"): on W, q read by Siconos (scipy, via NM_triplet; a global problem condensed
here, W = H^T M^-1 H, q = H^T M^-1 q_g + b, with scipy's sparse LU), u = W r + q and De Saxce's
modified velocity w = u + mu ||u_T|| e_N; res = ||r - P_K(r - w)||_2 / max(||q||_2, 1e-300), the
natural map of Siconos' fc3d_compute_error with rho = 1, the same number for every answer.
Solved: res <= 1e-6. Prints a Markdown table and writes OUT/table.json. With --before, a
second build's Auto also runs on each file, right before or after ours (alternating), and a
before/after table follows.
Needs python3-siconos, python3-scipy; not part of CI.
"""
import argparse
import json
import glob
import os
import pickle
import select
import signal
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


def forked(fn, cap_s):
    """fn() in a forked child killed after cap_s seconds: its result, or None on a time-out or
    when the child dies (Siconos' reader ends the process on a file it cannot read)."""
    rd, wr = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: run, send the answer, leave without cleaning up
        os.close(rd)
        quiet = os.open(os.devnull, os.O_WRONLY)
        os.dup2(quiet, 1)  # Siconos' C code prints problems it reads to stdout
        try:
            data = pickle.dumps(fn())
        except BaseException:  # noqa: BLE001  (any failure is "no answer")
            data = b""
        with os.fdopen(wr, "wb") as f:
            f.write(data)
        os._exit(0)
    os.close(wr)
    chunks, deadline = [], time.monotonic() + cap_s
    with os.fdopen(rd, "rb") as f:
        while True:
            left = deadline - time.monotonic()
            ready, _, _ = select.select([f], [], [], max(left, 0))
            if not ready:
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                return None
            chunk = f.read1(1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
    os.waitpid(pid, 0)
    data = b"".join(chunks)
    return pickle.loads(data) if data else None


def capped(run, repeat, cap_s):
    """`timed(run, repeat)` in a child killed after cap_s seconds: (ms, (info, r)) or None."""
    def child():
        ms, (info, r) = timed(run, repeat)
        return ms, (int(info), np.asarray(r, float))
    return forked(child, cap_s)


def options(solver, tol, cap):
    so = sn.SolverOptions(solver)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = cap
    so.dparam[sn.SICONOS_DPARAM_TOL] = tol
    return so


def siconos_local(path, tol, repeat, cap_s):
    p = sn.frictionContact_new_from_filename(path)
    dim, nc = p.dimension, p.numberOfContacts
    m = dim * nc
    W = sn.NM_triplet(p.M).tocsr()
    q, mu = np.array(p.q, float), np.array(p.mu, float)
    if dim == 3:
        solvers = [("NSGS", sn.SICONOS_FRICTION_3D_NSGS, 10000, sn.fc3d_driver),
                   ("NSN-AC", sn.SICONOS_FRICTION_3D_NSN_AC, 1000, sn.fc3d_driver),
                   ("NSN-FB", sn.SICONOS_FRICTION_3D_NSN_FB, 1000, sn.fc3d_driver)]
    else:
        solvers = [("NSGS-2D", sn.SICONOS_FRICTION_2D_NSGS, 10000, sn.fc2d_driver),
                   ("Lemke-2D", sn.SICONOS_FRICTION_2D_LEMKE, 10000, sn.fc2d_driver),
                   ("CPG-2D", sn.SICONOS_FRICTION_2D_CPG, 10000, sn.fc2d_driver)]
    runs = []
    for name, solver, cap, driver in solvers:
        def run():
            r, u = np.zeros(m), np.zeros(m)
            info = driver(p, r, u, options(solver, tol, cap))
            return info, r
        runs.append(siconos_run(name, capped(run, repeat, cap_s), cap_s))
    return (W, q, mu, dim), runs


def siconos_run(name, out, cap_s):
    if out is None:
        return {"solver": name, "error": f"time-out (> {cap_s:g} s) or crash"}
    ms, (info, r) = out
    return {"solver": name, "ms": ms, "info": info, "r": r}


def siconos_global(path, tol, repeat, cap_s):
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
    for name, solver, cap in [("NSGS-WR", sn.SICONOS_GLOBAL_FRICTION_3D_NSGS_WR, 10000),
                              ("NSN-AC-WR", sn.SICONOS_GLOBAL_FRICTION_3D_NSN_AC_WR, 1000),
                              ("NSN-AC (global)", sn.SICONOS_GLOBAL_FRICTION_3D_NSN_AC, 1000)]:
        def run():
            r, u, v = np.zeros(m), np.zeros(m), np.zeros(n)
            info = sn.gfc3d_driver(p, r, u, v, options(solver, tol, cap))
            return info, r
        runs.append(siconos_run(name, capped(run, repeat, cap_s), cap_s))
    return (W, q, mu, dim), runs


ALGORITHMS = ["Uzawa", "GaussSeidel", "ClassicRccm", "AndersonGaussSeidel", "AndersonUzawa",
              "Newton", "Auto"]
SHORT = dict(zip(ALGORITHMS, ["Uzawa", "GS", "Classic", "AGS", "AU", "Newton", "Auto"]))

# What Siconos' own tests (beside the data, siconos 4.4.0 numerics/src/FrictionContact/test)
# expect to pass on each file: solver and tolerance in Siconos' own (relative) measure.
C1 = "NSGS, NSN-AC 1e-5 (data_collection_1: test_nsgs_1, test_nsn_1)"
EXPECTED = {
    **{f: C1 for f in ["FC3D_Example1", "FC3D_Example1_SBM", "FrictionContact3D_1c",
                       "FrictionContact3D_RR_1c", "NESpheres_10_1", "NESpheres_30_1",
                       "Confeti-ex13-Fc3D-SBM", "Rover1039", "Rover1040", "Rover1041",
                       "Rover11035", "Rover11211", "Rover3865", "Rover4144", "Rover4493",
                       "Rover4516", "Rover4609", "Rover4613", "Rover4622", "Rover9770"]},
    **{f: "NSGS 1e-5, NSN-AC 1e-5 with MUMPS only (test_nsgs_1, test_nsn_1)"
       for f in ["Capsules-i100-1090", "Capsules-i100-889", "Capsules-i101-404",
                 "Capsules-i103-990", "Capsules-i122-1617"]},
    "Rover4396": "NSN-AC 1e-5, NSN-FB 1e-3 (test_nsn_3)",
    "BoxesStack1-i100000-32.hdf5": "NSN-AC 1e-3; NSN-FB expected to fail (test_nsn_3)",
    "KaplasTower-i1061-4.hdf5": "NSN-FB 1e-3 (500 it.); NSN-AC unstable (test_nsn_2)",
    "RockPile_tob1": "NSN-FB 5e-2; NSN-AC unstable (test_nsn_2)",
    "Confeti-ex03-Fc3D-SBM": "NSGS 1e-5 expected to fail with most local solvers (test_nsgs_3)",
    "Confeti-ex13-4contact-Fc3D-SBM": "NSGS 1e-12 with some local solvers (test_nsgs_3)",
    "GFC3D_TwoRods1-condensed": "NSGS 1e-12 (test_nsgs_3)",
    "OneObject-i100000-499.hdf5": "data_collection_3/5 (test_nsgs_5, test_vi_based_1)",
    **{f: "NSGS-2D, Lemke, CPG 1e-5 (test_fc2d_1)"
       for f in ["FrictionContactProblem00374", "FrictionContactProblem00394",
                 "FrictionContactProblem00727", "FrictionContactProblem00031",
                 "FrictionContactProblem00071", "FrictionContactProblem00237",
                 "FC2D_SliderCrankLagrangian00000", "FC2D_SliderCrankLagrangian00001"]},
    **{f: "NSGS-WR, NSN-AC, NSN-AC-WR 1e-5 (test_solvers_wr_gfc3d_1, test_nsn_gfc3d_1)"
       for f in ["GFC3D_Example0", "GFC3D_Example00", "GFC3D_Example00_badly_scaled",
                 "GFC3D_Example1", "GFC3D_OneContact", "GFC3D_TwoRods1"]},
}


def ours_run(a, path, alg, binary=None, out=None):
    """One algorithm of ours in its own process, killed after --timeout seconds."""
    stem = os.path.splitext(os.path.basename(path))[0]
    binary, out = binary or a.ours, out or a.out
    cmd = [binary, out, path, "--tol", str(a.tol), "--repeat", str(a.repeat), "--only", alg]
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout)
    except subprocess.TimeoutExpired:
        return None, {"algorithm": alg, "error": f"time-out (> {a.timeout:g} s)"}
    if res.returncode != 0:
        lines = (res.stderr.strip() or f"exit {res.returncode}").splitlines()
        return lines[-1], None
    with open(os.path.join(out, f"{stem}.{alg}.ours.json")) as f:
        data = json.load(f)
    return None, data


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("files", nargs="*", help=".dat files, or folders (every .dat in them)")
    ap.add_argument("--ours", default="target/release/examples/siconos_dat_table")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=60.0,
                    help="seconds for each run (one algorithm of ours, one Siconos solver)")
    ap.add_argument("--before", default=None,
                    help="a second build of the example: its Auto runs beside ours on each "
                         "file (alternating which runs first), for a before/after table")
    ap.add_argument("--table", action="store_true",
                    help="only print the table of OUT/table.json (an earlier run)")
    a = ap.parse_args()
    if a.table:
        with open(os.path.join(a.out, "table.json")) as f:
            rows = json.load(f)
        print_table(rows)
        if any("auto_before" in row for row in rows):
            print_before_after(rows)
        return
    os.makedirs(a.out, exist_ok=True)
    files = []
    for f in a.files:
        files += sorted(glob.glob(os.path.join(f, "*.dat"))) if os.path.isdir(f) else [f]
    files.sort(key=os.path.getsize)
    rows, seen = [], {}
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0]
        with open(path, "rb") as f:
            content = f.read()
        if seen.get(stem) == content:  # the same file in two folders
            continue
        seen[stem] = content
        before = None
        if a.before and len(seen) % 2 == 0:
            before = ours_run(a, path, "Auto", a.before, os.path.join(a.out, "before"))[1]
        refused, auto = ours_run(a, path, "Auto")
        if a.before and before is None:
            before = ours_run(a, path, "Auto", a.before, os.path.join(a.out, "before"))[1]
        if refused is not None:
            rows.append({"file": stem, "refused": refused})
            print(f"{stem}: refused: {refused}", flush=True)
            continue
        ours = []
        for alg in ALGORITHMS[:-1]:
            err, run = ours_run(a, path, alg)
            ours.append(run["runs"][0] if "runs" in run else run)
        info = auto or {}
        if "runs" in info:
            ours.append(info["runs"][0])
        else:
            ours.append(info)
        glob_ = info.get("source", "local").startswith("global")
        side = siconos_global if glob_ else siconos_local
        out = forked(lambda: side(path, a.tol, a.repeat, a.timeout), 4 * a.timeout + 60)
        if out is None:
            rows.append({"file": stem, "refused": "Siconos could not read it (or timed out)"})
            continue
        (W, q, mu, dim), theirs = out
        row = {"file": stem, "source": info.get("source", "?"), "dim": dim, "contacts": len(mu),
               "read_ms": info.get("read_ms"), "ours": [], "siconos": [],
               "expected": EXPECTED.get(stem, "")}
        for run in ours:
            rr = {"algorithm": run["algorithm"], "ms": run.get("ms")}
            if "r" in run:
                rr.update(res=judge(W, q, mu, dim, np.array(run["r"])), picked=run["picked"],
                          iterations=run["iterations"], converged=run["converged"])
            else:
                rr["error"] = run["error"]
            row["ours"].append(rr)
        if before is not None:
            run = before["runs"][0] if "runs" in before else before
            rb = {"algorithm": "Auto", "ms": run.get("ms")}
            if "r" in run:
                rb.update(res=judge(W, q, mu, dim, np.array(run["r"])), picked=run["picked"],
                          iterations=run["iterations"])
            else:
                rb["error"] = run["error"]
            row["auto_before"] = rb
        for run in theirs:
            sr = {k: v for k, v in run.items() if k != "r"}
            if "r" in run:
                sr["res"] = judge(W, q, mu, dim, run["r"])
            row["siconos"].append(sr)
        rows.append(row)
        print(one_row(row), flush=True)
        with open(os.path.join(a.out, "table.json"), "w") as f:
            json.dump(rows, f, indent=1)
    with open(os.path.join(a.out, "table.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print_table(rows)
    if a.before:
        print_before_after(rows)


def print_before_after(rows):
    """Auto of --before against ours, each over our best (the fastest of our six algorithms,
    of this build, whose answer the judge accepts)."""
    print("\n| problem | n_c | our best: ms | Auto before: picked ms | Auto after: picked ms "
          "| before / best | after / best |")
    print("|---|---|---|---|---|---|---|")

    def txt(r):
        if "error" in r:
            return r["error"][:40], None
        picked = SHORT.get(r["picked"].split(" (")[0], r["picked"][:30])
        ok = r.get("res", np.inf) <= SOLVED
        return f"{picked} {r['ms']:.3g}" + ("" if ok else f" (res {r['res']:.1e})"), ok
    for row in rows:
        if "refused" in row or "auto_before" not in row:
            continue
        best = best_of([r for r in row["ours"] if r["algorithm"] != "Auto"], "algorithm")
        auto = next(r for r in row["ours"] if r["algorithm"] == "Auto")
        (tb, okb), (ta, oka) = txt(row["auto_before"]), txt(auto)
        rb = f"{row['auto_before']['ms'] / best['ms']:.2f}" if best and okb else "-"
        ra = f"{auto['ms'] / best['ms']:.2f}" if best and oka else "-"
        bt = f"{SHORT[best['algorithm']]} {best['ms']:.3g}" if best else "none"
        print(f"| {row['file']} | {row['contacts']} | {bt} | {tb} | {ta} | {rb} | {ra} |")


def cell(ms, res):
    return f"{ms:.3g}" if res <= SOLVED else f"({ms:.3g}, res {res:.1e})"


def best_of(runs, key):
    ok = [r for r in runs if r.get("res", np.inf) <= SOLVED]
    return min(ok, key=lambda r: r["ms"]) if ok else None


def failure(r, key):
    if "error" in r:
        return f"{SHORT.get(r[key], r[key])}: {r['error'].split(',')[0]}"
    return f"{SHORT.get(r[key], r[key])}: res {r['res']:.1e}"


def one_row(row):
    if "refused" in row:
        return f"| {row['file']} | refused: {row['refused']} |"
    mine = [r for r in row["ours"] if r["algorithm"] != "Auto"]
    best = best_of(mine, "algorithm")
    auto = next(r for r in row["ours"] if r["algorithm"] == "Auto")
    sbest = best_of(row["siconos"], "solver")
    best_txt = (f"{SHORT[best['algorithm']]} {best['ms']:.3g} ({best['res']:.1e})"
                if best else "none")
    if "error" in auto:
        auto_txt = auto["error"][:60]
    else:
        picked = auto["picked"].split(" (")[0]
        if picked.startswith("failed"):  # the error's best iterate
            why = "stalled" if "stalled" in picked else "not converged"
            picked = f"error ({why}), best iterate:"
        auto_txt = f"{SHORT.get(picked, picked)} {auto['ms']:.3g} ({auto['res']:.1e})"
    auto_ok = auto.get("res", np.inf) <= SOLVED
    ratio = f"{auto['ms'] / best['ms']:.2f}" if auto_ok and best else "-"
    sic_txt = (f"{sbest['solver']} {sbest['ms']:.3g} ({sbest['res']:.1e})" if sbest else "none")
    vs = f"{sbest['ms'] / auto['ms']:.2f}" if sbest and auto_ok else "-"
    bad = [r for r in row["ours"] if r.get("res", np.inf) > SOLVED]
    symmetric = [SHORT[r["algorithm"]] for r in bad if "needs a symmetric W" in r.get("error", "")]
    fails = [f"{', '.join(symmetric)}: need a symmetric W"] if symmetric else []
    fails += [failure(r, "algorithm") for r in bad
              if "needs a symmetric W" not in r.get("error", "")]
    fails += ["Siconos " + failure(r, "solver") for r in row["siconos"]
              if r.get("res", np.inf) > SOLVED]
    kind = f"{row['source']}, {row['dim']}D"
    return (f"| {row['file']} | {kind} | {row['contacts']} | {best_txt} | {auto_txt} | {ratio} | "
            f"{sic_txt} | {vs} | {'; '.join(fails) or '-'} |")


def print_table(rows):
    print("| problem | kind | n_c | our best: ms (res) | Auto: picked ms (res) | Auto / best | "
          "Siconos best: ms (res) | Siconos best / Auto | fails |")
    print("|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        if "refused" not in row:
            print(one_row(row))
    print("\nRefused:")
    for row in rows:
        if "refused" in row:
            print(f"- `{row['file']}`: {row['refused']}")


if __name__ == "__main__":
    main()
