// The 3D Signorini patch of tests/cli/solid.rs: a 1 x 1 x 0.5 block of P2 tetrahedra.
// Regenerate with: gmsh -3 patch.geo -format msh41 -o patch.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Physical Volume("block", 7) = {1};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Mesh.ElementOrder = 2;
Mesh.MeshSizeMax = 0.5;
Mesh.MeshSizeMin = 0.5;
Mesh.Binary = 0;
