#!/usr/bin/python3
"""Siconos peer for the impacting bar (issue 39): the same mesh, mass, step and theta as ours.

Our side is `crates/contact-solver/examples/moreau_jean_bar.rs` (P2 strip L = 1 x 0.1, plane
stress, E = rho = 1, nu = 0, consistent mass, v0 = 0.1 onto a rigid wall at x = 0, Moreau-Jean
theta = 1/2, e = 0). It writes the free dofs' M and K (triplets), the contact dofs (the x dof
of each node on x = 0), v0, h, theta, e, and its own contact-force history, mean-velocity
history and in-process time. This script reads that file and runs siconos.kernel on the same
matrices: LagrangianLinearTIDS(q0 = 0, v0, M, K, C = 0), one LagrangianLinearTIR (H = e_i,
b = 0: the gap is u_x) and NewtonImpactNSL(e) per contact dof, MoreauJeanOSI(theta),
TimeStepping with an LCP (Siconos' default, Lemke), then compares point by point:
  - the contact force sum_i lambda_i(1) / h after each step (lambda(1) is Siconos' impulse),
    relative to the peak force;
  - the mean velocity 1^T M v / m along x after each step (the rebound is the last one);
and prints both in-process times (ours: the example's median; Siconos: the median of
--repeat runs from the DynamicalSystem's construction to the last step).

Usage (Debian's Python, which sees python3-siconos):
    cargo build --release -p contact-solver --example moreau_jean_bar
    /usr/bin/python3 tools/peers/siconos_bar.py [--json out/moreau_jean_bar.json]
        [--example target/release/examples/moreau_jean_bar] [--nx 100] [--h 0.005]
        [--steps 520] [--repeat 3] [--no-run]
--no-run reads an existing JSON instead of running the example first.

Index sets: Siconos' MoreauJeanOSI activates an interaction when y + gamma h ydot <= 0 at the
start of the step (gamma = 1/2 by default); ours when g_k + h (1 - theta) v_n,k <= 0: the same
rule at theta = 1/2. Both apply Newton's law on v_n + e v_n,k.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np
import siconos.kernel as sk


def dense(n, triplets):
    a = np.zeros((n, n))
    for i, j, v in triplets:
        a[i, j] = v
    return a


def run_siconos(case, m, k):
    n, h, theta, e, steps = case["n"], case["h"], case["theta"], case["e"], case["steps"]
    v0 = np.array(case["v0"])
    ds = sk.LagrangianLinearTIDS(np.zeros(n), v0, m, k, np.zeros((n, n)))
    nsds = sk.NonSmoothDynamicalSystem(0.0, steps * h)
    nsds.insertDynamicalSystem(ds)
    inters = []
    for dof in case["contact_dofs"]:
        hmat = np.zeros((1, n))
        hmat[0, dof] = 1.0
        inter = sk.Interaction(sk.NewtonImpactNSL(e), sk.LagrangianLinearTIR(hmat))
        nsds.link(inter, ds)
        inters.append(inter)
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(theta),
                          sk.LCP())
    ones_x = np.array([1.0 if i % 2 == 0 else 0.0 for i in range(n)])
    m1 = m @ ones_x
    total = m1 @ ones_x
    force, velocity = [], []
    for _ in range(steps):
        sim.computeOneStep()
        force.append(sum(inter.lambda_(1)[0] for inter in inters) / h)
        velocity.append(m1 @ ds.velocity() / total)
        sim.nextStep()
    return np.array(force), np.array(velocity)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--json", default="out/moreau_jean_bar.json")
    p.add_argument("--example", default=None,
                   help="our binary (default: $CARGO_TARGET_DIR or target, release)")
    p.add_argument("--nx", type=int, default=100)
    p.add_argument("--h", type=float, default=0.005)
    p.add_argument("--steps", type=int, default=520)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--no-run", action="store_true")
    args = p.parse_args()

    if not args.no_run:
        exe = args.example or os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"),
                                           "release", "examples", "moreau_jean_bar")
        subprocess.run([exe, args.json, str(args.nx), str(args.h), str(args.steps), "5"],
                       check=True)
    with open(args.json) as f:
        case = json.load(f)
    n = case["n"]
    m, k = dense(n, case["mass"]), dense(n, case["stiffness"])

    times, result = [], None
    for _ in range(max(1, args.repeat)):
        start = time.perf_counter()
        result = run_siconos(case, m, k)
        times.append((time.perf_counter() - start) * 1e3)
    force, velocity = result
    ours_f = np.array(case["ours"]["force"])
    ours_v = np.array(case["ours"]["velocity"])
    peak = max(np.abs(force).max(), 1e-300)
    df = np.abs(force - ours_f)
    worst = int(df.argmax())
    dv = np.abs(velocity - ours_v).max() / abs(case["v0"][0])
    ms_siconos = float(np.median(times))
    ms_ours = case["ours"]["ms"]
    on = np.nonzero(force > 1e-6 * peak)[0]
    on_ours = np.nonzero(ours_f > 1e-6 * peak)[0]
    out = {
        "n": n, "nx": case["nx"], "h": case["h"], "steps": case["steps"],
        "contacts": len(case["contact_dofs"]),
        "peak_force": {"ours": float(ours_f.max()), "siconos": float(force.max())},
        "contact_steps": {"ours": [int(on_ours[0]), int(on_ours[-1])] if len(on_ours) else [],
                          "siconos": [int(on[0]), int(on[-1])] if len(on) else []},
        "max_force_diff_over_peak": float(df.max() / peak),
        "at_step": worst,
        "rebound": {"ours": float(ours_v[-1]), "siconos": float(velocity[-1])},
        "max_velocity_diff_over_v0": float(dv),
        "ms": {"ours": ms_ours, "siconos": ms_siconos},
        "speedup": ms_siconos / ms_ours,
    }
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
