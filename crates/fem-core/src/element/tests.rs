//! Unit tests of the triangles and tetrahedra (moved here with the kernels from
//! `element/mod.rs` and `solid/element.rs`); the new elements are tested in
//! `tests/integration/elements.rs`.

mod plane {
    use crate::element::{Element, Tri3, Tri6, tri6};
    use crate::error::FemError;
    use crate::idealization::Idealization;
    use crate::material::Material;
    use nalgebra::DMatrix;

    fn p2_coords(c: [[f64; 2]; 3]) -> Vec<[f64; 2]> {
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        vec![
            c[0],
            c[1],
            c[2],
            mid(c[0], c[1]),
            mid(c[1], c[2]),
            mid(c[2], c[0]),
        ]
    }

    #[test]
    fn shape_functions_partition_unity_and_gradients_sum_to_zero_works() {
        for xi in [[0.2, 0.3], [0.0, 0.0], [0.7, 0.1]] {
            let mut n = [0.0; 6];
            let mut dn = [[0.0; 2]; 6];
            tri6::shape(xi, &mut n);
            tri6::shape_derivatives(xi, &mut dn);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for a in 0..2 {
                assert!(dn.iter().map(|g| g[a]).sum::<f64>().abs() < 1e-14);
            }
            // Finite-difference check of the derivatives.
            let h = 1e-7;
            for a in 0..2 {
                let mut xp = xi;
                let mut xm = xi;
                xp[a] += h;
                xm[a] -= h;
                let (mut np, mut nm) = ([0.0; 6], [0.0; 6]);
                tri6::shape(xp, &mut np);
                tri6::shape(xm, &mut nm);
                for i in 0..6 {
                    assert!(((np[i] - nm[i]) / (2.0 * h) - dn[i][a]).abs() < 1e-8);
                }
            }
        }
    }

    #[test]
    fn stiffness_is_symmetric_with_rigid_modes_in_kernel_works() {
        let m = Material::new(200.0, 0.3, 0.0).unwrap();
        let c3 = vec![[0.1, 0.0], [1.3, 0.2], [0.4, 0.9]];
        let c6 = p2_coords([[0.1, 0.0], [1.3, 0.2], [0.4, 0.9]]);
        let mut k = DMatrix::zeros(0, 0);
        for ideal in [
            Idealization::PlaneStrain,
            Idealization::PlaneStress { thickness: 2.0 },
        ] {
            for (el, coords) in [(&Tri3 as &dyn Element<2>, &c3), (&Tri6, &c6)] {
                el.stiffness_into(0, coords, &m, &ideal, &mut k).unwrap();
                assert!((&k - k.transpose()).norm() < 1e-12 * k.norm());
                // Translations and the infinitesimal rotation produce no force.
                let n = coords.len();
                let modes = [
                    (0..n).flat_map(|_| [1.0, 0.0]).collect::<Vec<_>>(),
                    (0..n).flat_map(|_| [0.0, 1.0]).collect(),
                    coords.iter().flat_map(|p| [-p[1], p[0]]).collect(),
                ];
                for mode in modes {
                    let f = &k * nalgebra::DVector::from_vec(mode);
                    assert!(f.norm() < 1e-12 * k.norm(), "rigid mode not in kernel");
                }
                assert!(k.clone().symmetric_eigenvalues().min() > -1e-10 * k.norm());
            }
        }
        // Axisymmetric: only the axial translation is a rigid mode.
        Tri6.stiffness_into(0, &c6, &m, &Idealization::Axisymmetric, &mut k)
            .unwrap();
        let f = &k * nalgebra::DVector::from_vec((0..6).flat_map(|_| [0.0, 1.0]).collect());
        assert!(f.norm() < 1e-12 * k.norm());
    }

    #[test]
    fn stiffness_rejects_inverted_element() {
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let mut k = DMatrix::zeros(0, 0);
        let err = Tri3
            .stiffness_into(
                7,
                &[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
                &m,
                &Idealization::PlaneStrain,
                &mut k,
            )
            .unwrap_err();
        assert!(matches!(err, FemError::InvertedElement { element: 7, .. }));
    }
}

mod solid {
    use crate::element::kernel::{hooke, lame};
    use crate::element::{Element, Tet4, Tet10};
    use crate::error::FemError;
    use crate::material::Material;
    use nalgebra::DMatrix;

    fn tet(nodes: usize) -> &'static dyn Element<3> {
        if nodes == 4 { &Tet4 } else { &Tet10 }
    }

