// The hexahedral block of tests/solid/patch_hex.toml: [0, 1] x [0, 1] x [0, 0.5] as
// 2 x 2 x 2 eight-node hexahedra (Gmsh type 5), physical volume 7 "block", physical
// surfaces "bottom" (z = 0) and "top" (z = 0.5), quadrangles.
// Regenerate with: gmsh -3 hex_block.geo -format msh41 -o hex_block.msh
// (the committed file was written by ../gmsh/write_block_meshes.py, gmsh being unavailable
// there: the same mesh up to Gmsh's numbering)
Point(1) = {0, 0, 0};
l[] = Extrude {1, 0, 0} {Point{1}; Layers{2};};
s[] = Extrude {0, 1, 0} {Line{l[1]}; Layers{2}; Recombine;};
v[] = Extrude {0, 0, 0.5} {Surface{s[1]}; Layers{2}; Recombine;};
Physical Volume("block", 7) = {v[1]};
Physical Surface("bottom", 8) = {s[1]};
Physical Surface("top", 9) = {v[0]};
Mesh.ElementOrder = 1;
Mesh.Binary = 0;
