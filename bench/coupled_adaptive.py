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
    os.makedirs(os.path.join(here, "results"), exist_ok=True)
    with open(os.path.join(here, "results", name + ".json"), "w") as f:
        json.dump(c, f, indent=1)
    if os.path.exists(os.path.join(out, "comparison.png")):
        shutil.copy(os.path.join(out, "comparison.png"),
                    os.path.join(here, "results", name + ".png"))
    print("| model | particles at the end | wall s | memory MB | peak load N | peak vs full DEM | speed-up |")
    print("|---|---|---|---|---|---|---|")
    dem = m["full_dem"]
    for key in ("coupled", "coupled_fixed", "full_dem"):
        r = m[key]
        n = r.get("n_particles_final", r.get("n_particles", "-"))
        print("| %s | %s | %.1f | %.0f | %.2f | %+.2f %% | %.2fx |" % (
            key, n, r["wall_seconds"], r["peak_memory_bytes"] / 1e6, r["peak_load"],
            100 * (r["peak_load"] / dem["peak_load"] - 1),
            dem["wall_seconds"] / r["wall_seconds"]))
    print("particles: %.1f %% of the body (%d growths, largest energy jump %.2g)" % (
        100 * c["particle_share_of_body"], m["coupled"]["n_region_growth_events"],
        m["coupled"]["growth_energy_jump_max"]))


if __name__ == "__main__":
    main()
