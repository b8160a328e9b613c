//! 3D interfaces between bodies (node pairs, node-to-face) and RCCM adhesion in 3D, against
//! exact answers.
//!
//! - **Two-block patch** (the contact patch test between bodies: T. A. Laursen,
//!   *Computational Contact and Impact Mechanics*, Springer 2002, §5.3): a block on a block,
//!   rollers on the sides `x = 0` and `y = 0`, the base held, the top pushed down by `δ`. The
//!   state is uniaxial, `σ_zz = −E δ / H` over the total height, and it lies in the discrete
//!   space of P1 and P2 elements on either side of any interface grid: the force on every
//!   contactor node is `σ ∫ N_i dA` to round-off, for matching grids (node pairs) and for a
//!   top grid that does not match the bottom one (node-to-face, flat and P2).
//! - **Sliding blocks** (Coulomb's law between bodies): the top block pressed and moved along
//!   x, far enough that the whole interface slides: `|r_t| = μ r_n` at every contact and the
//!   tangential reaction opposes the slip.
//! - **A glued block pulled off** (RCCM, α = 0, seed 3.30 and 4.31 with this crate's signs): a
//!   block glued to a rigid plane, or to a second block by node pairs, its top pulled up by `δ`.
//!   The opening `u` is uniform and solves `E (δ − u) / H = β² C u` with
//!   `β = min(β_prev, w / (C u²))` (the interface's energy release): a scalar equation solved
//!   here by bisection. Checked: the opening, β, and the total force, to the fixed point's
//!   tolerance.

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini};
use contact_solver::coupling::solid::{
    ContactZone3, PairNormals3, RigidPlane, SolidContactSimulation, TriSurface,
};
use contact_solver::{FlexibilityMode, SimulationSettings};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{Face, SolidKind, SolidMesh, SolidModel};
use fem_core::{Component, Material, Supports};

/// Two boxes, `[0,1]² × [0,1]` (region 0, sets `a.*`) under `[0,1]² × [1,2]` (region 1, sets
/// `b.*`), `na` and `nb` cells per side in x and y: separate nodes on the interface.
pub(crate) fn two_blocks(kind: SolidKind, na: usize, nb: usize) -> SolidMesh {
    let a = box_mesh(
        &lines(0.0, 1.0, na),
        &lines(0.0, 1.0, na),
        &lines(0.0, 1.0, 1),
        kind,
    )
    .unwrap();
    let b = box_mesh(
        &lines(0.0, 1.0, nb),
        &lines(0.0, 1.0, nb),
        &lines(1.0, 2.0, 1),
        kind,
    )
    .unwrap();
    let (node_offset, element_offset) = (a.node_count(), a.element_count());
    let mut nodes = a.nodes().to_vec();
    nodes.extend_from_slice(b.nodes());
    let mut connectivity = a.connectivity().to_vec();
    connectivity.extend(b.connectivity().iter().map(|n| n + node_offset));
    let mut regions = vec![0; a.element_count()];
    regions.extend(vec![1; b.element_count()]);
    let mut mesh = SolidMesh::new(nodes, kind, connectivity, regions).unwrap();
    for (prefix, m, no, eo) in [("a", &a, 0, 0), ("b", &b, node_offset, element_offset)] {
        for (name, set) in m.node_sets() {
            let set = set.iter().map(|n| n + no).collect();
            mesh.add_node_set(&format!("{prefix}.{name}"), set).unwrap();
        }
        for (name, faces) in m.facet_sets() {
            let faces = faces
                .iter()
                .map(|f| Face {
                    element: f.element + eo,
                    side: f.side,
                })
                .collect();
            mesh.add_face_set(&format!("{prefix}.{name}"), faces)
                .unwrap();
        }
    }
    mesh
}

