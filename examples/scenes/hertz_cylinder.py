#!/usr/bin/env python3
"""Writes hertz_cylinder.msh: the half cylinder of examples/scenes/hertz.toml, P2, Gmsh 4.1 ASCII.

The body is x in [0, L], between the arc y = R - sqrt(R^2 - x^2) (bottom) and y = H (top): a
rectangle grid, uniform over [0, b] in x and y (the contact zone) and growing geometrically
beyond, mapped by y' = y + (R - sqrt(R^2 - x^2)) (1 - y/H), mid-side nodes included (so P2
sides on the arc are curved). Physical curves "bottom" (the arc), "top", "axis" (x = 0) and
"right"; physical surface "body" (tag 1, hence region 1). Needs only the standard library:

    python3 hertz_cylinder.py > hertz_cylinder.msh
"""
import math

R, L, H = 100.0, 20.0, 20.0  # arc radius, half width, height
B, CELLS, GROWTH = 1.5, 8, 1.5  # uniform zone [0, B]^2 of CELLS^2 cells, then growth


def lines(end):
    h = B / CELLS
    out = [B * i / CELLS for i in range(CELLS + 1)]
    size = h * GROWTH
    while out[-1] + size < end - 0.5 * size:
        out.append(out[-1] + size)
        size *= GROWTH
    out.append(end)
    return out


xs, ys = lines(L), lines(H)
nx, ny = len(xs) - 1, len(ys) - 1
# P2 lattice: (2 nx + 1) x (2 ny + 1) points, odd indices at the middle of the cells
px = [xs[i // 2] if i % 2 == 0 else 0.5 * (xs[i // 2] + xs[i // 2 + 1]) for i in range(2 * nx + 1)]
py = [ys[j // 2] if j % 2 == 0 else 0.5 * (ys[j // 2] + ys[j // 2 + 1]) for j in range(2 * ny + 1)]
W = 2 * nx + 1


def tag(i, j):
    return j * W + i + 1


def point(i, j):
    x, y = px[i], py[j]
    cap = R - math.sqrt(R * R - x * x)
    return x, y + cap * (1.0 - y / H)


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


curves = {
    1: ("bottom", side_lines([(i, 0) for i in range(W)])),
    2: ("right", side_lines([(2 * nx, j) for j in range(2 * ny + 1)])),
    3: ("top", side_lines([(i, 2 * ny) for i in range(W - 1, -1, -1)])),
    4: ("axis", side_lines([(0, j) for j in range(2 * ny, -1, -1)])),
}
n_nodes = W * (2 * ny + 1)
out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "5"]
out += [f'1 {t} "{name}"' for t, (name, _) in curves.items()]
out += ['2 1 "body"', "$EndPhysicalNames", "$Entities", "0 4 1 0"]
for t in curves:
    out.append(f"{t} 0 0 0 {L} {H} 0 1 {t} 0")
out.append(f"1 0 0 0 {L} {H} 0 1 1 4 1 2 3 4")
out += ["$EndEntities", "$Nodes", f"1 {n_nodes} 1 {n_nodes}", f"2 1 0 {n_nodes}"]
out += [str(k) for k in range(1, n_nodes + 1)]
for j in range(2 * ny + 1):
    for i in range(W):
        x, y = point(i, j)
        out.append(f"{x!r} {y!r} 0")
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
