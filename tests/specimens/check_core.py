#!/usr/bin/env python3
"""Checks of a cylindrical core cut from a packing (Particles/specimen volume, docs/specimens.md).

    check_core.py cubic SUMMARY.json CORE.msh RADIUS E_B
        The simple cubic core. The lattice fills the core's bounding box (read from the mesh's
        nodes) exactly as the lattice generator does; the columns whose spheres lie wholly inside
        the cylinder (axis distance <= R - r) are counted here, independently of the code, with
        a margin of at least r / 5 between every column and that limit (so the facets of the
        meshed circle, which stand 0.03 r inside it, cannot change the count). Checks:
          n_particles = columns x layers, exactly;
          E over the lattice cells (columns x (2r)^2) = pi E_b / 4 within 1e-6 (the columns
            carry the load independently; the box specimen's closed form, tests/app checks the
            box to the same 1e-6);
          E over the nominal area pi R^2 against the box's pi E_b / 4: in the ratio of the
            core's solid fraction to the box's, within 1e-6.
    check_core.py fill SUMMARY.json CORE.msh RADIUS TOL
        Any packing (HCP, random): the core holds as many spheres as the box packing's number
        density (summary.json's porosity is the box's) puts in the region where a whole
        sphere's centre may lie (radius R - r, height H - 2r), within relative TOL; and every
        sphere lies within the cylinder: the particles' bounding square (radii included,
        summary's cross_section_area) is at most (2R)^2.

Prints every number it judges; exit 1 on any failed check. Plain python3.
"""
import json
import math
import sys

failures = []


def check(ok, text):
    print(("ok   " if ok else "FAIL ") + text)
    if not ok:
        failures.append(text)


def near(value, reference, tol, what):
    rel = abs(value - reference) / abs(reference)
    check(rel <= tol, f"{what}: {value:.9g} vs {reference:.9g} (relative {rel:.2e} <= {tol:g})")


def mesh_box(msh):
    """Bounding box of the nodes of a gmsh 2.2 ASCII mesh."""
    with open(msh) as f:
        lines = f.read().splitlines()
    start = lines.index("$Nodes") + 2
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for line in lines[start:]:
        if line.startswith("$EndNodes"):
            break
        xyz = [float(v) for v in line.split()[1:4]]
        lo = [min(a, b) for a, b in zip(lo, xyz)]
        hi = [max(a, b) for a, b in zip(hi, xyz)]
    return lo, hi


def cylinder(msh):
    lo, hi = mesh_box(msh)
    centre = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]
    radius = max(hi[0] - lo[0], hi[1] - lo[1]) / 2
    return lo, hi, centre, radius, hi[2] - lo[2]


def axis_count(lo, hi, r):
    """Spheres of a simple cubic lattice along an axis of [lo, hi] (dem/packing/packings.cc)."""
    return int(math.floor((hi - lo - 2 * r) / (2 * r) + 1e-9)) + 1


def check_cubic(summary, msh, r, e_b):
    lo, hi, centre, R, H = cylinder(msh)
    nx, ny, nz = (axis_count(lo[d], hi[d], r) for d in range(3))
    columns = 0
    margin = math.inf
    for i in range(nx):
        for j in range(ny):
            rho = math.hypot(lo[0] + r + 2 * r * i - centre[0], lo[1] + r + 2 * r * j - centre[1])
            margin = min(margin, abs(rho - (R - r)))
            columns += rho <= R - r
    print(f"core: R = {R:.6g} m, H = {H:.6g} m, {columns} columns of {nz} spheres, "
          f"closest column {margin:.3g} m from the limit R - r")
    check(margin >= r / 5, f"every column at least r/5 from the limit R - r ({margin:.3g} m)")
    check(summary["n_particles"] == columns * nz,
          f"n_particles {summary['n_particles']} = {columns} x {nz}")
    force_over_strain = summary["youngs_modulus"] * summary["cross_section_area"]
    e_box = math.pi * e_b / 4
    near(force_over_strain / (columns * (2 * r) ** 2), e_box, 1e-6, "E over the lattice cells")
    sphere = 4 / 3 * math.pi * r**3
    solid_core = summary["n_particles"] * sphere / (math.pi * R**2 * H)
    solid_box = 1 - summary["porosity"]
    print(f"solid fraction: core {solid_core:.6g}, box {solid_box:.6g} (pi/6 = {math.pi / 6:.6g})")
    near(solid_box, math.pi / 6, 1e-9, "box solid fraction = pi/6")
    e_nominal = force_over_strain / (math.pi * R**2)
    near(e_nominal / e_box, solid_core / solid_box, 1e-6,
         "E over pi R^2 / E_box = core / box solid fraction")


def check_fill(summary, msh, r, tol):
    lo, hi, centre, R, H = cylinder(msh)
    density = (1 - summary["porosity"]) / (4 / 3 * math.pi * r**3)  # spheres per m^3, the box's
    expected = density * math.pi * (R - r) ** 2 * (H - 2 * r)
    n = summary["n_particles"]
    print(f"core: R = {R:.6g} m, H = {H:.6g} m; box porosity {summary['porosity']:.6g}")
    near(n, expected, tol, "spheres in the core vs the box's density x the centres' region")
    area = summary["cross_section_area"]
    check(area <= (2 * R) ** 2 * (1 + 1e-9),
          f"particles' bounding square {area:.6g} m^2 <= (2R)^2 = {(2 * R) ** 2:.6g} m^2")


def main():
    if len(sys.argv) != 6 or sys.argv[1] not in ("cubic", "fill"):
        sys.exit(__doc__)
    with open(sys.argv[2]) as f:
        summary = json.load(f)
    values = (summary, sys.argv[3], float(sys.argv[4]), float(sys.argv[5]))
    (check_cubic if sys.argv[1] == "cubic" else check_fill)(*values)
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)


if __name__ == "__main__":
    main()
