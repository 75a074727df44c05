#!/usr/bin/python3
"""Biaxial series across the columns of columnar ice (docs/columnar_ice.md), after Smith &
Schulson (1994): runs examples/columnar_biaxial.prm at confinement ratios R = sigma_2 / sigma_1
(default 0, 0.1, ..., 0.5) with `dembridge run`, and reports for each R the peak of sigma_1 and
the orientation of the cracks up to that peak: the share of crack normals within 30 degrees of
the confined axis y and of the free column axis z (an isotropic population puts 1 - cos 30 =
0.134 near each axis). Writes OUT/biaxial.csv and OUT/biaxial.png (strength against R beside
the normals' shares, with Smith & Schulson's transition at R of about 0.2 marked). Their measured
strengths are not in the project's sources (the thesis cites only Timco & Weeks' account of the
modes), so the plot marks the transition and the strength normalised by its R = 0 value, the
form in which the trend (rising with R below the transition) is compared, and no measured point.

    /usr/bin/python3 scripts/study_biaxial.py --out study_biaxial
    /usr/bin/python3 scripts/study_biaxial.py --ratios 0,0.3 --set "Particles/seed=2"

sigma_1 is the x+ face's support reaction (history.csv: pushed_end_fx, along -x) over the face
area of the drive load; the peak is the largest recorded value (Output/history interval), the
cracks up to it those of cracks.csv whose time is not later. A run whose summary.json exists is
not run again. Requires numpy and matplotlib (Debian: /usr/bin/python3).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "examples" / "columnar_biaxial.prm"


def read_csv(path, columns):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in columns}


def drive_area(case):
    """The `area` of subsection Load drive in the case file (m^2)."""
    inside = False
    for line in Path(case).read_text().splitlines():
        words = line.split("#")[0].split()
        if words[:3] == ["subsection", "Load", "drive"]:
            inside = True
        elif inside and words[:1] == ["end"]:
            break
        elif inside and words[:2] == ["set", "area"]:
            return float(words[3])
    raise SystemExit(f"{case}: no area in subsection Load drive")


def analyse(run, area):
    history = read_csv(run / "history.csv", ["time", "pushed_end_fx"])
    sigma = -history["pushed_end_fx"] / area
    k = int(np.argmax(sigma))
    cracks = read_csv(run / "cracks.csv", ["time", "axis_x", "axis_y", "axis_z"])
    before = cracks["time"] <= history["time"][k]
    axes = np.stack([cracks["axis_x"], cracks["axis_y"], cracks["axis_z"]], axis=1)[before]
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    near = np.abs(axes) > math.cos(math.radians(30))
    n = len(axes)
    return sigma[k], n, near[:, 1].mean() if n else 0.0, near[:, 2].mean() if n else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ratios", default="0,0.1,0.2,0.3,0.4,0.5")
    ap.add_argument("--out", default="study_biaxial")
    ap.add_argument("--dembridge",
                    default=os.environ.get("DEMBRIDGE", str(ROOT / "build" / "app" / "dembridge")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="passed to every run")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    area = drive_area(CASE)
    rows = []
    for ratio in [float(r) for r in a.ratios.split(",")]:
        run = out / f"R{ratio:.2f}"
        if not (run / "summary.json").is_file():
            cmd = [a.dembridge, "run", str(CASE), "--output-dir", str(run),
                   "--set", f"Load confine/ratio={ratio:g}"]
            for s in a.set:
                cmd += ["--set", s]
            print(" ".join(cmd), flush=True)
            with open(out / f"R{ratio:.2f}.log", "w") as log:
                if subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT).returncode != 0:
                    sys.exit(f"dembridge failed: see {out}/R{ratio:.2f}.log")
        peak, n, near_y, near_z = analyse(run, area)
        rows.append((ratio, peak, n, near_y, near_z))
        print(f"R = {ratio:.2f}: peak sigma_1 {peak / 1e6:.3f} MPa, {n} cracks up to it, normals "
              f"within 30 degrees of y {near_y:.3f}, of z {near_z:.3f}", flush=True)
    with open(out / "biaxial.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["ratio", "peak_sigma_1_Pa", "cracks_to_peak", "normals_near_y",
                    "normals_near_z"])
        w.writerows(rows)
    if a.no_plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    r = np.array(rows)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.plot(r[:, 0], r[:, 1] / 1e6, "o-")
    left.set_xlabel("R = sigma_2 / sigma_1")
    left.set_ylabel("peak sigma_1 (MPa)")
    if r[0, 0] == 0:
        normalised = left.secondary_yaxis(
            "right", functions=(lambda s: s * 1e6 / r[0, 1], lambda q: q * r[0, 1] / 1e6))
        normalised.set_ylabel("peak / peak at R = 0")
    left.set_title("strength against confinement")
    right.plot(r[:, 0], r[:, 3], "s-", label="normal near y (confined): splitting along the load")
    right.plot(r[:, 0], r[:, 4], "^-", label="normal near z (columns, free): out of plane")
    right.axhline(1 - math.cos(math.radians(30)), color="grey", lw=0.8, label="isotropic")
    right.set_xlabel("R = sigma_2 / sigma_1")
    right.set_ylabel("share of the cracks up to the peak")
    right.set_title("crack normals")
    for ax in (left, right):
        ax.axvline(0.2, color="k", ls="--", lw=0.8)
        ax.text(0.205, ax.get_ylim()[0], " Smith & Schulson:\n splitting | faulting",
                fontsize=7, va="bottom")
    right.legend(fontsize=7, loc="upper center")
    fig.text(0.01, 0.01, "Smith & Schulson (1994): transition only; their measured points are "
             "not in the project's sources", fontsize=7, color="grey")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(out / "biaxial.png", dpi=120)
    print(f"wrote {out / 'biaxial.csv'} and {out / 'biaxial.png'}")


if __name__ == "__main__":
    main()