    fn unit_tet() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]
    }

    fn tet10(c: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut out = c.to_vec();
        for [i, j] in crate::element::tet10::TET_EDGES {
            out.push(core::array::from_fn(|a| 0.5 * (c[i][a] + c[j][a])));
        }
        out
    }

    #[test]
    fn shape_functions_partition_unity_and_match_finite_differences_works() {
        let xi = [0.21, 0.17, 0.33];
        for nodes in [4, 10] {
            let (mut n, mut dn) = ([0.0; 10], [[0.0; 3]; 10]);
            tet(nodes).shape(xi, &mut n, &mut dn);
            assert!((n[..nodes].iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for c in 0..3 {
                let h = 1e-6;
                let (mut np, mut nm, mut d) = ([0.0; 10], [0.0; 10], [[0.0; 3]; 10]);
                let mut xp = xi;
                xp[c] += h;
                tet(nodes).shape(xp, &mut np, &mut d);
                let mut xm = xi;
                xm[c] -= h;
                tet(nodes).shape(xm, &mut nm, &mut d);
                for i in 0..nodes {
                    let fd = (np[i] - nm[i]) / (2.0 * h);
                    // central differences of a quadratic are exact up to round-off / h
                    assert!((fd - dn[i][c]).abs() < 1e-9, "node {i} dir {c}");
                }
            }
        }
    }

    #[test]
    fn stiffness_is_symmetric_with_six_rigid_modes_works() {
        let m = Material::new(210.0, 0.3, 0.0).unwrap();
        let c4 = vec![
            [0.1, 0.0, 0.2],
            [1.3, 0.1, 0.0],
            [0.2, 1.1, 0.1],
            [0.3, 0.2, 0.9],
        ];
        for coords in [c4.clone(), tet10(&c4)] {
            let n = coords.len();
            let mut k = DMatrix::zeros(0, 0);
            let el: &dyn Element<3> = if n == 4 { &Tet4 } else { &Tet10 };
            el.stiffness_into(0, &coords, &m, &(), &mut k).unwrap();
            assert!((&k - k.transpose()).amax() < 1e-12 * k.amax());
            let eig = k.clone().symmetric_eigen().eigenvalues;
            let zero = eig.iter().filter(|v| v.abs() < 1e-9 * k.amax()).count();
            assert_eq!(zero, 6, "three translations and three rotations");
            assert!(eig.iter().all(|v| *v > -1e-9 * k.amax()));
            // a rotation about z is a zero-energy mode
            let u: Vec<f64> = coords.iter().flat_map(|p| [-p[1], p[0], 0.0]).collect();
            let f = &k * nalgebra::DVector::from_vec(u);
            assert!(f.amax() < 1e-12 * k.amax());
        }
    }

    #[test]
    fn uniform_strain_gives_hooke_stress_works() {
        let m = Material::new(100.0, 0.25, 0.0).unwrap();
        let (lambda, mu) = lame(&m);
        let grad = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
        let c4 = unit_tet();
        for coords in [c4.clone(), tet10(&c4)] {
            let u: Vec<f64> = coords
                .iter()
                .flat_map(|p| {
                    let g = &grad;
                    core::array::from_fn::<f64, 3, _>(|i| {
                        g[i][0] * p[0] + g[i][1] * p[1] + g[i][2] * p[2]
                    })
                })
                .collect();
            let mut out = Vec::new();
            let el: &dyn Element<3> = if coords.len() == 4 { &Tet4 } else { &Tet10 };
            el.stresses_into(0, &coords, &m, &(), &u, &mut out).unwrap();
            let e = [
                grad[0][0],
                grad[1][1],
                grad[2][2],
                0.5 * (grad[0][1] + grad[1][0]),
                0.5 * (grad[1][2] + grad[2][1]),
                0.5 * (grad[2][0] + grad[0][2]),
            ];
            let want = hooke(lambda, mu, e);
            for (_, s) in out {
                for k in 0..6 {
                    assert!((s[k] - want[k]).abs() < 1e-12 * 100.0, "{k}");
                }
            }
        }
    }

    #[test]
    fn self_weight_sums_to_the_weight_works() {
        let c4 = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 0.0, 1.5],
        ];
        let volume = 2.0 * 3.0 * 1.5 / 6.0;
        for coords in [c4.clone(), tet10(&c4)] {
            let mut f = vec![0.0; 3 * coords.len()];
            let el: &dyn Element<3> = if coords.len() == 4 { &Tet4 } else { &Tet10 };
            el.body_force_into(0, &coords, &(), &|_| [0.0, 0.0, -2.0], &mut f)
                .unwrap();
            let fz: f64 = f.iter().skip(2).step_by(3).sum();
            assert!((fz + 2.0 * volume).abs() < 1e-13);
        }
    }

    #[test]
    fn inverted_element_captures_errors() {
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let mut c = unit_tet();
        c.swap(1, 2);
        let mut k = DMatrix::zeros(0, 0);
        assert!(matches!(
            Tet4.stiffness_into(7, &c, &m, &(), &mut k),
            Err(FemError::InvertedElement { element: 7, .. })
        ));
    }
}
