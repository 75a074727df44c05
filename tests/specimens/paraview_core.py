# pvpython check that ParaView shows the core of Particles/specimen volume as a cylinder: the
# particle series of the run (OUT/particles.pvd) holds summary.json's n_particles spheres, every
# one wholly inside the cylinder of radius R and height H about the z axis (axis distance + r
# <= R, r <= z <= H - r, to 1e-9 R), and they reach its rim (the largest axis distance + r
# within 2r of R) and both end faces (within 1e-3 H: the file holds the compressed state, the top
# moved down by 5e-5 H), so what ParaView draws is the core, not the box. The exit code is the
# result.
#     pvpython paraview_core.py OUT R H
import json
import math
import sys

from paraview import servermanager
from paraview.simple import PVDReader

out, R, H = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
with open(out + "/summary.json") as f:
    n_expected = json.load(f)["n_particles"]
reader = PVDReader(FileName=out + "/particles.pvd")
reader.UpdatePipeline()
p = servermanager.Fetch(reader)
radius = p.GetPointData().GetArray("radius")
n = p.GetNumberOfPoints()
rim = 0.0
z_lo, z_hi = math.inf, -math.inf
outside = 0
tol = 1e-9 * R
for i in range(n):
    x, y, z = p.GetPoint(i)
    r = radius.GetValue(i)
    rho = math.hypot(x, y) + r
    rim = max(rim, rho)
    z_lo, z_hi = min(z_lo, z - r), max(z_hi, z + r)
    outside += rho > R + tol or z - r < -tol or z + r > H + tol
r0 = radius.GetValue(0)
print(f"ParaView: {n} particles (summary: {n_expected}), {outside} outside the cylinder; rim "
      f"{rim:.6g} m (R = {R:g} m), z from {z_lo:.6g} to {z_hi:.6g} m (H = {H:g} m)")
ok = n == n_expected and outside == 0 and rim > R - 2 * r0
ok = ok and abs(z_lo) <= 1e-3 * H and abs(z_hi - H) <= 1e-3 * H
print("ok" if ok else "FAIL")
sys.exit(0 if ok else 1)
