#!/usr/bin/env python3
"""Checks of a cylindrical core cut from a packing (Particles/specimen volume, docs/specimens.md).

    check_core.py cubic SUMMARY.json CORE.msh RADIUS E_B
        The simple cubic core. The lattice fills the core's bounding box (read from the mesh's
        nodes) exactly as the lattice generator does; the columns whose spheres lie wholly inside
        the cylinder (axis distance <= R - r) are counted here, independently of the code, with
        every column kept at least r / 5 inside that limit (so the facets of the meshed circle,
        which stand 0.03 r inside it, cannot drop one). Checks:
          n_particles = columns x layers, exactly;
          E over the lattice cells (columns x (2r)^2) = pi E_b / 4 within 1e-6 (the columns
            carry the load independently; the box specimen's closed form, tests/app checks the
            box to the same 1e-6);
          E over the nominal area pi R^2 against the box's pi E_b / 4: in the ratio of the
            core's solid fraction to the box's, within 1e-6.
    check_core.py fill SUMMARY.json CORE.msh RADIUS TOL [SOLID_FRACTION]
        Any packing (HCP, random): the core holds as many spheres as the packing's number
        density (SOLID_FRACTION / sphere volume; by default the box packing's, 1 - summary.json's
        porosity) puts in the region where a whole sphere's centre may lie (radius R - r,
        height H - 2r), within relative TOL; and every
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
    margin = math.inf  # of the columns kept, inside the limit R - r
    for i in range(nx):
        for j in range(ny):
            rho = math.hypot(lo[0] + r + 2 * r * i - centre[0], lo[1] + r + 2 * r * j - centre[1])
            if rho <= R - r:
                columns += 1
                margin = min(margin, R - r - rho)
    print(f"core: R = {R:.6g} m, H = {H:.6g} m, {columns} columns of {nz} spheres, the outermost "
          f"kept {margin:.3g} m inside the limit R - r")
    # the facets stand inside the circle (their vertices lie on it): they can only drop a column
    # that is kept here, and only one closer to the limit than they stand in (0.03 r)
    check(margin >= r / 5, f"every kept column at least r/5 inside the limit R - r")
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
    # summary.json's E is over the mesh's section (its volume over its height): the faceted
    # circle, a little below pi R^2, not the particles' bounding square (0.64 pi R^2 here)
    near(summary["cross_section_area"], math.pi * R**2, 1e-2,
         "cross_section_area = the core's section")


def check_fill(summary, msh, r, tol, solid=None):
    lo, hi, centre, R, H = cylinder(msh)
    solid = 1 - summary["porosity"] if solid is None else solid
    print(f"solid fraction of the packing: {solid:.6g}")
    density = solid / (4 / 3 * math.pi * r**3)  # spheres per m^3
    expected = density * math.pi * (R - r) ** 2 * (H - 2 * r)
    n = summary["n_particles"]
    print(f"core: R = {R:.6g} m, H = {H:.6g} m; box porosity {summary['porosity']:.6g}")
    near(n, expected, tol, "spheres in the core vs the packing's density x the centres' region")
    area = summary["cross_section_area"]
    check(area <= (2 * R) ** 2 * (1 + 1e-9),
          f"particles' bounding square {area:.6g} m^2 <= (2R)^2 = {(2 * R) ** 2:.6g} m^2")


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if not (mode == "cubic" and len(sys.argv) == 6 or mode == "fill" and len(sys.argv) in (6, 7)):
        sys.exit(__doc__)
    with open(sys.argv[2]) as f:
        summary = json.load(f)
    values = (summary, sys.argv[3], *(float(v) for v in sys.argv[4:]))
    (check_cubic if mode == "cubic" else check_fill)(*values)
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)


if __name__ == "__main__":
    main()
