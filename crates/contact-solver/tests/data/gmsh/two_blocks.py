#!/usr/bin/env python3
"""Writes two_blocks_p1.msh and two_blocks_p2.msh (Gmsh 4.1 ASCII) with the Gmsh SDK
(`pip install gmsh`; made with Gmsh 4.15.2): a block pressed on a block, issue 36.

    upper: [0, 2] x [0, 1]    physical surface "upper" (tag 2), curves "upper_bottom", "upper_top"
    lower: [0, 2] x [-1, 0]   physical surface "lower" (tag 1), curves "lower_bottom", "lower_top"

The two blocks share no node (two separate surfaces of the built-in kernel, each with its own
points), so the interface y = 0 holds two coincident curves. Both are transfinite, NX x NY
cells, each cell cut by a diagonal alternating as the library's `rectangle` generator does
(Gmsh's "AlternateLeft" arrangement), so the nodes (and, for the run comparison, the triangles)
are the generator's. Gmsh numbers the points first, then the nodes inside each curve, then
the surfaces' nodes, and orients the curves as the loops go: sorting a curve's nodes by tag
does not follow the curve ("lower_top_tagged", the lower top joined by a physical point of
the same name, is such a set, sorted by tag: it serves the checks of `bipo check`). Run:

    python3 two_blocks.py
"""
import gmsh

NX, NY = 4, 2


def block(y0, y1):
    g = gmsh.model.geo
    p = [g.addPoint(0, y0, 0), g.addPoint(2, y0, 0), g.addPoint(2, y1, 0), g.addPoint(0, y1, 0)]
    lines = [g.addLine(p[k], p[(k + 1) % 4]) for k in range(4)]
    loop = g.addCurveLoop(lines)
    s = g.addPlaneSurface([loop])
    for k, line in enumerate(lines):
        g.mesh.setTransfiniteCurve(line, (NX if k % 2 == 0 else NY) + 1)
    g.mesh.setTransfiniteSurface(s, "AlternateLeft", p)
    return s, lines


for order in (1, 2):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("two_blocks")
    lower, ll = block(-1.0, 0.0)
    upper, ul = block(0.0, 1.0)
    gmsh.model.geo.synchronize()
    m = gmsh.model
    m.addPhysicalGroup(2, [lower], 1, "lower")
    m.addPhysicalGroup(2, [upper], 2, "upper")
    m.addPhysicalGroup(1, [ll[0]], 11, "lower_bottom")
    m.addPhysicalGroup(1, [ll[2]], 12, "lower_top")
    m.addPhysicalGroup(1, [ul[0]], 13, "upper_bottom")
    m.addPhysicalGroup(1, [ul[2]], 14, "upper_top")
    m.addPhysicalGroup(0, [4], 21, "lower_left_top")
    # the lower top again, joined by a physical point of the same name: the reader then keeps
    # one set sorted by tag (no longer one curve), the order of old: a polyline that zig-zags
    m.addPhysicalGroup(1, [ll[2]], 15, "lower_top_tagged")
    m.addPhysicalGroup(0, [4], 22, "lower_top_tagged")
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(order)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(f"two_blocks_p{order}.msh")
    gmsh.finalize()
