//! The pressure recovery of `work_precision_hertz`: the L2 projection of the bottom edge's
//! nodal forces, its lumped form, and the L2 distance to Hertz's pressure (a module of the
//! example, kept apart for its size).

use faer::Mat;
use faer::linalg::solvers::Solve;
use fem_core::Mesh;

// Gauss–Legendre, 4 points on [0, 1] (the rule of `project_pressure_at_origin`).
const GAUSS_X: [f64; 4] = [
    0.069_431_844_202_973_71,
    0.330_009_478_207_571_9,
    0.669_990_521_792_428_1,
    0.930_568_155_797_026_3,
];
const GAUSS_W: [f64; 4] = [
    0.173_927_422_568_726_9,
    0.326_072_577_431_273_1,
    0.326_072_577_431_273_1,
    0.173_927_422_568_726_9,
];

/// `∫_lo^hi f`, 4-point Gauss on each of 4 equal sub-intervals.
fn integrate(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    const PIECES: usize = 4;
    let d = (hi - lo) / PIECES as f64;
    (0..PIECES)
        .map(|k| {
            let a = lo + k as f64 * d;
            GAUSS_X
                .iter()
                .zip(&GAUSS_W)
                .map(|(&s, &w)| w * d * f(a + s * d))
                .sum::<f64>()
        })
        .sum()
}

/// Shape functions of a bottom side in its parameter `s ∈ [0, 1]`, local order `[a, b, mid]`.
fn side_shape(s: f64, nodes: usize) -> [f64; 3] {
    if nodes == 3 {
        [
            (1.0 - s) * (1.0 - 2.0 * s),
            s * (2.0 * s - 1.0),
            4.0 * s * (1.0 - s),
        ]
    } else {
        [1.0 - s, s, 0.0]
    }
}

/// The pressure recovered on the bottom edge.
pub(crate) struct Recovered {
    /// The edge's nodes, sorted.
    pub(crate) nodes: Vec<usize>,
    /// The L2 projection `M p = f` at each node.
    pub(crate) projected: Vec<f64>,
    /// The lumped recovery `p_i = f_i / Σ_j M_ij` at each node (NaN where `Σ_j M_ij = 0`).
    pub(crate) lumped: Vec<f64>,
}

/// The L2 projection `M p = f` of the nodal forces on the bottom edge (the recipe of
/// `hertz_scene::project_pressure_at_origin`, every nodal value kept), and the lumped
/// recovery beside it.
pub(crate) fn project_pressure(mesh: &Mesh, force: &[f64], axisymmetric: bool) -> Recovered {
    let sides = mesh.edge_set("bottom").expect("the scene tags its bottom");
    let mut nodes: Vec<usize> = sides.iter().flat_map(|&s| mesh.side_nodes(s)).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let index = |n: usize| nodes.binary_search(&n).expect("a bottom node");
    let m = nodes.len();
    let mut mass = Mat::<f64>::zeros(m, m);
    for &side in sides {
        let local: Vec<usize> = mesh.side_nodes(side).collect();
        let (xa, xb) = (mesh.nodes()[local[0]][0], mesh.nodes()[local[1]][0]);
        for (&s, &w) in GAUSS_X.iter().zip(&GAUSS_W) {
            let shape = side_shape(s, local.len());
            let x = xa + s * (xb - xa);
            let weight = w * (xb - xa).abs() * if axisymmetric { x } else { 1.0 };
            for (i, &ni) in local.iter().enumerate() {
                for (j, &nj) in local.iter().enumerate() {
                    mass[(index(ni), index(nj))] += weight * shape[i] * shape[j];
                }
            }
        }
    }
    // ∫ N_i w dx is 0 for a P2 vertex on the axis (w = r): no lumped value there
    let scale = (0..m).map(|i| mass[(i, i)]).fold(0.0, f64::max);
    let lumped = (0..m)
        .map(|i| {
            let row: f64 = (0..m).map(|j| mass[(i, j)]).sum();
            if row.abs() > 1e-12 * scale {
                force[nodes[i]] / row
            } else {
                f64::NAN
            }
        })
        .collect();
    let rhs = Mat::<f64>::from_fn(m, 1, |i, _| force[nodes[i]]);
    let p = mass.partial_piv_lu().solve(&rhs);
    let projected = (0..m).map(|i| p[(i, 0)]).collect();
    Recovered {
        nodes,
        projected,
        lumped,
    }
}

/// `‖p_h − p_H‖ / ‖p_H‖` over the bottom edge (weight `x` in axisymmetry), with
/// `p_H(x) = p0 √(1 − x²/a²)` for `x < a`, 0 beyond.
///
/// ```text
/// ‖p_H‖² = p0² 2a/3   (plane strain, ∫_0^a (1 − x²/a²) dx)
///        = p0² a²/4   (axisymmetric, ∫_0^a r (1 − r²/a²) dr)
/// ```
pub(crate) fn pressure_l2_error(
    mesh: &Mesh,
    recovered: &Recovered,
    axisymmetric: bool,
    a: f64,
    p0: f64,
) -> f64 {
    let hertz = |x: f64| p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
    let weight = |x: f64| if axisymmetric { x } else { 1.0 };
    let mut squared = 0.0;
    for &side in mesh.edge_set("bottom").expect("the scene tags its bottom") {
        let local: Vec<usize> = mesh.side_nodes(side).collect();
        let (xa, xb) = (mesh.nodes()[local[0]][0], mesh.nodes()[local[1]][0]);
        let values: Vec<f64> = local
            .iter()
            .map(|&n| {
                let i = recovered.nodes.binary_search(&n).expect("a bottom node");
                recovered.projected[i]
            })
            .collect();
        let p_h = |x: f64| {
            let shape = side_shape((x - xa) / (xb - xa), local.len());
            values.iter().zip(shape).map(|(v, n)| v * n).sum::<f64>()
        };
        let f = |x: f64| (p_h(x) - hertz(x)).powi(2) * weight(x);
        let (lo, hi) = (xa.min(xb), xa.max(xb));
        if lo < a {
            // x = a − u², dx = −2u du: p_H = p0/a · u √(a + x) is smooth in u
            let top = hi.min(a);
            squared += integrate(
                |u| {
                    let x = a - u * u;
                    2.0 * u * f(x)
                },
                (a - top).sqrt(),
                (a - lo).sqrt(),
            );
        }
        if hi > a {
            squared += integrate(f, lo.max(a), hi);
        }
    }
    let reference = if axisymmetric {
        p0 * p0 * a * a / 4.0
    } else {
        p0 * p0 * 2.0 * a / 3.0
    };
    (squared / reference).sqrt()
}
