#!/usr/bin/python3
"""Speed of coupled localized-damage runs: `dembridge compare` on the 2 m notched
sea-ice beam (bench/coupled_notched_beam.prm: particles in the middle 0.2 m, r = 5 mm,
softening bonds) runs the coupled beam, the full-DEM beam of the same packing (20,200 spheres)
and the elastic FE model one after the other in the same benchmark run, one thread each.
Reports wall time, peak memory, peak load, limit load (the peak before an unstable crack's snap:
app/studies/compare.cc) and fracture energy of each and the coupled run's
speed-up; copies comparison.json and comparison.png to bench/results/coupled_damage.{json,png}.

The same comparison on a beam twice as long (bench/coupled_notched_beam_4m.prm: 40,070 spheres
against the same 2,070) with --case bench/coupled_notched_beam_4m.prm --tag 4m: the coupled run's
advantage grows with the continuum's share of the body.

Usage: /usr/bin/python3 bench/coupled_damage.py [--build build] [--case CASE] [--tag TAG]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--case", default=os.path.join(here, "coupled_notched_beam.prm"))
    ap.add_argument("--tag", default="", help="suffix of the result files (e.g. 4m)")
    a = ap.parse_args()
    exe = os.path.join(a.build, "app", "dembridge")
    if not os.access(exe, os.X_OK):
        sys.exit("coupled_damage.py: %s not found (build first: bash scripts/setup.sh)" % exe)
    name = "coupled_damage" + ("_" + a.tag if a.tag else "")
    out = os.path.join(a.build, "bench-output", name)
    load_before = os.getloadavg()
    subprocess.run([exe, "compare", a.case, "--output-dir", out, "--set",
                    "Output/write vtu=false"], check=True)
    with open(os.path.join(out, "comparison.json")) as f:
        c = json.load(f)
    c["benchmark"] = "coupled_damage"
    c["machine_load_before"] = load_before
    c["machine_load_after"] = os.getloadavg()
    os.makedirs(os.path.join(here, "results"), exist_ok=True)
    with open(os.path.join(here, "results", name + ".json"), "w") as f:
        json.dump(c, f, indent=1)
    if os.path.exists(os.path.join(out, "comparison.png")):
        shutil.copy(os.path.join(out, "comparison.png"),
                    os.path.join(here, "results", name + ".png"))
    m, v = c["models"], c["coupled_vs_full_dem"]
    print("| model | particles | wall s | memory MB | peak load N | limit load N | fracture energy J |")
    print("|---|---|---|---|---|---|---|")
    for name in ("coupled", "full_dem", "full_fem"):
        r = m[name]
        print("| %s | %s | %.1f | %.0f | %s | %s | %s |" % (
            name, r.get("n_particles", "-"), r["wall_seconds"], r["peak_memory_bytes"] / 1e6,
            "%.2f" % r["peak_load"] if "peak_load" in r else "-",
            "%.2f" % r["limit_load"] if "limit_load" in r else "-",
            "%.4g" % r["fracture_energy"] if "fracture_energy" in r else "-"))
    print("coupled / full DEM: speed-up %.2f, peak load %.4f, limit load %.4f, fracture energy %.4f"
          % (v["speedup"], v["peak_load_ratio"], v["limit_load_ratio"], v["fracture_energy_ratio"]))


if __name__ == "__main__":
    main()
