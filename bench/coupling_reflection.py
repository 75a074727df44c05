#!/usr/bin/python3
"""Reflection curve of the coupled DEM-FE handshake band: the share of a longitudinal
pulse's energy reflected by the band, swept over the pulse's dominant wavelength (2 ... 40
particle spacings d) and the FE element size (1 ... 4 d), in both directions (continuum ->
particles, particles -> continuum).

Each point is `coupling_check wave_point LAMBDA/d H/d TYING SOLVE FLOOR`: a bar of the simple
cubic PBM lattice (r = 5 mm, 1 x 1 particle across) and its continuum (the lattice's own tensor),
band width max(3 d, 2 h), bar halves max(0.8 m, 8 lambda); it prints the energy left on the
starting side (R) and on the other (T) once the pulse has crossed, and the energy balance.
A continuum of element size h cannot carry a wave shorter than 2 h: those points start in the
particles only (the continuum -> particles entry is left empty).

Writes bench/results/coupling_reflection.csv, .json and .png.
Usage: /usr/bin/python3 bench/coupling_reflection.py [--build build] [--tying particle]
       [--solve exact] [--floor 0.1] [--quick]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def run_point(exe, lam, h, tying, solve, floor):
    out = subprocess.run([exe, "wave_point", str(lam), str(h), tying, solve, str(floor)],
                         capture_output=True, text=True, check=True).stdout
    result = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 7 and parts[0] in ("in", "out"):
            result[parts[0]] = {"reflected": float(parts[2]), "transmitted": float(parts[4]),
                                "balance": float(parts[6])}
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--tying", default="particle", choices=["particle", "node"])
    ap.add_argument("--solve", default="exact", choices=["exact", "lumped"])
    ap.add_argument("--floor", type=float, default=0.1)
    ap.add_argument("--quick", action="store_true", help="three wavelengths, two element sizes")
    a = ap.parse_args()
    exe = os.path.join(a.build, "tests", "coupling", "coupling_check")
    if not os.access(exe, os.X_OK):
        sys.exit("coupling_reflection.py: %s not found (build first: bash scripts/setup.sh)" % exe)
    wavelengths = [4, 10, 20] if a.quick else [2, 3, 4, 5, 6, 8, 10, 15, 20, 30, 40]
    sizes = [1, 2] if a.quick else [1, 2, 3, 4]
    rows = []
    start = time.time()
    for h in sizes:
        for lam in wavelengths:
            r = run_point(exe, lam, h, a.tying, a.solve, a.floor)
            fe_carries = lam >= 2 * h
            row = {"wavelength_over_d": lam, "element_size_over_d": h,
                   "reflected_from_continuum": r["in"]["reflected"] if fe_carries else None,
                   "transmitted_from_continuum": r["in"]["transmitted"] if fe_carries else None,
                   "reflected_from_particles": r["out"]["reflected"],
                   "transmitted_from_particles": r["out"]["transmitted"],
                   "balance_error": max(r["out"]["balance"], r["in"]["balance"] if fe_carries else 0)}
            rows.append(row)
            print("h = %d d, lambda = %2d d: R(continuum->particles) %s, R(particles->continuum) "
                  "%.3e, balance %.1e" % (h, lam, "%.3e" % row["reflected_from_continuum"]
                                          if fe_carries else "   -     ",
                                          row["reflected_from_particles"], row["balance_error"]),
                  flush=True)
    results = os.path.join(here, "results")
    os.makedirs(results, exist_ok=True)
    base = os.path.join(results, "coupling_reflection")
    with open(base + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for row in rows:
            w.writerow({k: ("" if v is None else v) for k, v in row.items()})
    with open(base + ".json", "w") as f:
        json.dump({"benchmark": "coupling_reflection", "tying": a.tying, "constraint_solve": a.solve,
                   "weight_floor": a.floor, "particle_radius": 0.005, "band_width": "max(3 d, 2 h)",
                   "wall_seconds": time.time() - start, "points": rows}, f, indent=1)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no plot (apt-get install python3-matplotlib)")
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, key, title in ((axes[0], "reflected_from_continuum", "continuum -> particles"),
                           (axes[1], "reflected_from_particles", "particles -> continuum")):
        for h in sizes:
            pts = [(r["wavelength_over_d"], r[key]) for r in rows
                   if r["element_size_over_d"] == h and r[key] is not None]
            ax.loglog([p[0] for p in pts], [max(p[1], 1e-12) for p in pts], "o-",
                      label="h = %d d" % h)
        ax.axhline(0.01, color="grey", ls="--", lw=0.8)
        ax.set_title(title)
        ax.set_xlabel("dominant wavelength / particle spacing d")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("reflected energy / incident energy")
    axes[1].legend()
    fig.suptitle("Handshake band reflection (bridging domain, %s tying, weight floor %g)"
                 % (a.tying, a.floor))
    fig.tight_layout()
    fig.savefig(base + ".png", dpi=130)
    print("wrote", base + ".csv", base + ".json", base + ".png")


if __name__ == "__main__":
    main()