/// Rollers on `x = 0` and `y = 0` of both blocks, the base held along z, the top moved by
/// `top` (the components given).
pub(crate) fn supports(mesh: &SolidMesh, top: &[(Component, f64)]) -> Supports {
    let mut s = Supports::new();
    for p in ["a", "b"] {
        s.fix(mesh.node_set(&format!("{p}.x0")).unwrap(), Component::X)
            .fix(mesh.node_set(&format!("{p}.y0")).unwrap(), Component::Y);
    }
    s.fix(mesh.node_set("a.z0").unwrap(), Component::Z);
    for &(c, v) in top {
        s.prescribe(mesh.node_set("b.z1").unwrap(), c, v).unwrap();
    }
    s
}

/// The bottom block's node at the position of each of `nodes`.
pub(crate) fn matching(mesh: &SolidMesh, nodes: &[usize], among: &[usize]) -> Vec<usize> {
    nodes
        .iter()
        .map(|&n| {
            let x = mesh.nodes()[n];
            *among
                .iter()
                .find(|&&m| {
                    let y = mesh.nodes()[m];
                    (0..3).all(|a| (x[a] - y[a]).abs() < 1e-12)
                })
                .expect("matching grids")
        })
        .collect()
}

#[test]
fn two_block_patch_is_exact_for_pairs_and_faces() {
    let (e, nu, delta) = (1000.0, 0.3, 1e-3);
    let m = Material::new(e, nu, 0.0).unwrap();
    let sigma = e * delta / 2.0;
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        for label in ["pairs", "pairs, surface normals", "faces"] {
            // matching grids: node-to-face must give the pairs' answer
            let mesh = two_blocks(kind, 2, 2);
            let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
            let law = Signorini;
            let targets = matching(&mesh, &nodes, mesh.node_set("a.z1").unwrap());
            let zone = match label {
                "pairs" => {
                    let n = PairNormals3::Fixed([0.0, 0.0, 1.0]);
                    ContactZone3::node_pairs("i", nodes, targets, n, law, 0.1)
                }
                "pairs, surface normals" => {
                    let n =
                        PairNormals3::Surface(TriSurface::from_face_set(&mesh, "a.z1").unwrap());
                    ContactZone3::node_pairs("i", nodes, targets, n, law, 0.1)
                }
                _ => {
                    let surface = TriSurface::from_face_set(&mesh, "a.z1").unwrap();
                    ContactZone3::node_to_face("i", nodes, surface, law, 0.1)
                }
            }
            .with_areas(areas);
            let s = supports(&mesh, &[(Component::Z, -delta)]);
            let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
            let mut sim = SolidContactSimulation::new(
                model,
                vec![zone],
                SimulationSettings::for_dimension::<3>(),
            )
            .unwrap();
            let res = sim.step(1.0, 1.0).unwrap();
            check_uniform(&res.contacts, sigma, &format!("{kind:?} {label}"));
            // the interface's displacement: uniform strain δ / 2 over the height
            let node = sim.structure().mesh().node_set("b.z0").unwrap()[0];
            let uz = sim.nodal_displacement(node)[2];
            assert!((uz + delta / 2.0).abs() < 1e-9, "{kind:?} {label}: {uz}");
        }
    }
}

fn check_uniform(
    contacts: &[contact_solver::coupling::solid::SolidContactRecord],
    sigma: f64,
    label: &str,
) {
    let total: f64 = contacts.iter().map(|c| c.r.n).sum();
    // the solver's tolerance (1e-10 relative) on a unit area
    assert!(
        (total - sigma).abs() < 1e-8 * sigma,
        "{label}: {total} vs {sigma}"
    );
    for c in contacts {
        let want = sigma * c.area;
        assert!(
            (c.r.n - want).abs() < 1e-7 * sigma,
            "{label}: node {} r_n {} vs {want}",
            c.node,
            c.r.n
        );
        assert!(c.gap.abs() < 1e-12, "{label}: gap {}", c.gap);
        assert!((c.normal[2] - 1.0).abs() < 1e-12);
    }
}

