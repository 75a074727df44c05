#!/usr/bin/python3
"""Speed of the coupled mode: the coupled three-point bending beam
(examples/coupled_bending.prm: 2.5 m, particles in the middle 0.25 m, r = 5 mm) against the
explicit full-DEM run of the same beam and lattice (tests/coupling/long_beam_dem.prm with the
explicit solver), in the same benchmark run, both quasi-static to rest; the full DEM's static
solution is the reference deflection. Reports wall time, peak memory, midspan deflection and
its error, and the coupling's own share of the coupled run's time (continuum, transfers,
multipliers).

Full-DEM explicit settings: the load ramp of the coupled run (0.05 s), local (particle)
damping 0.7 (PFC's default) and the stop at an unbalanced-force ratio of 1e-5.

Three coupled runs: the example as it is (Q1 cells with incompatible modes, growing from one
spacing at the band to 0.1 m, two cells across the depth and the width) and, for the record,
the same with four cells across (3,450 DoFs) and
uniform plain Q1 cells one spacing long, four across (17,550 DoFs, neither graded nor with
incompatible modes). The coupling's cost is reported against
the particle region's own (the goal: below a quarter).

Writes bench/results/coupled_speed_r5mm.json. Usage: /usr/bin/python3 bench/coupled_speed.py
[--build build] [--radius 0.005] [--skip-full-dem]
"""
import argparse
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def run(exe, case, out, sets):
    args = [exe, "run", case, "--output-dir", out]
    for s in sets:
        args += ["--set", s]
    t0 = time.time()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - t0
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return wall, summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(root, "build"))
    ap.add_argument("--radius", type=float, default=0.005)
    ap.add_argument("--skip-full-dem", action="store_true")
    a = ap.parse_args()
    exe = os.path.join(a.build, "app", "dembridge")
    if not os.access(exe, os.X_OK):
        sys.exit("coupled_speed.py: %s not found (build first: bash scripts/setup.sh)" % exe)
    r = a.radius
    d = 2 * r
    work = os.path.join(a.build, "bench-output", "coupled_speed")
    common = ["Particles/radius=%g" % r, "Output/write vtu=false"]
    coupled_sets = common + ["Coupling/band width=%g" % (3 * d),
                             "Coupling/band element size=%g" % d]
    dem_sets = common + ["Particles/origin=%g, 0, 0" % (-r),
                         "Particles/box size=%g, 0.1, 0.1" % (2.5 + d)]
    results = {"benchmark": "coupled_speed", "radius": r,
               "machine_load": os.getloadavg(), "runs": {}}
    case = os.path.join(root, "examples", "coupled_bending.prm")
    full = os.path.join(root, "tests", "coupling", "long_beam_dem.prm")
    wall, s = run(exe, full, os.path.join(work, "full_dem_static"), dem_sets)
    reference = s["midspan_deflection"]
    results["runs"]["full_dem_static"] = {"wall_seconds": wall, "midspan_deflection": reference,
                                          "n_particles": s["n_particles"],
                                          "peak_memory_bytes": s.get("peak_memory_bytes")}
    print("full DEM static: %.1f s, deflection %.6e m" % (wall, reference), flush=True)
    four_across = ["Coupling/element size=%g, 0.025, 0.025" % d]
    variants = [("coupled", ["Coupling/element size=%g, 0.05, 0.05" % d]),
                ("coupled_four_cells_across",
                 four_across + ["Coupling/far element size=0.1, 0.025, 0.025"]),
                ("coupled_uniform_q1", four_across + ["FEM/incompatible modes=false",
                                                      "Coupling/far element size=0, 0, 0"])]
    for name, extra in variants:
        wall, s = run(exe, case, os.path.join(work, name), coupled_sets + extra)
        particles = s["solver_seconds"] - s["coupling_seconds"]
        results["runs"][name] = {
            "wall_seconds": wall, "solver_seconds": s["solver_seconds"],
            "coupling_seconds": s["coupling_seconds"], "coupling_share": s["coupling_share"],
            "coupling_over_particles": s["coupling_seconds"] / particles,
            "steps": s["steps"], "time_step": s["time_step"], "n_particles": s["n_particles"],
            "n_fe_dofs": s["n_fe_dofs"], "midspan_deflection": s["midspan_deflection"],
            "deflection_error": s["midspan_deflection"] / reference - 1,
            "fe_midspan_deflection": s.get("fe_midspan_deflection"),
            "peak_memory_bytes": s.get("peak_memory_bytes")}
        print("%s: %.1f s (%d steps, %d FE DoFs, coupling %.2f of the particles' time), "
              "deflection error %.3f %%" % (name, wall, s["steps"], s["n_fe_dofs"],
                                            results["runs"][name]["coupling_over_particles"],
                                            100 * results["runs"][name]["deflection_error"]),
              flush=True)
    if not a.skip_full_dem:
        explicit = dem_sets + ["Simulation/solver=explicit", "Damping/particle damping=0.7",
                               "Simulation/equilibrium ratio=1e-5", "Simulation/end time=2",
                               "Load midspan_load/ramp time=0.05", "Output/history interval=2000"]
        wall, s = run(exe, full, os.path.join(work, "full_dem_explicit"), explicit)
        results["runs"]["full_dem_explicit"] = {
            "wall_seconds": wall, "solver_seconds": s.get("solver_seconds"), "steps": s["steps"],
            "time_step": s["time_step"], "n_particles": s["n_particles"],
            "midspan_deflection": s["midspan_deflection"],
            "deflection_error": s["midspan_deflection"] / reference - 1,
            "peak_memory_bytes": s.get("peak_memory_bytes")}
        c, f = results["runs"]["coupled"], results["runs"]["full_dem_explicit"]
        results["speedup_wall"] = f["wall_seconds"] / c["wall_seconds"]
        results["speedup_wall_uniform_q1"] = (f["wall_seconds"] /
                                              results["runs"]["coupled_uniform_q1"]["wall_seconds"])
        results["memory_ratio"] = (f["peak_memory_bytes"] / c["peak_memory_bytes"]
                                   if f["peak_memory_bytes"] and c["peak_memory_bytes"] else None)
        print("full DEM explicit: %.1f s (%d steps), deflection error %.3f %%; coupled is %.2fx "
              "faster" % (wall, s["steps"], 100 * f["deflection_error"], results["speedup_wall"]))
    os.makedirs(os.path.join(here, "results"), exist_ok=True)
    out = os.path.join(here, "results", "coupled_speed_r%gmm.json" % (1000 * r))
    with open(out, "w") as f:
        json.dump(results, f, indent=1)
    print("wrote", out)


if __name__ == "__main__":
    main()
