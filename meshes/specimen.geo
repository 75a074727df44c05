// The 0.25 x 0.1 x 0.1 m specimen of the thesis (section 4, three-point bending, Fig. 28) as a
// structured hexahedral mesh for deal.II, with the support and load strips as physical groups.
//   x along the length, y across the width, z up; supports on the bottom (z = 0), load on top.
//   pin    : bottom strip x in [0, s]           (thesis: left corner particles)
//   roller : bottom strip x in [L - s, L]       (thesis: right corner particles)
//   load   : top strip    x in [L/2 - b/2, L/2 + b/2]
// Span between strip centres Le = L - s = 0.24 m for s = 0.01 m (corner particles of radius
// 5 mm); load width b = 0.01 m (eq. 68 of the thesis with b).
// Generate: gmsh -3 -format msh22 specimen.geo -o specimen.msh
L = 0.25; W = 0.1; H = 0.1;
s = 0.01;   // support strip width (m)
b = 0.01;   // load strip width (m)
nx_strip = 1; nx_span = 3; ny = 2; nz = 2; // coarse layers (9 x 2 x 2); refine in deal.II

xs[] = {0, s, L/2 - b/2, L/2 + b/2, L - s, L};
nxs[] = {nx_strip, nx_span, nx_strip, nx_span, nx_strip};
For i In {0:5}
  Point(i + 1) = {xs[i], 0, 0};
EndFor
For i In {0:4}
  Line(i + 1) = {i + 1, i + 2};
  Transfinite Curve{i + 1} = nxs[i] + 1;
EndFor

For i In {0:4}
  bottom[] = Extrude {0, W, 0} { Curve{i + 1}; Layers{ny}; Recombine; };
  bottom_surface[i] = bottom[1];
  body[] = Extrude {0, 0, H} { Surface{bottom[1]}; Layers{nz}; Recombine; };
  top_surface[i] = body[0];
  volume[i] = body[1];
  If (i == 0)
    left_surface = body[5];
  EndIf
  If (i == 4)
    right_surface = body[3];
  EndIf
EndFor

Physical Surface("pin", 1) = {bottom_surface[0]};
Physical Surface("roller", 2) = {bottom_surface[4]};
Physical Surface("load", 3) = {top_surface[2]};
Physical Surface("left", 4) = {left_surface};
Physical Surface("right", 5) = {right_surface};
Physical Curve("pin_edge", 6) = {1};
Physical Volume("specimen", 7) = {volume[]};
