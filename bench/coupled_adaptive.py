#!/usr/bin/python3
"""Speed of an adaptive particle region (docs/adaptive.md): `dembridge compare` on the unnotched
4 m beam (bench/coupled_adaptive_beam_4m.prm: particles at first only under the load point, the
region grows where the beam cracks) runs the adaptive coupled beam, the same coupled beam with
the region it ended with placed at the start (coupled_fixed), the full DEM of the same lattice
(20,050 spheres) and the elastic FE reference, one after the other, one thread each. Reports
each model's wall time, peak memory, peak load and particles, the speed-ups against full DEM,
the share of the body that became particles (the adaptive run's final particles over full DEM's)
and the machine and its load; copies comparison.json and comparison.png to
bench/results/coupled_adaptive_4m.{json,png}.

Usage: /usr/bin/python3 bench/coupled_adaptive.py [--build build] [--case CASE] [--tag TAG]
"""
import argparse
import csv
import json
import os
import platform
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def quasi_static_peak(output, direction, group):
    """The largest load before the first bond breaks, from a model's history.csv: the beam
    cracks unstably at its peak and rings, so that peak_load is an inertial spike after the snap.
    A coupled run has the column `load`; full DEM the group's force, read along the load
    direction (the driven group's force on the beam is minus its reaction)."""
    path = os.path.join(output, "history.csv")
    if not os.path.exists(path):
        return None
    best = None
    first_break = None
    with open(path) as f:
        for row in csv.DictReader(f):
            if float(row["n_broken_bonds"]) > 0:
                first_break = float(row["time"])
                break
            if "load" in row:
                load, deflection = float(row["load"]), float(row["load_displacement"])
            else:
                force = [float(row["%s_f%s" % (group, c)]) for c in "xyz"]
                shift = [float(row["%s_u%s" % (group, c)]) for c in "xyz"]
                load = sum(a * b for a, b in zip(force, direction))
                deflection = sum(a * b for a, b in zip(shift, direction))
            if best is None or load > best["load"]:
                best = {"load": load, "time": float(row["time"]), "deflection": deflection}
    if best is not None:
        best["first_break_time"] = first_break
        try:  # the crack log's time of the first break, between two records
            with open(os.path.join(output, "summary.json")) as f:
                best["first_break_time"] = json.load(f)["first_crack"]["time"]
        except (OSError, KeyError, TypeError, ValueError):
            pass
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--case", default=os.path.join(here, "coupled_adaptive_beam_4m.prm"))
    ap.add_argument("--tag", default="4m", help="suffix of the result files")
    a = ap.parse_args()
    exe = os.path.join(a.build, "app", "dembridge")
    if not os.access(exe, os.X_OK):
        sys.exit("coupled_adaptive.py: %s not found (build first: bash scripts/setup.sh)" % exe)
    name = "coupled_adaptive" + ("_" + a.tag if a.tag else "")
    out = os.path.join(a.build, "bench-output", name)
    load_before = os.getloadavg()
    # the elastic reference on Q1 cells of two diameters: its stiffness only draws the line
    subprocess.run([exe, "compare", a.case, "--output-dir", out, "--fe-degree", "1",
                    "--set", "Output/write vtu=false", "--set", "Simulation/threads=1"],
                   check=True)
    with open(os.path.join(out, "comparison.json")) as f:
        c = json.load(f)
    m = c["models"]
    c["benchmark"] = "coupled_adaptive"
    c["machine"] = {"cpu": cpu_model(), "cores": os.cpu_count(),
                    "load_before": load_before, "load_after": os.getloadavg(),
                    "note": "shared machine: other jobs ran beside the benchmark"}
    c["particle_share_of_body"] = m["coupled"]["n_particles_final"] / m["full_dem"]["n_particles"]
    peaks = {}
    for key in ("full_dem", "coupled", "coupled_fixed"):
        peak = quasi_static_peak(m[key]["output"], c["load_direction"], c["load_group"])
        if peak is not None:
            peaks[key] = peak
    if "full_dem" in peaks:
        for peak in peaks.values():
            peak["ratio_to_full_dem"] = peak["load"] / peaks["full_dem"]["load"]
    c["quasi_static_peak"] = peaks
    c["quasi_static_peak_note"] = ("the largest load before the first bond breaks: the beam cracks "
                                   "unstably at its peak and rings, so peak_load and limit_load "
                                   "are inertial spikes after the snap")
    os.makedirs(os.path.join(here, "results"), exist_ok=True)
    with open(os.path.join(here, "results", name + ".json"), "w") as f:
        json.dump(c, f, indent=1)
    if os.path.exists(os.path.join(out, "comparison.png")):
        shutil.copy(os.path.join(out, "comparison.png"),
                    os.path.join(here, "results", name + ".png"))
    print("| model | particles at the end | wall s | memory MB | quasi-static peak N | vs full DEM "
          "| speed-up |")
    print("|---|---|---|---|---|---|---|")
    dem = m["full_dem"]
    for key in ("coupled", "coupled_fixed", "full_dem"):
        r = m[key]
        n = r.get("n_particles_final", r.get("n_particles", "-"))
        peak = peaks.get(key, {"load": float("nan"), "ratio_to_full_dem": float("nan")})
        print("| %s | %s | %.1f | %.0f | %.2f | %+.2f %% | %.2fx |" % (
            key, n, r["wall_seconds"], r["peak_memory_bytes"] / 1e6, peak["load"],
            100 * (peak["ratio_to_full_dem"] - 1), dem["wall_seconds"] / r["wall_seconds"]))
    print("particles: %.1f %% of the body (%d growths, largest energy jump %.2g)" % (
        100 * c["particle_share_of_body"], m["coupled"]["n_region_growth_events"],
        m["coupled"]["growth_energy_jump_max"]))


if __name__ == "__main__":
    main()
