#!/usr/bin/env python3
"""Damage benchmark (not a test): a compression to failure of about 25,000 particles,
and the contact throughput against YADE on the same packing in the same run.

    python3 bench/damage_bench.py [--build build] [--threads 1] [--repeats 3] [--skip-failure]

1. packing: examples/compression_failure.prm at r = 2.5 mm (the 0.25 x 0.1 x 0.1 m specimen,
   random close packing, seed 1: 23,746 spheres), saved once as a particle file;
2. failure: compression_failure.prm on that packing (86,158 parallel bonds, brittle, linear
   contacts for the fragments, two platens) with the upper platen at --velocity (default
   0.05 m/s, strain rate 0.2 1/s) to a strain of --end-strain (default 1.5e-3, past the
   collapse): bond-updates and contact-updates per second of the whole step, and the share of
   the step spent in the neighbour search (Verlet list checks and rebuilds, which must stay below
   15 %) and in the contact loop, from the run's summary.json;
3. contacts: bench/contacts_box.prm (the same packing without bonds in a box of six walls, the
   x+ wall moving in) for --contact-steps steps, and YADE on the same packing, box and time step
   (bench/peers/yade_contact_bench.py), alternated --repeats times so that both see the same load
   on a shared machine: contact-updates per second (wall and CPU time) and the neighbour search's
   share of the step.
Writes bench/results/damage_compression_r2.5mm_threads{T}.json and
bench/results/damage_contacts_r2.5mm_threads{T}.json (every run, the load average at its start,
and the best and median of the repeats). Plain python3; YADE is run as `yade -jT -n -x`.
"""
import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

here = Path(__file__).resolve().parent
root = here.parent


def run_timed(cmd, log):
    """Runs cmd; returns (wall seconds, CPU seconds of the child, load average at the start)."""
    load = os.getloadavg()[0]
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with open(log, "w") as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT)
    wall = time.perf_counter() - t0
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if rc != 0:
        sys.exit(f"failed ({rc}): {' '.join(map(str, cmd))}; see {log}")
    cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    return wall, cpu, load


def dembridge(exe, case, out, sets, log):
    cmd = [exe, "run", str(case), "--output-dir", str(out)]
    for s in sets:
        cmd += ["--set", s]
    wall, cpu, load = run_timed(cmd, log)
    return json.load(open(out / "summary.json")), wall, cpu, load


