//! Shared mesh helpers of fem-core's integration tests.
#![allow(dead_code)]

use fem_core::{ElementKind, Mesh, Side};

// ---------------------------------------------------------------------------------------------
// A structured, optionally distorted, mesh of the unit square, mapped by a closure.

/// xorshift64*: a small deterministic generator (no `rand` dependency), values in [−1, 1).
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (v >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// `nx × ny` cells on the unit square `(s, t) ∈ [0, 1]²`, mapped to the domain by `map`; two
/// triangles per cell with alternating diagonals. Interior vertices move by up to `distort`
/// cell sizes; for P2, interior mid-side nodes move by up to `curve` cell sizes (0 keeps them
/// at the images of the mid-sides, so they lie on mapped curves). Edge sets and node sets
/// "bottom", "right", "top", "left" (images of `t = 0`, `s = 1`, `t = 1`, `s = 0`); node sets
/// "boundary" and "interior".
pub fn grid(
    kind: ElementKind,
    [nx, ny]: [usize; 2],
    distort: f64,
    curve: f64,
    seed: u64,
    map: impl Fn([f64; 2]) -> [f64; 2],
) -> Mesh {
    let step = if kind == ElementKind::Tri6 { 2 } else { 1 };
    let (mx, my) = (step * nx, step * ny);
    let id = |i: usize, j: usize| j * (mx + 1) + i;
    let mut rng = Rng(seed);
    let on_boundary = |i: usize, j: usize| i == 0 || j == 0 || i == mx || j == my;
    // Parameter coordinates in cell units; vertices first.
    let mut p = vec![[f64::NAN; 2]; (mx + 1) * (my + 1)];
    for j in (0..=my).step_by(step) {
        for i in (0..=mx).step_by(step) {
            let mut q = [(i / step) as f64, (j / step) as f64];
            if !on_boundary(i, j) {
                q[0] += distort * rng.next();
                q[1] += distort * rng.next();
            }
            p[id(i, j)] = q;
        }
    }
    let mut conn = Vec::new();
    let mut sets: [(&str, Vec<Side>); 4] = [
        ("bottom", vec![]),
        ("right", vec![]),
        ("top", vec![]),
        ("left", vec![]),
    ];
    for cj in 0..ny {
        for ci in 0..nx {
            let (i, j) = (step * ci, step * cj);
            let (sw, se, ne, nw) = ([i, j], [i + step, j], [i + step, j + step], [i, j + step]);
            let tris = if (ci + cj) % 2 == 0 {
                [[sw, se, ne], [sw, ne, nw]]
            } else {
                [[sw, se, nw], [se, ne, nw]]
            };
            for t in tris {
                let element = conn.len() / kind.node_count();
                conn.extend(t.iter().map(|c| id(c[0], c[1])));
                if step == 2 {
                    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                        let m = [(t[a][0] + t[b][0]) / 2, (t[a][1] + t[b][1]) / 2];
                        let (pa, pb) = (p[id(t[a][0], t[a][1])], p[id(t[b][0], t[b][1])]);
                        let mut q = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0];
                        if !on_boundary(m[0], m[1]) && p[id(m[0], m[1])][0].is_nan() {
                            q[0] += curve * rng.next();
                            q[1] += curve * rng.next();
                        }
                        if p[id(m[0], m[1])][0].is_nan() {
                            p[id(m[0], m[1])] = q;
                        }
                        conn.push(id(m[0], m[1]));
                    }
                }
                for (side, (a, b)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                    let (ca, cb) = (t[a], t[b]);
                    let which = if ca[1] == 0 && cb[1] == 0 {
                        Some(0)
                    } else if ca[0] == mx && cb[0] == mx {
                        Some(1)
                    } else if ca[1] == my && cb[1] == my {
                        Some(2)
                    } else if ca[0] == 0 && cb[0] == 0 {
                        Some(3)
                    } else {
                        None
                    };
                    if let Some(w) = which {
                        sets[w].1.push(Side {
                            element,
                            side: side as u8,
                        });
                    }
                }
            }
        }
    }
    let nodes: Vec<[f64; 2]> = p
        .iter()
        .map(|q| map([q[0] / nx as f64, q[1] / ny as f64]))
        .collect();
    let mut mesh = Mesh::new(nodes, kind, conn, vec![]).unwrap();
    for (name, on) in [
        ("bottom", [None, Some(0)]),
        ("right", [Some(mx), None]),
        ("top", [None, Some(my)]),
        ("left", [Some(0), None]),
    ] {
        let nodes = (0..=my)
            .flat_map(|j| (0..=mx).map(move |i| (i, j)))
            .filter(|&(i, j)| on[0].is_none_or(|v| v == i) && on[1].is_none_or(|v| v == j))
            .map(|(i, j)| id(i, j))
            .collect();
        mesh.add_node_set(name, nodes).unwrap();
    }
    let all = (0..=my).flat_map(|j| (0..=mx).map(move |i| (i, j)));
    let (bnd, int): (Vec<_>, Vec<_>) = all.partition(|&(i, j)| on_boundary(i, j));
    let ids = |v: Vec<(usize, usize)>| v.into_iter().map(|(i, j)| id(i, j)).collect();
    mesh.add_node_set("boundary", ids(bnd)).unwrap();
    mesh.add_node_set("interior", ids(int)).unwrap();
    for (name, sides) in sets {
        mesh.add_edge_set(name, sides).unwrap();
    }
    mesh
}
