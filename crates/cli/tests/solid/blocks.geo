// Two P2 blocks of tests/cli/solid.rs, one on the other, each with its own nodes on the
// interface z = 1 (two boxes, not fused): [0,1]^2 x [0,1] (volume 1) under [0,1]^2 x [1,2]
// (volume 2), structured (transfinite, 2 cells a side), so the interface nodes match.
// Regenerate with: gmsh -3 blocks.geo -format msh41 -o blocks.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
Physical Volume("lower", 1) = {1};
Physical Volume("upper", 2) = {2};
Physical Surface("base") = {5};
Physical Surface("lower_top") = {6};
Physical Surface("upper_bottom") = {11};
Physical Surface("top") = {12};
Physical Surface("x0") = {1, 7};
Physical Surface("y0") = {3, 9};
Transfinite Curve {:} = 3;
Transfinite Surface {:};
Transfinite Volume {:};
Mesh.ElementOrder = 2;
Mesh.Binary = 0;
