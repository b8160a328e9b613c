#!/usr/bin/env python3
"""Writes footing_dp.msh: the half model of examples/scenes/footing_dp.toml, P2 triangles, Gmsh 4.1
ASCII (the mesh of fem-core's `issue_40_strip_footing` test, `FootingMesh::CI`).

The soil is x in [0, W], y in [-H, 0], the footing's half-width B on y = 0, x <= B. A grid of
UNDER + BESIDE cells across and DOWN cells down, straight-sided, graded RATIO : 1 towards the
footing edge (B, 0) along both lines (a geometric progression: the cell next to the edge is the
smallest), each cell split into two 6-node triangles. Physical curves "footing" (y = 0, x <= B),
"surface" (y = 0, x >= B), "left" (x = 0), "right" (x = W), "bottom" (y = -H); physical surface
"soil" (tag 1, hence region 1). Needs only the standard library:

    python3 footing_dp.py > footing_dp.msh
"""

W, H, B = 10.0, 6.0, 1.0
UNDER, BESIDE, DOWN, RATIO = 10, 20, 14, 40.0


def graded(a, b, n, fine_at_end):
    """n cells from a to b, geometric, the largest RATIO times the smallest."""
    q = RATIO ** (1.0 / (n - 1)) if n > 1 else 1.0
    sizes = [q ** i for i in range(n)]  # growing
    if fine_at_end:
        sizes.reverse()
    total = sum(sizes)
    out, x = [a], a
    for s in sizes[:-1]:
        x += (b - a) * s / total
        out.append(x)
    out.append(b)
    return out


xs = graded(0.0, B, UNDER, True) + graded(B, W, BESIDE, False)[1:]
ys = graded(-H, 0.0, DOWN, True)
nx, ny = len(xs) - 1, len(ys) - 1
px = [xs[i // 2] if i % 2 == 0 else 0.5 * (xs[i // 2] + xs[i // 2 + 1]) for i in range(2 * nx + 1)]
py = [ys[j // 2] if j % 2 == 0 else 0.5 * (ys[j // 2] + ys[j // 2 + 1]) for j in range(2 * ny + 1)]
NW = 2 * nx + 1


def tag(i, j):
    return j * NW + i + 1


triangles = []
for cj in range(ny):
    for ci in range(nx):
        i, j = 2 * ci, 2 * cj
        c = [(i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2)]
        m = lambda a, b: ((a[0] + b[0]) // 2, (a[1] + b[1]) // 2)
        if (ci + cj) % 2 == 0:  # diagonal 0-2
            tris = [(c[0], c[1], c[2]), (c[0], c[2], c[3])]
        else:  # diagonal 1-3
            tris = [(c[0], c[1], c[3]), (c[1], c[2], c[3])]
        for a, b, d in tris:  # counter-clockwise; Gmsh Tri6: corners, then mids 01, 12, 20
            triangles.append([tag(*a), tag(*b), tag(*d), tag(*m(a, b)), tag(*m(b, d)), tag(*m(d, a))])


def side_lines(pts):
    """3-node lines (end, end, mid) along a lattice polyline of even length."""
    return [[tag(*pts[k]), tag(*pts[k + 2]), tag(*pts[k + 1])] for k in range(0, len(pts) - 1, 2)]


top, edge = 2 * ny, 2 * UNDER
curves = {
    1: ("bottom", side_lines([(i, 0) for i in range(NW)])),
    2: ("right", side_lines([(2 * nx, j) for j in range(2 * ny + 1)])),
    3: ("surface", side_lines([(i, top) for i in range(NW - 1, edge - 1, -1)])),
    4: ("footing", side_lines([(i, top) for i in range(edge, -1, -1)])),
    5: ("left", side_lines([(0, j) for j in range(2 * ny, -1, -1)])),
}
n_nodes = NW * (2 * ny + 1)
out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(curves) + 1)]
out += [f'1 {t} "{name}"' for t, (name, _) in curves.items()]
out += ['2 1 "soil"', "$EndPhysicalNames", "$Entities", f"0 {len(curves)} 1 0"]
for t in curves:
    out.append(f"{t} 0 {-H} 0 {W} 0 0 1 {t} 0")
out.append(f"1 0 {-H} 0 {W} 0 0 1 1 5 1 2 3 4 5")
out += ["$EndEntities", "$Nodes", f"1 {n_nodes} 1 {n_nodes}", f"2 1 0 {n_nodes}"]
out += [str(k) for k in range(1, n_nodes + 1)]
for j in range(2 * ny + 1):
    for i in range(NW):
        out.append(f"{px[i]!r} {py[j]!r} 0")
n_lines = sum(len(c[1]) for c in curves.values())
n_el = len(triangles) + n_lines
out += ["$EndNodes", "$Elements", f"{1 + len(curves)} {n_el} 1 {n_el}"]
e = 1
out.append(f"2 1 9 {len(triangles)}")
for t in triangles:
    out.append(" ".join(map(str, [e] + t)))
    e += 1
for t, (_, segs) in curves.items():
    out.append(f"1 {t} 8 {len(segs)}")
    for s in segs:
        out.append(" ".join(map(str, [e] + s)))
        e += 1
out.append("$EndElements")
print("\n".join(out))
