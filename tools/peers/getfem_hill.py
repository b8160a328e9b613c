#!/usr/bin/python3
"""GetFEM peer for Hill's thick cylinder (plane strain, von Mises, perfect plasticity; issue 40).

Reads the JSON written by our example on the very same mesh,

    cargo run -p fem-core --example hill_cylinder -- hill.json
    /usr/bin/python3 tools/peers/getfem_hill.py hill.json [--max-res 1e-8] [--noisy]

and runs GetFEM's small-strain elastoplasticity brick ('plane strain Prandtl Reuss',
DISPLACEMENT_ONLY: return mapping inside GetFEM's Newton, model.solve with its default
linear solver) on it: the quarter ring a <= r <= b of P2 triangles (FEM_PK(2,2) on the
curved GT_PK(2,2) geometry, IM_TRIANGLE(2): the same 3-point rule as ours), u_y = 0 on
y = 0 and u_x = 0 on x = 0 (normal Dirichlet conditions with multipliers), the pressure p
on r = a, in the same load steps as ours (`steps_per_level` equal steps to each level).
Yield: ||dev sigma|| <= sqrt(2/3) sigma_y with sigma_y = sqrt(3) k (von Mises with shear
yield stress k, as ours).

Prints one JSON line per level, ours beside GetFEM's: the inner-radius displacement u_r(a)
at (a, 0), the elastic-plastic radius (between the outermost integration point with a
plastic strain and the innermost one without, beyond it; the same reading as ours), Hill's
radius, Newton iterations per step and wall times (GetFEM: the model's assembly and the
solves of that level; ours: the Newton path of that level, from the JSON).
"""
import argparse
import json
import math
import time

import numpy as np
import getfem as gf


def hill_radius(p, a, b, k):
    """c with p = k (2 ln(c/a) + 1 - c^2/b^2), by bisection."""
    lo, hi = a, b
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if k * (2 * math.log(mid / a) + 1 - mid * mid / (b * b)) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def faces_where(mesh, keep):
    """The outer faces whose points all satisfy keep(x, y)."""
    faces = mesh.outer_faces()
    pts = mesh.pts()
    chosen = []
    for j in range(faces.shape[1]):
        pid = mesh.pid_in_faces(faces[:, j:j + 1])
        if all(keep(pts[0, i], pts[1, i]) for i in pid):
            chosen.append(faces[:, j])
    return np.array(chosen).T


def run(case, max_res, noisy=False):
    a, b, k = case["a"], case["b"], case["k"]
    young, nu = case["young"], case["poisson"]
    lam = young * nu / ((1 + nu) * (1 - 2 * nu))
    mu = young / (2 * (1 + nu))
    nodes = np.array(case["nodes"], float)
    tri = np.array(case["triangles"], int)
    t0 = time.perf_counter()
    mesh = gf.Mesh("empty", 2)
    gt = gf.GeoTrans("GT_PK(2,2)")
    # points of every convex: 2 x 6 x n
    pts = np.transpose(nodes[tri], (2, 1, 0))
    mesh.add_convex(gt, pts)
    tol = 1e-9
    INNER, BOTTOM, LEFT = 1, 2, 3
    mesh.set_region(INNER, faces_where(mesh, lambda x, y: abs(math.hypot(x, y) - a) < tol))
    mesh.set_region(BOTTOM, faces_where(mesh, lambda x, y: abs(y) < tol))
    mesh.set_region(LEFT, faces_where(mesh, lambda x, y: abs(x) < tol))

    mf_u = gf.MeshFem(mesh, 2)
    mf_u.set_fem(gf.Fem("FEM_PK(2,2)"))
    mf_m = gf.MeshFem(mesh, 1)
    mf_m.set_fem(gf.Fem("FEM_PK(2,2)"))
    mim = gf.MeshIm(mesh, gf.Integ("IM_TRIANGLE(2)"))
    mimd_t = gf.MeshImData(mim, -1, [2, 2])
    mimd_s = gf.MeshImData(mim, -1, [1])

    md = gf.Model("real")
    md.add_fem_variable("u", mf_u)
    md.add_fem_data("Previous_u", mf_u)
    md.add_im_data("xi", mimd_s)
    md.add_im_data("Previous_xi", mimd_s)
    md.add_im_data("Previous_Ep", mimd_t)
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [mu])
    md.add_initialized_data("sigma_y", [math.sqrt(3.0) * k])
    md.add_initialized_data("p", [0.0])
    md.set_time_step(1.0)
    law = ("plane strain Prandtl Reuss", 0, "u", "xi", "Previous_Ep",
           "lambda", "mu", "sigma_y", "1", "timestep")
    md.add_small_strain_elastoplasticity_brick(mim, *law)
    # the pressure pushes the inner surface outwards: t = -p n (n the outward normal)
    md.add_source_term(mim, "-p*(Normal.Test_u)", INNER)
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mf_m, BOTTOM)
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mf_m, LEFT)
    build = time.perf_counter() - t0

    probe = np.array([[a], [0.0]])
    levels = []
    p_done = 0.0
    for level in case["ours"]["levels"]:
        p_level = level["pressure"]
        n = case["steps_per_level"]
        its = []
        t = time.perf_counter()
        for s in range(1, n + 1):
            md.set_variable("p", [p_done + (p_level - p_done) * s / n])
            out = md.solve("max_res", max_res, "max_iter", 40, *(["noisy"] if noisy else []))
            its.append(int(out[0]) if isinstance(out, (tuple, list)) else int(out))
            md.small_strain_elastoplasticity_next_iter(mim, *law)
        seconds = time.perf_counter() - t
        p_done = p_level
        u_inner = float(md.interpolation("u", probe, mesh)[0])
        levels.append({"pressure": p_level, "u_inner": u_inner, "iterations": its,
                       "seconds": seconds,
                       "plastic_radius": plastic_radius_getfem(md, mimd_s, a, b)})
    return levels, build


def plastic_radius_getfem(md, mimd_s, a, b):
    x = np.reshape(md.interpolation("X(1)", mimd_s), (-1,))
    y = np.reshape(md.interpolation("X(2)", mimd_s), (-1,))
    ep = np.reshape(md.interpolation("Norm(Previous_Ep)", mimd_s), (-1,))
    r = np.hypot(x, y)
    yielded = r[ep > 0.0]
    outer = max(yielded.max() if yielded.size else a, a)
    beyond = r[(ep == 0.0) & (r > outer)]
    inner = beyond.min() if beyond.size else b
    return 0.5 * (outer + inner)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--max-res", type=float, default=1e-8)
    ap.add_argument("--noisy", action="store_true")
    args = ap.parse_args()
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    with open(args.case) as f:
        case = json.load(f)
    a, b, k = case["a"], case["b"], case["k"]
    t0 = time.perf_counter()
    levels, build = run(case, args.max_res, args.noisy)
    total = time.perf_counter() - t0
    for ours, theirs in zip(case["ours"]["levels"], levels):
        p = ours["pressure"]
        print(json.dumps({
            "p": p,
            "hill_radius": round(hill_radius(p * k, a, b, k), 6),
            "ours": {key: ours[key] for key in ("u_inner", "plastic_radius", "iterations",
                                                 "seconds")},
            "getfem": theirs,
            "u_inner_rel_diff": (ours["u_inner"] - theirs["u_inner"]) / theirs["u_inner"],
        }))
    print(json.dumps({"ours_total_seconds": case["ours"]["total_seconds"],
                      "getfem_total_seconds": total, "getfem_build_seconds": build}))


if __name__ == "__main__":
    main()