def step_figures(j, cpu):
    """Throughput of the whole step (solver_seconds: the time-stepping loop, records included)."""
    t = j["solver_seconds"]
    f = {
        "n_particles": j["n_particles"],
        "n_bonds": j["n_bonds"],
        "steps": j["steps"],
        "time_step": j["time_step"],
        "solver_seconds": t,
        "process_cpu_seconds": cpu,  # the whole process: reading, setup and output included
        "ms_per_step": 1e3 * t / j["steps"],
        "bond_updates_per_second": j["n_bonds"] * j["steps"] / t,
        "contact_updates": j["contact_updates"],
        "contact_updates_per_second": j["contact_updates"] / t,
        "contact_updates_per_second_contact_loop": j["contact_updates_per_second"],
        "neighbour_list_builds": j["neighbour_list_builds"],
        "neighbour_search_seconds": j["neighbour_search_seconds"],
        "neighbour_search_share": j["neighbour_search_seconds"] / t,
        "contact_loop_share": j["contact_seconds"] / t,
        "n_contacts_final": j["n_contacts"],
        "energy_balance_error": j["energy_balance_error"],
    }
    return f


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=str(root / "build"))
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--radius", type=float, default=2.5e-3)
    ap.add_argument("--velocity", type=float, default=0.05, help="platen speed (m/s)")
    ap.add_argument("--end-strain", type=float, default=1.5e-3)
    ap.add_argument("--contact-steps", type=int, default=300)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--skip-failure", action="store_true")
    ap.add_argument("--work", default="/tmp/dembridge-damage-bench")
    ap.add_argument("--results", default=str(here / "results"))
    args = ap.parse_args()

    exe = Path(args.build) / "app" / "dembridge"
    if not exe.exists():
        sys.exit(f"{exe}: build first (bash scripts/setup.sh)")
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    results = Path(args.results)
    results.mkdir(parents=True, exist_ok=True)
    tag = f"r{args.radius * 1e3:g}mm_threads{args.threads}"
    case = root / "examples" / "compression_failure.prm"
    packing = work / f"packing_r{args.radius * 1e3:g}mm.csv"
    machine = {"nproc": os.cpu_count(), "uname": " ".join(os.uname())}
    if not packing.exists():  # the random packing once (one step of the example)
        print(f"packing r = {args.radius} m ...", flush=True)
        dembridge(exe, case, work / "pack",
                  # the recorded figures rest on the measured estimate's packing
                  [f"Particles/radius={args.radius}", f"Particles/save file={packing}",
                   "Particles/jamming estimate=measured",
                   "Simulation/max steps=1", "Output/write vtu=false"], work / "pack.log")
    from_file = ["Particles/source=file", f"Particles/file={packing}", "Output/write vtu=false",
                 f"Simulation/threads={args.threads}"]

    if not args.skip_failure:
        length = 0.25
        end_time = 1e-3 + args.end_strain * length / args.velocity
        print(f"compression to failure, {end_time:.4g} s simulated ...", flush=True)
        j, wall, cpu, load = dembridge(
            exe, case, work / "failure",
            from_file + [f"Wall upper/velocity=-{args.velocity}, 0, 0",
                         f"Simulation/end time={end_time}", "Output/history interval=500",
                         "Contacts/reference tensile strength=0"], work / "failure.log")
        f = step_figures(j, cpu)
        f.update({
            "case": "examples/compression_failure.prm on the r = 2.5 mm packing",
            "platen_velocity": args.velocity,
            "strain_rate": args.velocity / length,
            "peak_stress": j["peak_stress"],
            "strain_at_peak": j["strain_at_peak"],
            "final_stress": j["final_stress"],
            "final_strain": j["final_strain"],
            "n_broken_bonds": j["n_broken_bonds"],
            "broken_bonds_tension": j["broken_bonds_tension"],
            "broken_bonds_shear": j["broken_bonds_shear"],
            "threads": args.threads,
            "process_wall_seconds": wall,
            "loadavg_1min_at_start": load,
            "loadavg_1min_at_end": os.getloadavg()[0],
            "version": j.get("provenance", {}).get("version") if isinstance(
                j.get("provenance"), dict) else None,
        } | machine)
        out = results / f"damage_compression_{tag}.json"
        out.write_text(json.dumps(f, indent=2) + "\n")
        print(json.dumps(f, indent=2), flush=True)

    # Contacts: dembridge and YADE alternated on the same packing, box and time step.
    yade = shutil.which("yade")
    runs = []
    box = here / "contacts_box.prm"
    box_sets = from_file + [f"Wall upper/velocity=-{args.velocity}, 0, 0",
                            "Output/history interval=100"]
    # the time step first (one step), then runs that end at --contact-steps steps by their end
    # time (a run stops after the step that starts within half a step of it); a run stopped by
    # 'max steps' would not record its last step (run_explicit.cc)
    j, _, _, _ = dembridge(exe, box, work / "contacts", box_sets + ["Simulation/max steps=1"],
                           work / "contacts.log")
    box_sets.append(f"Simulation/end time={(args.contact_steps - 1) * j['time_step']!r}")
    for k in range(args.repeats):
        j, wall, cpu, load = dembridge(exe, box, work / "contacts", box_sets, work / "contacts.log")
        f = step_figures(j, cpu)
        f.update({"tool": "dembridge", "repeat": k, "loadavg_1min_at_start": load,
                  "mean_contacts": f["contact_updates"] / f["steps"]})
        runs.append(f)
        print(json.dumps(f), flush=True)
        dt = j["time_step"]
        if not yade:
            print("yade not found (apt-get install yade): dembridge only", flush=True)
            continue
        yjson = work / "yade.json"
        wall, cpu, load = run_timed(
            [yade, f"-j{args.threads}", "-n", "-x", str(here / "peers" / "yade_contact_bench.py"),
             "--packing", str(packing), "--dt", repr(dt), "--density", "1500",
             "--steps", str(args.contact_steps), "--velocity", str(args.velocity),
             "--json-out", str(yjson)], work / "yade.log")
        y = json.load(open(yjson))
        y.update({"repeat": k, "process_wall_seconds": wall, "process_cpu_seconds": cpu})
        runs.append(y)
        print(json.dumps(y), flush=True)

    summary = {}
    for tool in ("dembridge", "yade"):
        mine = [r for r in runs if r["tool"] == tool]
        if not mine:
            continue
        best = max(mine, key=lambda r: r["contact_updates_per_second"])
        summary[tool] = {
            "repeats": len(mine),
            "best_contact_updates_per_second": best["contact_updates_per_second"],
            "median_contact_updates_per_second": statistics.median(
                r["contact_updates_per_second"] for r in mine),
            "mean_contacts": best["mean_contacts"],
            "neighbour_search_share_of_best": best["neighbour_search_share"],
            "ms_per_step_of_best": best["ms_per_step"],
            "loadavg_1min_at_start_of_best": best["loadavg_1min_at_start"],
        }
    data = {"case": "bench/contacts_box.prm vs bench/peers/yade_contact_bench.py, r = 2.5 mm "
                    "packing of the compression benchmark",
            "threads": args.threads, "steps": args.contact_steps,
            "summary": summary, "runs": runs} | machine
    out = results / f"damage_contacts_{tag}.json"
    out.write_text(json.dumps(data, indent=2) + "\n")
    print(json.dumps(summary, indent=2))


if __name__ == "__main__":
    main()
