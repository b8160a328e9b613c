#!/usr/bin/python3
"""GetFEM peer for the 3D Hertz quarter model (rigid ball pressed into an elastic block).

Block [0,Lx]x[0,Ly]x[z0,0] on the tensor grid xs, ys, zs (each cell split into 6
tetrahedra by GetFEM's 'regular simplices'), P2 Lagrange displacement, small-strain
isotropic elasticity (E, nu).  u_x = 0 on x = 0, u_y = 0 on y = 0, u_z = d on z = z0.
Frictionless contact of the top face z = 0 with the rigid sphere of radius R centred at
(0, 0, R); GetFEM's obstacle is the signed distance, positive outside the sphere.

Usage:
    /usr/bin/python3 getfem_hertz3d.py [case.json] [--refine N] [--brick nodal|integral]
        [--r R_AUG] [--aug 1|2|3] [--lsolver mumps|superlu|auto] [--max-iter N]
        [--max-res RES] [--noisy] [--fine N]

case.json = {"xs": [...], "ys": [...], "zs": [...], "R": 10, "E": 1000, "nu": 0.3,
             "d": 0.04}; without it the default graded case is used.  --refine N
halves every grid interval N times.  Prints one JSON line with the results.

Defaults: nodal contact brick (add_nodal_contact_with_rigid_obstacle_brick, one
multiplier per top-face P2 node, normal = obstacle normal at the reference node),
non-symmetric Alart-Curnier (aug 1), r = E, GetFEM's Newton (model.solve) with MUMPS.
Forces are read from f = K u (z components): P_q on the top face, checked against the
bottom reaction.  a_fe = largest sqrt(x^2+y^2) of a top node with a nonzero multiplier
(nodal) or with pressure above 5% of the peak (integral, heuristic).
Seen with Debian's GetFEM 5.4.2: 'superlu' segfaults on these systems; nodal aug 3
does not converge (100 iterations, wrong sign); aug 2 converges, slower.
"""
import argparse
import json
import math
import sys
import time

import numpy as np
import getfem as gf


def default_case():
    r = (4.0 / 0.9) ** 0.25
    xs = [0.0, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9] + [0.9 * r ** k for k in range(1, 5)]
    s = (4.0 / 0.6) ** 0.25
    zpos = [0.0, 0.15, 0.3, 0.45, 0.6] + [0.6 * s ** k for k in range(1, 5)]
    zs = sorted(-z for z in zpos)
    return {"xs": xs, "ys": list(xs), "zs": zs, "R": 10.0, "E": 1000.0, "nu": 0.3,
            "d": 0.04}


def fine_case(n):
    """The grid of `examples/hertz_3d.rs --fine n`: n fine cells to 0.9 in x, y, m = (2n+1)//3
    fine cells to 0.6 in depth, m geometric cells beyond each (n = 6 is the default case)."""
    m = (2 * n + 1) // 3

    def graded(l, nf, fine, nc):
        v = [fine * i / nf for i in range(nf + 1)]
        r = (l / fine) ** (1.0 / nc)
        return v + [fine * r ** k for k in range(1, nc + 1)]

    xs = graded(4.0, n, 0.9, m)
    zs = sorted(-z for z in graded(4.0, m, 0.6, m))
    return {"xs": xs, "ys": list(xs), "zs": zs, "R": 10.0, "E": 1000.0, "nu": 0.3,
            "d": 0.04}


