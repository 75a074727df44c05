// A cylindrical core specimen (Particles/specimen volume): diameter 0.1 m, height 0.2 m (twice
// the diameter, the usual core), axis z from z = 0, centred on the z axis. Tetrahedra of at most
// 8 mm: about 40 facets around the circumference, whose flat faces stand inside the circle by
// R (1 - cos(pi / 40)) = 0.15 mm. examples/compression_core_cubic.prm and tests/specimens fill it
// with r = 5 mm spheres (10 diameters across, 20 along).
// Generate: gmsh -3 -format msh22 core_cylinder.geo -o core_cylinder.msh (the build does this
// for every meshes/*.geo, into <build>/meshes).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 0.2, 0.05};
Physical Volume("core") = {1};
Mesh.CharacteristicLengthMax = 0.008;
