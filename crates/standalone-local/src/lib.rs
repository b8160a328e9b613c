//! A host code's view of `contact-solver` with `default-features = false`: it condenses its own
//! contact problem to `x = W r + q` (here: a chain of springs pressed on a rough rigid floor)
//! and hands it to the local layer, without compiling `fem-core`, `vtkio` or any FE coupling.
//!
//! Run `cargo run -p standalone-local` for the numbers; `tests/` checks them against closed
//! forms and the Coulomb conditions.

use contact_solver::{ReducedProblem, SolverError};

/// The reduced problem of `n` nodes, each on a vertical spring of flexibility `f` (node `i`
/// pushed down by `d_i`), linked horizontally to its neighbours by springs of stiffness `k`
/// and pulled sideways at node 0 by a free tangential gap `s`; friction coefficient `mu`.
///
/// `W` is the flexibility of that system at the contact points, normal first per contact:
/// the normal blocks are decoupled (`f` on the diagonal), the tangential part is the inverse
/// of a grounded chain stiffness `K_t = k·tridiag(−1, 2, −1) + k_g I` (`k_g = 1/f`), so `W`
/// is dense, symmetric and positive definite.
///
/// # Errors
/// As for [`ReducedProblem::new`].
pub fn spring_chain(
    n: usize,
    f: f64,
    k: f64,
    d: &[f64],
    s: f64,
    mu: f64,
) -> Result<ReducedProblem, SolverError> {
    let kt = tangential_flexibility(n, k, 1.0 / f);
    let m = 2 * n;
    let mut w = vec![0.0; m * m];
    let mut q = vec![0.0; m];
    for i in 0..n {
        w[(2 * i) * m + 2 * i] = f;
        for j in 0..n {
            w[(2 * i + 1) * m + 2 * j + 1] = kt[i * n + j];
        }
        q[2 * i] = -d[i];
    }
    q[1] = s;
    ReducedProblem::new(w, q, vec![mu; n])
}

/// Inverse of `k·tridiag(−1, 2, −1) + k_g I` (n × n, row-major), by Gauss–Jordan: the host
/// code's own linear algebra, nothing borrowed from the library.
fn tangential_flexibility(n: usize, k: f64, kg: f64) -> Vec<f64> {
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        a[i * n + i] = 2.0 * k + kg;
        if i > 0 {
            a[i * n + i - 1] = -k;
        }
        if i + 1 < n {
            a[i * n + i + 1] = -k;
        }
    }
    let mut inv = vec![0.0; n * n];
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    // The matrix is SPD and diagonally dominant: no pivoting needed.
    for c in 0..n {
        let p = a[c * n + c];
        for j in 0..n {
            a[c * n + j] /= p;
            inv[c * n + j] /= p;
        }
        for r in 0..n {
            if r != c {
                let factor = a[r * n + c];
                for j in 0..n {
                    a[r * n + j] -= factor * a[c * n + j];
                    inv[r * n + j] -= factor * inv[c * n + j];
                }
            }
        }
    }
    inv
}
