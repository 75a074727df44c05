"""dembridge against YADE on the bonded HCP lattice, in alternating runs (the goal: "10x YADE").

Both codes' rates move with the shared host's speed from minute to minute (YADE measured 3.4 M
to 5.1 M bond-updates/s on one thread on different hours of the same day), so a ratio between a
dembridge run and a YADE run taken minutes apart is as noisy as the host. Here the two alternate
round by round, each round a YADE run (bench/peers/yade_hcp_bench.py, bonds_only, 200 timed
steps) right before a dembridge-bench run (the same 26,004-sphere lattice, dashpots on, best of
5 x 100 steps, with the plain reference loop alternating inside it), and the ratio is taken
within each pair; the JSON keeps every pair and the median.

usage: /usr/bin/python3 bench/yade_alternating.py [--build build] [--rounds 5] [--threads 1 2]
       [--json bench/results/yade_alternating_r2.5mm.json]
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--build", default=os.path.join(here, "build"))
ap.add_argument("--rounds", type=int, default=5)
ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
ap.add_argument("--json", default=os.path.join(here, "bench", "results",
                                               "yade_alternating_r2.5mm.json"))
args = ap.parse_args()

bench = os.path.join(args.build, "bench", "dembridge-bench")
if not os.access(bench, os.X_OK):
    sys.exit(f"yade_alternating.py: {bench}: not built (bash scripts/setup.sh)")
if shutil.which("yade") is None:
    sys.exit("yade_alternating.py: yade is not installed "
             "(apt-get install --no-install-recommends yade)")


def yade_run(threads):
    out = subprocess.run(["yade", f"-j{threads}", "-n", "-x",
                          os.path.join(here, "bench", "peers", "yade_hcp_bench.py"), "--mode",
                          "bonds_only", "--steps", "200", "--timing-steps", "0"],
                         capture_output=True, text=True, check=True).stdout
    lines = [line for line in out.splitlines() if line.startswith("{")]
    if not lines:
        sys.exit("yade_alternating.py: no JSON line in YADE's output")
    r = json.loads(lines[-1])
    return r["bond_updates_per_second"], r["n_bonds"]


def dembridge_run(threads):
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "dembridge.json")
        subprocess.run([bench, "--packing", "hcp", "--threads", str(threads), "--steps", "100",
                        "--rounds", "5", "--json", path], capture_output=True, check=True)
        with open(path) as f:
            r = json.load(f)
    run = r["runs"][0]
    return (run["full"]["bond_updates_per_second"], run["plain"]["bond_updates_per_second"],
            r["n_bonds"])


result = {"benchmark": "dembridge-bench against YADE 2023.02a, alternating runs",
          "specimen": "HCP lattice r = 2.5 mm in 0.25 x 0.1 x 0.1 m, dashpots on (dembridge)",
          "rounds": args.rounds, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
          "loadavg_1min_at_start": os.getloadavg()[0], "threads": {}}
for threads in args.threads:
    pairs = []
    for k in range(args.rounds):
        yade, yade_bonds = yade_run(threads)
        full, plain, bonds = dembridge_run(threads)
        if yade_bonds != bonds:
            sys.exit(f"yade_alternating.py: YADE has {yade_bonds} bonds, dembridge {bonds}")
        pairs.append({"yade": yade, "dembridge_best": full, "plain_loop_best": plain,
                      "ratio": full / yade})
        print(f"threads {threads} round {k + 1}: YADE {yade / 1e6:.2f} M, dembridge "
              f"{full / 1e6:.1f} M (plain loop {plain / 1e6:.1f} M): {full / yade:.1f}x",
              file=sys.stderr)
    ratios = [p["ratio"] for p in pairs]
    result["threads"][str(threads)] = {
        "pairs": pairs, "ratio_median": statistics.median(ratios), "ratio_min": min(ratios),
        "ratio_max": max(ratios),
        "yade_median": statistics.median(p["yade"] for p in pairs),
        "dembridge_median": statistics.median(p["dembridge_best"] for p in pairs)}
os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
with open(args.json, "w") as f:
    json.dump(result, f, indent=1)
for threads, r in result["threads"].items():
    print(f"{threads} thread(s): dembridge / YADE median {r['ratio_median']:.1f}x "
          f"(range {r['ratio_min']:.1f}-{r['ratio_max']:.1f}x over {args.rounds} pairs; "
          f"YADE median {r['yade_median'] / 1e6:.2f} M, dembridge {r['dembridge_median'] / 1e6:.1f} M)")
