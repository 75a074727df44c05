// The particle region of examples/coupled_compression.prm (the middle 0.09 m of the thesis
// specimen) as a gmsh volume, tetrahedra: a coupled run with Coupling/particle region file = this
// mesh must give the box run's result (tests/coupling: coupled_compression_region_box).
// Generate: gmsh -3 -format msh22 region_compression_box.geo -o region_compression_box.msh
SetFactory("OpenCASCADE");
Box(1) = {0.08, 0, 0, 0.09, 0.1, 0.1};
Physical Volume("particle-region") = {1};
Mesh.CharacteristicLengthMax = 0.02;
