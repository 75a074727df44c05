// Notched beam for the later damage runs: the 0.25 x 0.1 x 0.1 m specimen with a through-width
// notch at midspan on the tension (bottom) side, structured hexahedra for deal.II.
//   notch  : x in [L/2 - n/2, L/2 + n/2], z in [0, a], all y (faces: physical group "notch")
//   pin, roller : bottom support strips of width s at the ends; load : top strip of width b.
// The notch is a column of cells that is extruded but left out of the physical volume, so gmsh
// (MSH 2.2 writes only physical elements) leaves a slot whose faces are the group "notch".
// Generate: gmsh -3 -format msh22 notched_beam.geo -o notched_beam.msh
L = 0.25; W = 0.1; H = 0.1;
s = 0.01;   // support strip width (m)
b = 0.01;   // load strip width (m)
n = 0.002;  // notch width (m)
a = 0.02;   // notch depth (m)
ny = 2; nz_low = 1; nz_high = 2;

xs[] = {0, s, L/2 - b/2, L/2 - n/2, L/2 + n/2, L/2 + b/2, L - s, L};
nxs[] = {1, 3, 1, 1, 1, 3, 1};
notch = 3; // index of the notch segment
For i In {0:7}
  Point(i + 1) = {xs[i], 0, 0};
EndFor
For i In {0:6}
  Line(i + 1) = {i + 1, i + 2};
  Transfinite Curve{i + 1} = nxs[i] + 1;
EndFor

solid[] = {};
For i In {0:6}
  bottom[] = Extrude {0, W, 0} { Curve{i + 1}; Layers{ny}; Recombine; };
  bottom_surface[i] = bottom[1];
  low[] = Extrude {0, 0, a} { Surface{bottom[1]}; Layers{nz_low}; Recombine; };
  high[] = Extrude {0, 0, H - a} { Surface{low[0]}; Layers{nz_high}; Recombine; };
  top_surface[i] = high[0];
  solid[] += {high[1]};
  If (i != notch)
    solid[] += {low[1]};
  EndIf
  If (i == notch)
    notch_faces[] = {low[0], low[3], low[5]};
  EndIf
EndFor

Physical Surface("pin", 1) = {bottom_surface[0]};
Physical Surface("roller", 2) = {bottom_surface[6]};
Physical Surface("load", 3) = {top_surface[2], top_surface[3], top_surface[4]};
Physical Surface("notch", 4) = {notch_faces[]};
Physical Volume("beam", 5) = {solid[]};