def refine(v):
    v = np.asarray(v, float)
    out = np.empty(2 * len(v) - 1)
    out[0::2] = v
    out[1::2] = 0.5 * (v[:-1] + v[1:])
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", nargs="?")
    ap.add_argument("--refine", type=int, default=0)
    ap.add_argument("--fine", type=int, default=None,
                    help="the grid of examples/hertz_3d.rs --fine N (10: ~1e5 DOF)")
    ap.add_argument("--brick", choices=["nodal", "integral"], default="nodal")
    ap.add_argument("--r", type=float, default=None,
                    help="augmentation parameter (default: E)")
    ap.add_argument("--aug", type=int, default=1,
                    help="nodal: 1 nonsym. Alart-Curnier, 2 symmetric, 3 new unsym.; "
                         "integral: option 1..4")
    ap.add_argument("--lsolver", default="mumps")
    ap.add_argument("--max-iter", type=int, default=100)
    ap.add_argument("--max-res", type=float, default=1e-9)
    ap.add_argument("--noisy", action="store_true")
    ap.add_argument("--dump", default=None, help="save top-face nodal data (.npz)")
    a = ap.parse_args()

    case = default_case() if a.fine is None else fine_case(a.fine)
    if a.case:
        with open(a.case) as f:
            case.update(json.load(f))
    xs, ys, zs = (np.asarray(case[k], float) for k in ("xs", "ys", "zs"))
    for _ in range(a.refine):
        xs, ys, zs = refine(xs), refine(ys), refine(zs)
    R, E, nu, d = (float(case[k]) for k in ("R", "E", "nu", "d"))
    assert abs(zs[-1]) < 1e-14 and abs(xs[0]) < 1e-14 and abs(ys[0]) < 1e-14
    r_aug = E if a.r is None else a.r

    t0 = time.perf_counter()
    # ---- mesh, regions --------------------------------------------------------------
    m = gf.Mesh('regular simplices', xs, ys, zs)
    XMIN, YMIN, BOTTOM, TOP = 1, 2, 3, 4
    m.set_region(XMIN, m.outer_faces_with_direction([-1., 0., 0.], 0.01))
    m.set_region(YMIN, m.outer_faces_with_direction([0., -1., 0.], 0.01))
    m.set_region(BOTTOM, m.outer_faces_with_direction([0., 0., -1.], 0.01))
    m.set_region(TOP, m.outer_faces_with_direction([0., 0., 1.], 0.01))

    mfu = gf.MeshFem(m, 3)
    mfu.set_fem(gf.Fem('FEM_PK(3,2)'))
    mfs = gf.MeshFem(m, 1)            # scalar P2 (Dirichlet multipliers, obstacle)
    mfs.set_fem(gf.Fem('FEM_PK(3,2)'))
    # volume: degree-2 rule is exact for P2 stiffness on straight tets; boundary terms
    # (P2 x P2 face products) need degree 4, so a separate richer rule is used there.
    mim = gf.MeshIm(m, gf.Integ('IM_TETRAHEDRON(2)'))
    mimb = gf.MeshIm(m, gf.Integ('IM_TETRAHEDRON(5)'))

    # ---- model ----------------------------------------------------------------------
    md = gf.Model('real')
    md.add_fem_variable('u', mfu)
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    md.add_initialized_data('lambda', [lam])
    md.add_initialized_data('mu', [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, 'u', 'lambda', 'mu')
    md.add_initialized_data('zero', [0.])
    md.add_initialized_data('mdval', [-d])   # u.n = -d on the bottom (n = -e_z)
    md.add_normal_Dirichlet_condition_with_multipliers(mimb, 'u', mfs, XMIN, 'zero')
    md.add_normal_Dirichlet_condition_with_multipliers(mimb, 'u', mfs, YMIN, 'zero')
    md.add_normal_Dirichlet_condition_with_multipliers(mimb, 'u', mfs, BOTTOM, 'mdval')

    md.add_initialized_data('r', [r_aug])
    obstacle_expr = 'sqrt(x*x+y*y+(z-%.17g)*(z-%.17g))-%.17g' % (R, R, R)
    if a.brick == 'nodal':
        nbc = mfu.basic_dof_on_region(TOP).size // 3
        md.add_variable('lambda_n', nbc)
        md.add_nodal_contact_with_rigid_obstacle_brick(mimb, 'u', 'lambda_n', 'r', TOP,
                                                       obstacle_expr, a.aug)
    else:
        P = mfs.basic_dof_nodes()
        obs = np.sqrt(P[0] ** 2 + P[1] ** 2 + (P[2] - R) ** 2) - R
        md.add_initialized_fem_data('obstacle', mfs, obs)
        md.add_filtered_fem_variable('lambda_n', mfs, TOP)
        md.add_integral_contact_with_rigid_obstacle_brick(mimb, 'u', 'lambda_n',
                                                          'obstacle', 'r', TOP, a.aug)
    t1 = time.perf_counter()

    opts = ['max_res', a.max_res, 'max_iter', a.max_iter, 'lsolver', a.lsolver]
    if a.noisy:
        opts.append('noisy')
    ret = md.solve(*opts)
    t2 = time.perf_counter()
    nit = int(ret[0]) if isinstance(ret, (tuple, list, np.ndarray)) else int(ret)
    converged = bool(ret[1]) if isinstance(ret, (tuple, list, np.ndarray)) and len(ret) > 1 else None

    # ---- post-processing ------------------------------------------------------------
    U = md.variable('u')
    # Internal nodal forces f = K u (exact equilibrium: on the top face they are the
    # contact forces, on the bottom the support reactions).
    K = gf.asm_linear_elasticity(mim, mfu, mfs, np.full(mfs.nbdof(), lam),
                                 np.full(mfs.nbdof(), mu))
    f = K.mult(U)
    pts = mfu.basic_dof_nodes()
    top = mfu.basic_dof_on_region(TOP)
    bot = mfu.basic_dof_on_region(BOTTOM)
    topz = top[2::3]   # dofs come in (x, y, z) triples per node
    botz = bot[2::3]
    assert np.all(np.abs(pts[2, topz]) < 1e-12)
    Pq_top = float(-np.sum(f[topz]))     # contact pushes the top face down
    Pq_bot = float(np.sum(f[botz]))      # support pushes the bottom up
    rad = np.hypot(pts[0, topz], pts[1, topz])
    fn = -f[topz]                        # nodal contact force (z), >= 0 where in contact

    Ln = md.variable('lambda_n')
    res = {}
    if a.brick == 'nodal':
        # the multiplier lambda_n[j] belongs to the j-th node of TOP (same order)
        Pq_mult = float(np.sum(Ln))
        lam_abs = np.abs(Ln)
        tol = 1e-8 * max(lam_abs.max(), 1e-300)
        inc = lam_abs > tol
        res["multiplier_sum_q"] = Pq_mult
        res["lambda_sign"] = "negative" if Ln.sum() < 0 else "positive"
    else:
        Pq_mult = None
    rad_c = rad
    if a.brick == 'integral':
        # weak (integral) contact: the P2 multiplier field oscillates (~1% of p0) past
        # the contact edge, so 'in contact' = pressure beyond 5% of its peak (heuristic).
        ldofs = mfs.basic_dof_on_region(TOP)
        lp = mfs.basic_dof_nodes()[:, ldofs]
        rad_c = np.hypot(lp[0], lp[1])
        sgn = -1.0 if Ln.sum() < 0 else 1.0
        inc = sgn * Ln > 0.05 * np.abs(Ln).max()
        res["multiplier_peak_pressure"] = float(np.abs(Ln).max())
    # closed gap: displacement along the obstacle normal reaches the gap
    X, Y, Zp = pts[0, topz], pts[1, topz], pts[2, topz]
    rho = np.sqrt(X * X + Y * Y + (Zp - R) ** 2)
    gap = rho - R
    un = np.vstack([-X / rho, -Y / rho, -(Zp - R) / rho])
    uvec = np.vstack([U[topz - 2], U[topz - 1], U[topz]])
    pen = np.sum(un * uvec, axis=0) - gap
    closed = pen > -1e-5 * d
    a_fe = float(rad_c[inc].max()) if inc.any() else 0.0
    a_closed = float(rad[closed].max()) if closed.any() else 0.0
    # smallest radius of a node not in contact beyond a_fe (bracket of the edge)
    outside = rad_c[(~inc) & (rad_c > a_fe)]
    a_next = float(outside.min()) if outside.size else None

    P = 4.0 * Pq_top
    Estar = E / (1 - nu * nu)
    a_h = math.copysign(abs(3.0 * P * R / (4.0 * Estar)) ** (1.0 / 3.0), P)
    # Hertz from indentation depth d (rigid sphere, semi-infinite body): P = 4/3 E* R^1/2 d^3/2
    P_hertz_d = 4.0 / 3.0 * Estar * math.sqrt(R) * d ** 1.5
    inner = rad < 0.5 * a_h
    F_inner_q = float(np.sum(fn[inner]))
    F_inner_hertz_frac = 1.0 - (1.0 - 0.25) ** 1.5   # Hertz: fraction of P in r < a/2

    res.update({
        "brick": a.brick, "aug_version": a.aug, "r_aug": r_aug, "lsolver": a.lsolver,
        "refine": a.refine, "grid": [len(xs), len(ys), len(zs)],
        "n_tets": int(m.nbcvs()), "n_nodes_p2": int(mfu.nbdof() // 3),
        "dofs_u": int(mfu.nbdof()), "dofs_total": int(md.nbdof()),
        "n_contact_candidates": int(topz.size),
        "newton_iters": nit, "converged": converged,
        "P_q": Pq_top, "P_q_bottom_reaction": Pq_bot, "P": P,
        "P_hertz_from_d": P_hertz_d,
        "a_fe": a_fe, "a_fe_gap_closed": a_closed, "a_next_free_node": a_next,
        "n_nodes_in_contact": int(inc.sum()),
        "a_hertz_of_P": a_h,
        "F_inside_half_aHertz_q": F_inner_q, "F_inside_half_aHertz": 4 * F_inner_q,
        "F_inside_fraction": F_inner_q / Pq_top if Pq_top else None,
        "F_inside_fraction_hertz": F_inner_hertz_frac,
        "max_penetration": float(pen.max()),
        "min_pen_of_contact_nodes": float(pen[inc].min()) if inc.any() and a.brick == 'nodal' else None,
        "max_pen_of_free_nodes": float(pen[~inc].max()) if (~inc).any() and a.brick == 'nodal' else None,
        "t_setup_s": t1 - t0, "t_solve_s": t2 - t1, "t_total_s": t2 - t0,
    })
    if a.dump:
        mfl = md.mesh_fem_of_variable('lambda_n') if a.brick == 'integral' else None
        np.savez(a.dump, rad=rad, fn=fn, pen=pen, Ln=Ln,
                 lnodes=(mfs.basic_dof_nodes()[:, mfs.basic_dof_on_region(TOP)]
                         if mfl is not None else np.zeros(0)))
    print(json.dumps(res))


if __name__ == "__main__":
    main()
