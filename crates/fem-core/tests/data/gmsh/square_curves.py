#!/usr/bin/env python3
"""Writes square_curves_p1.msh and square_curves_p2.msh (Gmsh 4.1 ASCII) with the Gmsh SDK
(`pip install gmsh`; made with Gmsh 4.15.2), for the ordering of physical curves (issue 36).

The square [0, 2] x [0, 1] is cut by the line x = 1 into two surfaces sharing it (one mesh,
conforming), meshed unstructured (size 0.3). Physical curves:

    "bottom"  the two bottom lines, (0,0) -> (1,0) -> (2,0): one open chain across a point
    "outline" the six boundary lines: one closed curve
    "middle"  the line x = 1 inside the square (its sides are shared by two triangles)
    "tee"     the outline and the middle line: branches at (1, 0) and (1, 1)
    "ends"    the lines x = 0 and x = 2: two disjoint pieces

Physical surfaces "left" (tag 1) and "right" (tag 2). Run:

    python3 square_curves.py
"""
import gmsh

for order in (1, 2):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("square_curves")
    g = gmsh.model.geo
    size = 0.3
    p = [g.addPoint(x, y, 0, size) for x, y in [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]]
    b1, b2 = g.addLine(p[0], p[1]), g.addLine(p[1], p[2])
    right = g.addLine(p[2], p[3])
    t2, t1 = g.addLine(p[3], p[4]), g.addLine(p[4], p[5])
    left = g.addLine(p[5], p[0])
    mid = g.addLine(p[1], p[4])
    s1 = g.addPlaneSurface([g.addCurveLoop([b1, mid, t1, left])])
    s2 = g.addPlaneSurface([g.addCurveLoop([b2, right, t2, -mid])])
    g.synchronize()
    m = gmsh.model
    m.addPhysicalGroup(2, [s1], 1, "left")
    m.addPhysicalGroup(2, [s2], 2, "right")
    m.addPhysicalGroup(1, [b2, b1], 11, "bottom")
    m.addPhysicalGroup(1, [b1, b2, right, t2, t1, left], 12, "outline")
    m.addPhysicalGroup(1, [mid], 13, "middle")
    m.addPhysicalGroup(1, [b1, b2, right, t2, t1, left, mid], 14, "tee")
    m.addPhysicalGroup(1, [left, right], 15, "ends")
    m.mesh.generate(2)
    m.mesh.setOrder(order)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(f"square_curves_p{order}.msh")
    gmsh.finalize()