/// A top grid that does not match the bottom one (3 × 3 on 2 × 2 cells). On a target that
/// moves rigidly (every bottom node prescribed: up by `d`, and the lateral expansion of the
/// uniaxial state) the state is uniform and exact: this checks the projection, the weights
/// `N_k` and the frame. On a deformable bottom block, one-pass node-to-face does not pass the
/// patch test (T. A. Laursen, op. cit., §5.3: the contactor's forces, spread on the target by
/// the weights, are not the target's consistent loads): the total force is within 1 % of the
/// uniform answer, and the interface carries no tension.
#[test]
fn non_matching_faces_are_exact_on_a_moving_target() {
    let (e, nu, delta, d) = (1000.0, 0.3, 1e-3, 2e-4);
    let m = Material::new(e, nu, 0.0).unwrap();
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        let mesh = two_blocks(kind, 2, 3);
        let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
        let surface = TriSurface::from_face_set(&mesh, "a.z1").unwrap();
        let zone =
            ContactZone3::node_to_face("i", nodes, surface, Signorini, 0.1).with_areas(areas);
        // the top block: rollers, its top down by δ; the bottom block: prescribed
        let mut s = Supports::new();
        s.fix(mesh.node_set("b.x0").unwrap(), Component::X)
            .fix(mesh.node_set("b.y0").unwrap(), Component::Y)
            .prescribe(mesh.node_set("b.z1").unwrap(), Component::Z, -delta)
            .unwrap();
        let strain = (delta + d) * nu; // lateral strain of the uniaxial state, height 1
        let mut bottom: Vec<usize> = (0..mesh.element_count())
            .filter(|&el| mesh.regions()[el] == 0)
            .flat_map(|el| mesh.element(el).to_vec())
            .collect();
        bottom.sort_unstable();
        bottom.dedup();
        for &n in &bottom {
            let x = mesh.nodes()[n];
            s.prescribe(&[n], Component::X, strain * x[0])
                .unwrap()
                .prescribe(&[n], Component::Y, strain * x[1])
                .unwrap()
                .prescribe(&[n], Component::Z, d)
                .unwrap();
        }
        let model = SolidModel::new(mesh.clone(), &[(0, m), (1, m)], s).unwrap();
        let mut sim = SolidContactSimulation::new(
            model,
            vec![zone.clone()],
            SimulationSettings::for_dimension::<3>(),
        )
        .unwrap();
        let res = sim.step(1.0, 1.0).unwrap();
        check_uniform(
            &res.contacts,
            e * (delta + d),
            &format!("{kind:?} moving target"),
        );
        // the same interface on a deformable bottom block
        let s = supports(&mesh, &[(Component::Z, -delta)]);
        let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
        let mut sim = SolidContactSimulation::new(
            model,
            vec![zone],
            SimulationSettings::for_dimension::<3>(),
        )
        .unwrap();
        let res = sim.step(1.0, 1.0).unwrap();
        let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
        let sigma = e * delta / 2.0;
        eprintln!("{kind:?} deformable target: total {total} vs uniform {sigma}");
        assert!((total / sigma - 1.0).abs() < 0.01, "{kind:?}: {total}");
        assert!(res.contacts.iter().all(|c| c.r.n >= -1e-12));
    }
}

