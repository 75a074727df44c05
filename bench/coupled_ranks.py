#!/usr/bin/python3
"""Coupled runs on 1 and more MPI ranks: wall, solver and coupling seconds per rank count, for
one or more dembridge binaries in the same invocation (say the commit before a change and
after it), so that both see the same machine load.

Cases: the coupled bending beam (examples/coupled_bending.prm, 1,242 FE DoFs, 600 interface
particles) to 0.05 s and the notched beam (examples/coupled_notched_bending.prm) to 0.0215 s,
past its first break; VTU output off. The particle region steps on rank 0 and the continuum is
split over the ranks (docs/parallel.md), so the particles bound the wall time from below: the
figure to read is how much more ranks cost or save, not a speed-up of the particles.

Runs are interleaved (for each case and rank count, each binary in turn) and each records the
load average at its start beside the whole invocation's. `mpirun --bind-to none`: Open MPI
otherwise binds each rank, and a rank's threads share one core.

    /usr/bin/python3 bench/coupled_ranks.py [--binary NAME=PATH]... [--ranks 1,2]
        [--cases bending,notched] [--repeat 1] [--note TEXT] [--output FILE] [--work DIR]

Writes bench/results/coupled_bending_ranks.json unless --output names another file; prints a
table. The default binary is build/app/dembridge, named "current".
"""
import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASES = {
    "bending": ("examples/coupled_bending.prm", 0.05),
    "notched": ("examples/coupled_notched_bending.prm", 0.0215),
}


def machine():
    cpu = ""
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    return dict(host=platform.node(), cpu=cpu, cores=os.cpu_count(),
                load_average=os.getloadavg())


def run_once(exe, ranks, case, end_time, out):
    shutil.rmtree(out, ignore_errors=True)
    cmd = [exe, "run", os.path.join(ROOT, case), "--output-dir", out,
           "--set", "Output/write vtu=false", "--set", "Simulation/end time=%g" % end_time]
    if ranks > 1:
        cmd = ["mpirun", "--bind-to", "none", "-np", str(ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    load = os.getloadavg()
    start = time.time()
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env)
    wall = time.time() - start
    if done.returncode:
        sys.exit("coupled_ranks.py: %s failed:\n%s" % (" ".join(cmd), done.stdout[-2000:]))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return dict(ranks=ranks, wall_seconds=wall, solver_seconds=s["solver_seconds"],
                coupling_seconds=s["coupling_seconds"], steps=s["steps"],
                load_average_at_start=load, midspan_deflection=s.get("midspan_deflection"),
                n_fe_dofs=s.get("n_fe_dofs"), n_interface_particles=s.get("n_interface_particles"),
                git_commit=s.get("git_commit"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", action="append", default=[],
                    help="NAME=PATH of a dembridge binary (repeatable)")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--cases", default="bending")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--note", default="", help="a line kept in the JSON (what the binaries are)")
    ap.add_argument("--output", default=os.path.join(HERE, "results",
                                                     "coupled_bending_ranks.json"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench-output",
                                                   "coupled_ranks"))
    a = ap.parse_args()
    binaries = [b.split("=", 1) for b in a.binary] or [
        ["current", os.path.join(ROOT, "build", "app", "dembridge")]]
    for name, exe in binaries:
        if not os.access(exe, os.X_OK):
            sys.exit("coupled_ranks.py: --binary %s: %s is not an executable" % (name, exe))
    ranks = [int(n) for n in a.ranks.split(",")]
    cases = a.cases.split(",")
    for c in cases:
        if c not in CASES:
            sys.exit("coupled_ranks.py: --cases: unknown case '%s' (%s)" % (c, ", ".join(CASES)))
    results = dict(benchmark="coupled_ranks", note=a.note, machine=machine(),
                   binaries={name: exe for name, exe in binaries}, runs=[])
    for case in cases:
        prm, end_time = CASES[case]
        for n in ranks:
            for rep in range(a.repeat):
                for name, exe in binaries:
                    out = os.path.join(a.work, "%s_%s_np%d" % (case, name, n))
                    r = run_once(exe, n, prm, end_time, out)
                    r.update(case=case, binary=name, end_time=end_time, repeat=rep)
                    results["runs"].append(r)
                    print("%-8s %-8s np%d  wall %6.2f s  solver %6.2f s  coupling %6.2f s  "
                          "load %.2f" % (case, name, n, r["wall_seconds"], r["solver_seconds"],
                                         r["coupling_seconds"], r["load_average_at_start"][0]),
                          flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.output)), exist_ok=True)
    with open(a.output, "w") as f:
        json.dump(results, f, indent=1)
    print("\n| case | binary | ranks | steps | wall s | solver s | coupling s | load (1 min) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in results["runs"]:
        print("| %s | %s | %d | %d | %.2f | %.2f | %.2f | %.2f |"
              % (r["case"], r["binary"], r["ranks"], r["steps"], r["wall_seconds"],
                 r["solver_seconds"], r["coupling_seconds"], r["load_average_at_start"][0]))
    print("written: %s" % a.output)


if __name__ == "__main__":
    main()
