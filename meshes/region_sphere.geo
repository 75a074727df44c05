// A spherical particle region for coupled runs (Coupling/particle region file): radius 0.1 m
// about (0.12, 0.12, 0.12), inside the 0.24 m cube of tests/coupling (coupling_check *_volume)
// and examples/coupled_ball_region.prm. Tetrahedra of about 5 mm: the facets depart from the
// sphere by about h^2 / (6 R) = 0.04 mm.
// Generate: gmsh -3 -format msh22 region_sphere.geo -o region_sphere.msh
SetFactory("OpenCASCADE");
Sphere(1) = {0.12, 0.12, 0.12, 0.1};
Physical Volume("particle-region") = {1};
Mesh.CharacteristicLengthMin = 0.005;
Mesh.CharacteristicLengthMax = 0.005;
