// The quadrilateral block of tests/gmsh/quad_block.toml: the unit square as 4 x 4 nine-node
// quadrangles (Gmsh type 10), physical surface 1 "block", physical curves "bottom", "top".
// Regenerate with: gmsh -2 quad_block.geo -format msh41 -o quad_block.msh
// (the committed file was written by write_block_meshes.py, gmsh being unavailable there:
// the same mesh up to Gmsh's numbering)
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 5;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("block", 1) = {1};
Physical Curve("bottom", 2) = {1};
Physical Curve("top", 3) = {3};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;
Mesh.Binary = 0;
