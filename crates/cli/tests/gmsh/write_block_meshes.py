#!/usr/bin/env python3
"""Writes the two structured Gmsh meshes of issue 35's quadrilateral and hexahedral scenes
(gmsh was not installed where they were made; the .geo scripts beside them make the same
meshes with `gmsh -2 quad_block.geo -format msh41` / `gmsh -3 hex_block.geo -format msh41`,
up to Gmsh's node and element numbering):

- quad_block.msh: the unit square [0, 1]^2 as 4 x 4 nine-node quadrangles (Gmsh type 10),
  physical surface 1 "block", physical curves "bottom" (y = 0) and "top" (y = 1) as
  three-node lines (type 8);
- ../solid/hex_block.msh: the box [0, 1] x [0, 1] x [0, 0.5] as 2 x 2 x 2 eight-node
  hexahedra (type 5), physical volume 7 "block", physical surfaces "bottom" (z = 0) and
  "top" (z = 0.5) as four-node quadrangles (type 3).

MSH 4.1 ASCII, one entity per dimension used (no $Entities bounding boxes are needed by
readers other than Gmsh's own; we write a minimal valid $Entities section).
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(v):
    return repr(float(v))


def write_quad_block(path, n=4):
    m = 2 * n  # lattice of the 9-node quadrangles
    tag = {}
    coords = []
    for j in range(m + 1):
        for i in range(m + 1):
            tag[(i, j)] = len(coords) + 1
            coords.append((i / m, j / m, 0.0))
    quads = []
    for cj in range(n):
        for ci in range(n):
            i, j = 2 * ci, 2 * cj
            c = [(i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2)]
            mids = [(i + 1, j), (i + 2, j + 1), (i + 1, j + 2), (i, j + 1)]
            quads.append([tag[p] for p in c + mids + [(i + 1, j + 1)]])
    bottom = [[tag[(2 * k, 0)], tag[(2 * k + 2, 0)], tag[(2 * k + 1, 0)]] for k in range(n)]
    # the top curve runs from right to left, as the boundary of a counter-clockwise square
    top = [[tag[(2 * k + 2, m)], tag[(2 * k, m)], tag[(2 * k + 1, m)]] for k in range(n)]
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
           "$PhysicalNames", "3", '1 2 "bottom"', '1 3 "top"', '2 1 "block"', "$EndPhysicalNames",
           "$Entities", "0 2 1 0",
           "1 0 0 0 1 0 0 1 2 0",
           "3 0 1 0 1 1 0 1 3 0",
           "1 0 0 0 1 1 0 1 1 0",
           "$EndEntities",
           "$Nodes", f"1 {len(coords)} 1 {len(coords)}", f"2 1 0 {len(coords)}"]
    out += [str(k + 1) for k in range(len(coords))]
    out += [" ".join(fmt(v) for v in p) for p in coords]
    out.append("$EndNodes")
    total = len(quads) + len(bottom) + len(top)
    out += ["$Elements", f"3 {total} 1 {total}"]
    e = 1
    out.append(f"1 1 8 {len(bottom)}")
    for line in bottom:
        out.append(" ".join(map(str, [e] + line)))
        e += 1
    out.append(f"1 3 8 {len(top)}")
    for line in top:
        out.append(" ".join(map(str, [e] + line)))
        e += 1
    out.append(f"2 1 10 {len(quads)}")
    for q in quads:
        out.append(" ".join(map(str, [e] + q)))
        e += 1
    out.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def write_hex_block(path, n=(2, 2, 2), size=(1.0, 1.0, 0.5)):
    nx, ny, nz = n
    tag = {}
    coords = []
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                tag[(i, j, k)] = len(coords) + 1
                coords.append((size[0] * i / nx, size[1] * j / ny, size[2] * k / nz))
    hexes = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                b = [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k)]
                t = [(a, bb, c + 1) for (a, bb, c) in b]
                hexes.append([tag[p] for p in b + t])
    # quadrangles with normals pointing out of the box
    bottom = [[tag[(i, j, 0)], tag[(i, j + 1, 0)], tag[(i + 1, j + 1, 0)], tag[(i + 1, j, 0)]]
              for j in range(ny) for i in range(nx)]
    top = [[tag[(i, j, nz)], tag[(i + 1, j, nz)], tag[(i + 1, j + 1, nz)], tag[(i, j + 1, nz)]]
           for j in range(ny) for i in range(nx)]
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
           "$PhysicalNames", "3", '2 8 "bottom"', '2 9 "top"', '3 7 "block"', "$EndPhysicalNames",
           "$Entities", "0 0 2 1",
           f"5 0 0 0 {size[0]} {size[1]} 0 1 8 0",
           f"6 0 0 {size[2]} {size[0]} {size[1]} {size[2]} 1 9 0",
           f"1 0 0 0 {size[0]} {size[1]} {size[2]} 1 7 0",
           "$EndEntities",
           "$Nodes", f"1 {len(coords)} 1 {len(coords)}", f"3 1 0 {len(coords)}"]
    out += [str(k + 1) for k in range(len(coords))]
    out += [" ".join(fmt(v) for v in p) for p in coords]
    out.append("$EndNodes")
    total = len(hexes) + len(bottom) + len(top)
    out += ["$Elements", f"3 {total} 1 {total}"]
    e = 1
    for (entity, faces) in [(5, bottom), (6, top)]:
        out.append(f"2 {entity} 3 {len(faces)}")
        for q in faces:
            out.append(" ".join(map(str, [e] + q)))
            e += 1
    out.append(f"3 1 5 {len(hexes)}")
    for h in hexes:
        out.append(" ".join(map(str, [e] + h)))
        e += 1
    out.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    write_quad_block(os.path.join(HERE, "quad_block.msh"))
    write_hex_block(os.path.join(HERE, "..", "solid", "hex_block.msh"))