#[test]
fn sliding_blocks_obey_coulomb_between_bodies() {
    let (e, mu) = (1000.0, 0.3);
    let m = Material::new(e, 0.0, 0.0).unwrap();
    let mesh = two_blocks(SolidKind::Tet10, 2, 3);
    let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
    let surface = TriSurface::from_face_set(&mesh, "a.z1").unwrap();
    let law = Coulomb::new(mu).unwrap();
    let zone = ContactZone3::node_to_face("i", nodes, surface, law, 0.1).with_areas(areas);
    // the top pressed, then moved along x by 10 × the press: the whole interface slides
    let mut s = Supports::new();
    for c in [Component::X, Component::Y, Component::Z] {
        s.fix(mesh.node_set("a.z0").unwrap(), c);
    }
    s.prescribe(mesh.node_set("b.z1").unwrap(), Component::Z, -1e-3)
        .unwrap()
        .prescribe(mesh.node_set("b.z1").unwrap(), Component::X, 1e-2)
        .unwrap()
        .fix(mesh.node_set("b.z1").unwrap(), Component::Y);
    let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
    let mut sim =
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap();
    let res = sim.step(1.0, 1.0).unwrap();
    let (mut fn_, mut fx) = (0.0, 0.0);
    for c in res.contacts.iter().filter(|c| c.r.n > 1e-9) {
        let rt = c.r.t[0].hypot(c.r.t[1]);
        assert!(
            (rt - mu * c.r.n).abs() < 1e-6 * c.r.n.max(1e-3),
            "node {}: |r_t| {rt} vs μ r_n {}",
            c.node,
            mu * c.r.n
        );
        // the force on the top block opposes its motion (+x)
        let f = c.force();
        assert!(f[0] < 0.0, "node {}: {f:?}", c.node);
        fn_ += f[2];
        fx += f[0];
    }
    assert!(fn_ > 0.0 && ((-fx) / fn_ - mu).abs() < 1e-6, "{fx} {fn_}");
}

