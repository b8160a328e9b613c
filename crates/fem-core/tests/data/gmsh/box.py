#!/usr/bin/env python3
"""Writes box_p1.msh and box_p2.msh (Gmsh 4.1 ASCII) with the Gmsh SDK (`pip install gmsh`;
made with Gmsh 4.15.2), for the node sets and areas of physical surfaces (issue 36).

The box [0, 2] x [0, 1] x [0, 0.5] (OpenCASCADE kernel), meshed unstructured (size 0.6),
physical volume "body" (tag 1) and physical surfaces "top" (z = 0.5, area 2) and "sides"
(x = 0 and x = 2, two disjoint faces of area 0.5 each). Run:

    python3 box.py
"""
import gmsh

for order in (1, 2):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("box")
    v = gmsh.model.occ.addBox(0, 0, 0, 2, 1, 0.5)
    gmsh.model.occ.synchronize()
    faces = gmsh.model.getBoundary([(3, v)], oriented=False)
    def face_at(axis, value):
        for dim, tag in faces:
            lo = gmsh.model.getBoundingBox(dim, tag)
            if abs(lo[axis] - value) < 1e-6 and abs(lo[axis + 3] - value) < 1e-6:
                return tag
    m = gmsh.model
    m.addPhysicalGroup(3, [v], 1, "body")
    m.addPhysicalGroup(2, [face_at(2, 0.5)], 11, "top")
    m.addPhysicalGroup(2, [face_at(0, 0.0), face_at(0, 2.0)], 12, "sides")
    m.mesh.setSize(m.getEntities(0), 0.6)
    m.mesh.generate(3)
    m.mesh.setOrder(order)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(f"box_p{order}.msh")
    gmsh.finalize()
