#!/usr/bin/env python3
"""Compares an adaptive coupled run with the full-DEM run of the same beam (docs/adaptive.md).

usage: adaptive_compare.py COUPLED_DIR DEM_DIR GROUP [--peak TOL] [--crack DIST] [--balance TOL]
                           [--jump TOL]

COUPLED_DIR: summary.json (peak_load, energy_balance_error_max, the growth figures) and cracks.csv
of the adaptive coupled run; DEM_DIR: history.csv (the load group GROUP's force along -z) and
cracks.csv of the full-DEM run. Checks: the peak loads within TOL (relative; default 0.02), the
first broken bonds within DIST (m; default 0.02, two diameters of r = 5 mm), the coupled energy
balance within TOL at every record (default 0.01), at least one growth, every growth's energy jump
within TOL of the strain energy (default 0.01), and the band elastic (damage never reached it).
Prints each figure; exits 1 if a check fails. Standard library only.
"""
import csv
import json
import math
import sys


def first_crack(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    return [float(rows[0][k]) for k in ("x", "y", "z")], float(rows[0]["time"])


def main(argv):
    if len(argv) < 4:
        print(__doc__)
        return 2
    coupled, dem, group = argv[1], argv[2], argv[3]
    tol = {"--peak": 0.02, "--crack": 0.02, "--balance": 0.01, "--jump": 0.01}
    for k in range(4, len(argv) - 1, 2):
        tol[argv[k]] = float(argv[k + 1])
    with open(coupled + "/summary.json") as f:
        s = json.load(f)
    with open(dem + "/history.csv", newline="") as f:
        dem_load = [-float(r[group + "_fz"]) for r in csv.DictReader(f)]
    ok = True

    def report(passed, text):
        nonlocal ok
        print(("ok   " if passed else "FAIL ") + text)
        ok = ok and passed

    peak_c, peak_d = s["peak_load"], max(dem_load)
    report(abs(peak_c - peak_d) <= tol["--peak"] * peak_d,
           f"peak load {peak_c:.2f} N against full DEM {peak_d:.2f} N "
           f"({(peak_c / peak_d - 1) * 100:+.2f} %, within {tol['--peak'] * 100:g} %)")
    a, b = first_crack(coupled + "/cracks.csv"), first_crack(dem + "/cracks.csv")
    if a is None or b is None:
        report(False, "first crack: none in " + ("the coupled run" if a is None else "full DEM"))
    else:
        distance = math.dist(a[0], b[0])
        report(distance <= tol["--crack"],
               f"first crack at {a[0]} m (t = {a[1]:.5g} s) against full DEM's {b[0]} m "
               f"(t = {b[1]:.5g} s): {distance * 1e3:.2f} mm apart (within "
               f"{tol['--crack'] * 1e3:g} mm)")
    report(s["energy_balance_error_max"] <= tol["--balance"],
           f"energy balance error max {s['energy_balance_error_max']:.3e} (within "
           f"{tol['--balance']:g}, through every growth)")
    n = s["n_region_growth_events"]
    report(n >= 1, f"{n} growth events, {s['n_particles_final']} particles at the end")
    report(s["growth_energy_jump_max"] <= tol["--jump"],
           f"largest growth energy jump {s['growth_energy_jump_max']:.3e} of the strain energy "
           f"(within {tol['--jump']:g})")
    report(not s["damage_reached_band"],
           f"damage stayed out of the band (band failure index max "
           f"{s['band_failure_index_max']:.3f})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