fn rccm(c: f64, w: f64) -> Rccm {
    Rccm::new(RccmParams {
        c_n: c,
        c_t: c,
        w,
        alpha: 0.0,
        mu: 0.3,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap()
}

/// The opening and β of a glued bar of height `h` pulled by `delta` (module docs), from the
/// previous β.
fn pulled(e: f64, h: f64, c: f64, w: f64, delta: f64, beta_prev: f64) -> (f64, f64) {
    let beta = |u: f64| {
        let energy = c * u * u;
        if energy * beta_prev <= w {
            beta_prev
        } else {
            (w / energy).min(beta_prev)
        }
    };
    let f = |u: f64| e * (delta - u) / h - beta(u).powi(2) * c * u;
    let (mut lo, mut hi) = (0.0, delta);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let u = 0.5 * (lo + hi);
    (u, beta(u))
}

#[test]
fn glued_block_pulled_off_follows_rccm() {
    // the first steps are elastic, then β falls; E / H > 3 C keeps the softening stable (one
    // equilibrium per δ: `E (δ − u) / H − w² / (C u³)` decreases past the onset u₀ = √(w/C))
    let (e, c, w) = (1000.0, 100.0, 1e-4);
    let m = Material::new(e, 0.0, 0.0).unwrap();
    // the dense F* (Auto's choice for adhesion) and the primal active set with the springs on
    // the stiffness, both against the analytic answer
    for (label, kind, active_set) in [
        ("rigid", SolidKind::Tet10, false),
        ("pairs", SolidKind::Tet10, false),
        ("rigid", SolidKind::Tet4, false),
        ("rigid", SolidKind::Tet10, true),
        ("pairs", SolidKind::Tet10, true),
    ] {
        let mesh = two_blocks(kind, 2, 2);
        let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
        let law = rccm(c, w);
        let (zone, h, s) = if label == "rigid" {
            // the top block alone, glued to a rigid plane at z = 1; the bottom block is held
            let plane = RigidPlane::new([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]).unwrap();
            let zone = ContactZone3::rigid("glue", nodes, plane, law, 0.1).with_areas(areas);
            let mut s = Supports::new();
            for cmp in [Component::X, Component::Y, Component::Z] {
                s.fix(mesh.node_set("a.z0").unwrap(), cmp)
                    .fix(mesh.node_set("a.z1").unwrap(), cmp);
            }
            s.fix(mesh.node_set("b.x0").unwrap(), Component::X)
                .fix(mesh.node_set("b.y0").unwrap(), Component::Y);
            s.prescribe(mesh.node_set("b.z1").unwrap(), Component::Z, 0.0)
                .unwrap();
            (zone, 1.0, s)
        } else {
            let targets = matching(&mesh, &nodes, mesh.node_set("a.z1").unwrap());
            let n = PairNormals3::Fixed([0.0, 0.0, 1.0]);
            let zone =
                ContactZone3::node_pairs("glue", nodes, targets, n, law, 0.1).with_areas(areas);
            (zone, 2.0, supports(&mesh, &[(Component::Z, 0.0)]))
        };
        let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
        let mut settings = SimulationSettings::for_dimension::<3>();
        if active_set {
            settings.flexibility = FlexibilityMode::ActiveSet;
        }
        let mut sim = SolidContactSimulation::new(model, vec![zone], settings).unwrap();
        let top = sim.structure().mesh().node_set("b.z1").unwrap().to_vec();
        let mut beta_prev = 1.0;
        let mut damaged = false;
        for k in 1..=8 {
            let delta = 2e-4 * f64::from(k);
            sim.structure_mut()
                .set_prescribed(&top, Component::Z, delta)
                .unwrap();
            let res = sim.step(f64::from(k), 1.0).unwrap();
            assert_eq!(res.report.active_set, active_set);
            let (u, beta) = pulled(e, h, c, w, delta, beta_prev);
            beta_prev = beta;
            damaged |= beta < 0.999;
            let total: f64 = res.contacts.iter().map(|r| r.r.n).sum();
            let want = -beta * beta * c * u; // tension on a unit area
            assert!(
                (total - want).abs() < 1e-6 * want.abs(),
                "{label} {kind:?} (active set {active_set}) step {k}: force {total} vs {want}"
            );
            for r in &res.contacts {
                assert!(
                    (r.gap - u).abs() < 1e-6 * u,
                    "{label} step {k}: u {} vs {u}",
                    r.gap
                );
                if r.area > 0.0 {
                    assert!(
                        (r.beta - beta).abs() < 1e-6,
                        "{label} step {k}: β {}",
                        r.beta
                    );
                }
            }
        }
        assert!(damaged, "{label}: the load must reach the damage range");
        assert!(rccm(c, w).has_adhesion());
    }
}

#[test]
fn interface_zones_refuse_bad_input() {
    use contact_solver::SolverError;
    let mesh = two_blocks(SolidKind::Tet4, 1, 1);
    let m = Material::new(100.0, 0.3, 0.0).unwrap();
    let model = || {
        SolidModel::new(
            mesh.clone(),
            &[(0, m), (1, m)],
            supports(&mesh, &[(Component::Z, 0.0)]),
        )
        .unwrap()
    };
    let nodes = mesh.node_set("b.z0").unwrap().to_vec();
    let targets = matching(&mesh, &nodes, mesh.node_set("a.z1").unwrap());
    let run = |zone: ContactZone3<Signorini>| {
        SolidContactSimulation::new(
            model(),
            vec![zone],
            SimulationSettings::for_dimension::<3>(),
        )
        .err()
    };
    let geometry = |e: Option<SolverError>, what: &str| {
        assert!(
            matches!(&e, Some(SolverError::InvalidGeometry(m)) if m.contains(what)),
            "{what}: {e:?}"
        );
    };
    let up = PairNormals3::Fixed([0.0, 0.0, 1.0]);
    // pair lists of different lengths, an unknown target, a zero normal, normals per pair
    // of the wrong length, a node paired with itself
    geometry(
        run(ContactZone3::node_pairs(
            "p",
            nodes.clone(),
            targets[1..].to_vec(),
            up.clone(),
            Signorini,
            0.1,
        )),
        "target nodes",
    );
    let mut far = targets.clone();
    far[0] = 10_000;
    geometry(
        run(ContactZone3::node_pairs(
            "p",
            nodes.clone(),
            far,
            up.clone(),
            Signorini,
            0.1,
        )),
        "10000",
    );
    geometry(
        run(ContactZone3::node_pairs(
            "p",
            nodes.clone(),
            targets.clone(),
            PairNormals3::Fixed([0.0; 3]),
            Signorini,
            0.1,
        )),
        "unit normal",
    );
    geometry(
        run(ContactZone3::node_pairs(
            "p",
            nodes.clone(),
            targets.clone(),
            PairNormals3::PerPair(vec![[0.0, 0.0, 1.0]]),
            Signorini,
            0.1,
        )),
        "normals",
    );
    geometry(
        run(ContactZone3::node_pairs(
            "p",
            nodes.clone(),
            nodes.clone(),
            up,
            Signorini,
            0.1,
        )),
        "cannot move",
    );
    // surfaces: a wrong face size, a repeated node, an unknown node, an unknown face set
    assert!(TriSurface::new(4, vec![0, 1, 2, 3]).is_err());
    assert!(TriSurface::new(3, vec![0, 1]).is_err());
    assert!(TriSurface::new(3, vec![0, 1, 1]).is_err());
    assert!(TriSurface::from_face_set(&mesh, "nope").is_err());
    let bad = TriSurface::new(3, vec![0, 1, 99_999]).unwrap();
    geometry(
        run(ContactZone3::node_to_face(
            "f",
            nodes.clone(),
            bad,
            Signorini,
            0.1,
        )),
        "99999",
    );
}

/// The matrix-free path (no `F*`) gives the dense path's reactions: the sliding blocks of
/// `sliding_blocks_obey_coulomb_between_bodies` (node-to-face, Coulomb; 37 contacts, both
/// tangents used) and the two-block patch with node pairs (Signorini: the tangents decoupled).
/// The matrix-free iteration on node pairs and node-to-face, and the primal active set (the
/// contactor's dofs carrying the target's motion) on node-to-face with friction: every solver
/// stops at the relative tolerance 1e-10, reactions agree to 1e-6 of the largest.
#[test]
fn matrix_free_and_active_set_3d_match_dense() {
    use contact_solver::coupling::simulation::FlexibilityMode;
    let m = Material::new(1000.0, 0.3, 0.0).unwrap();
    let run = |mode: FlexibilityMode, friction: bool| {
        let mesh = two_blocks(SolidKind::Tet10, 2, if friction { 3 } else { 2 });
        let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
        let s = if friction {
            let mut s = Supports::new();
            for c in [Component::X, Component::Y, Component::Z] {
                s.fix(mesh.node_set("a.z0").unwrap(), c);
            }
            s.prescribe(mesh.node_set("b.z1").unwrap(), Component::Z, -1e-3)
                .unwrap()
                .prescribe(mesh.node_set("b.z1").unwrap(), Component::X, 2e-4)
                .unwrap()
                .fix(mesh.node_set("b.z1").unwrap(), Component::Y);
            s
        } else {
            supports(&mesh, &[(Component::Z, -1e-3)])
        };
        let zone: ContactZone3<contact_laws::StandardLaw> = if friction {
            let surface = TriSurface::from_face_set(&mesh, "a.z1").unwrap();
            let law = contact_laws::StandardLaw::Coulomb(Coulomb::new(0.3).unwrap());
            ContactZone3::node_to_face("i", nodes, surface, law, 0.1).with_areas(areas)
        } else {
            let targets = matching(&mesh, &nodes, mesh.node_set("a.z1").unwrap());
            let n = PairNormals3::Fixed([0.0, 0.0, 1.0]);
            let law = contact_laws::StandardLaw::Signorini(Signorini);
            ContactZone3::node_pairs("i", nodes, targets, n, law, 0.1).with_areas(areas)
        };
        let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
        let settings = SimulationSettings::for_dimension::<3>().with_flexibility(mode);
        let mut sim = SolidContactSimulation::new(model, vec![zone], settings).unwrap();
        let res = sim.step(1.0, 1.0).unwrap();
        assert_eq!(res.report.matrix_free, mode == FlexibilityMode::MatrixFree);
        assert_eq!(res.report.active_set, mode == FlexibilityMode::ActiveSet);
        res.contacts
            .iter()
            .map(|c| c.reaction())
            .collect::<Vec<_>>()
    };
    for friction in [false, true] {
        let dense = run(FlexibilityMode::Dense, friction);
        let largest = dense.iter().flatten().fold(0.0_f64, |a, b| a.max(b.abs()));
        // the frictionless pairs lie on roller planes: out of the active set's scope there
        let modes: &[FlexibilityMode] = if friction {
            &[FlexibilityMode::MatrixFree, FlexibilityMode::ActiveSet]
        } else {
            &[FlexibilityMode::MatrixFree]
        };
        for &mode in modes {
            let other = run(mode, friction);
            let worst = dense
                .iter()
                .flatten()
                .zip(other.iter().flatten())
                .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
            eprintln!(
                "friction {friction}: {mode:?} against dense {:.1e}",
                worst / largest
            );
            assert!(
                worst < 1e-6 * largest,
                "friction {friction}, {mode:?}: {worst} of {largest}"
            );
        }
    }
}

/// Laws by phase in 3D (`set_law`): a block pressed on a rigid plane without friction, then
/// with Coulomb friction and a shear of its top: the first phase has no tangential reaction,
/// the second `|Σ r_t| = μ Σ r_n` once it slides; an unknown zone and an adhesive law on a
/// zone without areas are refused; `reset_displacements` zeroes the reported displacement.
#[test]
fn laws_by_phase_in_3d() {
    use contact_laws::StandardLaw;
    use contact_solver::SolverError;
    let m = Material::new(1000.0, 0.0, 0.0).unwrap();
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 0.5, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    s.prescribe(&top, Component::Z, -1e-3)
        .unwrap()
        .fix(&top, Component::X)
        .fix(&top, Component::Y);
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let bare = ContactZone3::rigid(
        "floor",
        nodes.clone(),
        plane,
        StandardLaw::Signorini(Signorini),
        0.1,
    );
    let zone = bare.clone().with_areas(areas);
    let model = SolidModel::new(mesh.clone(), &[(0, m)], s.clone()).unwrap();
    let mut sim =
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap();
    let first = sim.step(1.0, 1.0).unwrap();
    assert!(
        first
            .contacts
            .iter()
            .all(|c| c.r.t[0] == 0.0 && c.r.t[1] == 0.0)
    );
    let mu = 0.3;
    sim.set_law("floor", StandardLaw::Coulomb(Coulomb::new(mu).unwrap()))
        .unwrap();
    sim.structure_mut()
        .set_prescribed(&top, Component::X, 1e-2)
        .unwrap();
    let second = sim.step(2.0, 1.0).unwrap();
    let (fn_, ft): (f64, f64) = second
        .contacts
        .iter()
        .fold((0.0, 0.0), |(a, b), c| (a + c.r.n, b + c.force()[0]));
    assert!((ft.abs() / fn_ - mu).abs() < 1e-6, "{ft} {fn_}");
    assert!(matches!(
        sim.set_law("nowhere", StandardLaw::Signorini(Signorini)),
        Err(SolverError::UnknownZone { .. })
    ));
    sim.reset_displacements();
    assert_eq!(sim.nodal_displacement(top[0]), [0.0; 3]);
    // a zone without areas cannot take an adhesive law
    let model = SolidModel::new(mesh, &[(0, m)], s).unwrap();
    let mut plain =
        SolidContactSimulation::new(model, vec![bare], SimulationSettings::for_dimension::<3>())
            .unwrap();
    assert!(matches!(
        plain.set_law("floor", StandardLaw::Rccm(rccm(100.0, 1e-4))),
        Err(SolverError::InvalidGeometry(m)) if m.contains("areas")
    ));
}
