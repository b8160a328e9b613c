//! Temporary diagnostics of the non-associated footing (issue 40).

use super::issue_40_strip_footing::*;
use fem_core::plastic::newton::NewtonSettings;
use fem_core::plastic::{ConstitutivePoint, PlasticModel, PointState, Voigt, VoigtMatrix};
use fem_core::{Component, FemError, Nonlinear, Structure};
use std::sync::{Arc, Mutex};

#[derive(Debug)]
struct Recorder {
    inner: Arc<dyn ConstitutivePoint>,
    log: Mutex<Vec<u8>>,
}

impl ConstitutivePoint for Recorder {
    fn elastic_tangent(&self) -> VoigtMatrix {
        self.inner.elastic_tangent()
    }
    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        self.inner.update(committed, strain, trial, tangent)?;
        let s = &trial.stress;
        let m = (s[0] + s[1] + s[2]) / 3.0;
        let dev = (s[0] - m).abs() + (s[1] - m).abs() + (s[2] - m).abs() + s[3].abs();
        let r = match (trial.yielding, dev > 0.0) {
            (false, _) => 0,
            (true, true) => 1,
            (true, false) => 2,
        };
        self.log.lock().unwrap().push(r);
        Ok(())
    }
    fn yield_function(&self, stress: &Voigt) -> f64 {
        self.inner.yield_function(stress)
    }
    fn symmetric_tangent(&self) -> bool {
        self.inner.symmetric_tangent()
    }
}

fn matvec(body: &PlasticModel<2>, x: &[f64]) -> Vec<f64> {
    let k = body.exact_tangent().unwrap();
    let mut y = vec![0.0; x.len()];
    let cp = k.symbolic().col_ptr();
    let ri = k.symbolic().row_idx();
    let v = k.val();
    for j in 0..x.len() {
        for p in cp[j]..cp[j + 1] {
            y[ri[p]] += v[p] * x[j];
        }
    }
    y
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[test]
#[ignore]
fn issue_40_diagnose_non_associated() {
    for theta in [10.0, 0.0] {
        let rec = Arc::new(Recorder {
            inner: soil(20.0, theta),
            log: Mutex::new(Vec::new()),
        });
        let (mut body, footing) = footing_body(&FootingMesh::CI, rec.clone());
        let newton = NewtonSettings {
            max_iterations: 40,
            tolerance: 1e-8,
            ..NewtonSettings::default()
        };
        let result = push(&mut body, &footing, 0.05, 20, &newton, 0);
        let reached = match &result {
            Ok(c) => c.last().unwrap().settlement,
            Err(FemError::NotConverged {
                converged_load_factor,
                ..
            }) => *converged_load_factor,
            Err(e) => panic!("{e}"),
        };
        eprintln!("θ = {theta}: first failure after δ/b = {reached}");
        // redo the failing step by hand from the committed state (no predictor)
        let n = body.dof_count();
        let mut u = vec![0.0; n];
        // recover u: solve elastic predictor? use pushes again: rerun the path to `reached`
        let (mut body, footing) = footing_body(&FootingMesh::CI, rec.clone());
        let steps = (reached / (0.05 / 20.0)).round() as usize;
        if steps > 0 {
            let curve = push(&mut body, &footing, reached, steps, &newton, 0).unwrap();
            eprintln!("  replayed to q = {}", curve.last().unwrap().pressure);
        }
        // u of the committed state: Newton at the same prescribed values from 0 converges?
        // simpler: store it through a zero-increment newton
        body.set_prescribed(&footing, Component::Y, -reached).unwrap();
        let r0 = fem_core::plastic::newton::solve(&mut body, &mut u, 0.0, 0.0, &newton);
        eprintln!("  re-equilibrate from 0: {:?}", r0.as_ref().map(|r| r.steps.len()).map_err(|e| e.to_string()));
        let target = reached + 0.05 / 20.0 / 8.0;
        body.set_prescribed(&footing, Component::Y, -target).unwrap();
        let (mut f_ext, mut f_int, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut prev: Vec<u8> = Vec::new();
        for it in 0..15 {
            rec.log.lock().unwrap().clear();
            body.external_force_into(0.0, &mut f_ext).unwrap();
            body.internal_force_into(&u, &mut f_int).unwrap();
            let log = rec.log.lock().unwrap().clone();
            let counts = [0u8, 1, 2].map(|k| log.iter().filter(|&&x| x == k).count());
            let switches = if prev.is_empty() {
                0
            } else {
                log.iter().zip(&prev).filter(|(a, b)| a != b).count()
            };
            let kinds: Vec<String> = if prev.is_empty() {
                vec![]
            } else {
                let mut m = std::collections::BTreeMap::new();
                for (a, b) in prev.iter().zip(&log) {
                    if a != b {
                        *m.entry((*a, *b)).or_insert(0) += 1;
                    }
                }
                m.iter().map(|((a, b), c)| format!("{a}->{b}:{c}")).collect()
            };
            prev = log;
            for i in 0..n {
                r[i] = f_ext[i] - f_int[i];
            }
            let scale = norm(&f_ext).max(norm(&f_int));
            let res = norm(&r) / scale;
            body.update_tangent().unwrap();
            let mut du = r.clone();
            let solved = body.solve_in_place(&mut du);
            // FD check of K du
            let kdu = matvec(&body, &du);
            let h = 1e-6 / norm(&du).max(1e-300) * norm(&u).max(1e-3);
            let up: Vec<f64> = u.iter().zip(&du).map(|(a, b)| a + h * b).collect();
            let um: Vec<f64> = u.iter().zip(&du).map(|(a, b)| a - h * b).collect();
            let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
            body.internal_force_into(&up, &mut fp).unwrap();
            body.internal_force_into(&um, &mut fm).unwrap();
            let fd: Vec<f64> = fp.iter().zip(&fm).map(|(a, b)| (a - b) / (2.0 * h)).collect();
            let err: Vec<f64> = fd.iter().zip(&kdu).map(|(a, b)| a - b).collect();
            eprintln!(
                "  it {it}: res {res:.2e}, regimes {counts:?}, switches {switches} {kinds:?}, FD err {:.2e}, solve {:?}",
                norm(&err) / norm(&kdu),
                solved.as_ref().err().map(|e| e.to_string())
            );
            body.internal_force_into(&u, &mut f_int).unwrap();
            if solved.is_err() || res < 1e-10 {
                break;
            }
            for (a, b) in u.iter_mut().zip(&du) {
                *a += b;
            }
        }
    }
}
