"""Markdown tables of the DEM core benchmark (bench/run_benchmarks.sh) from its JSON files.

usage: python3 bench/dem_results_table.py bench/results
"""
import json
import os
import sys

folder = sys.argv[1] if len(sys.argv) > 1 else "bench/results"


def load(name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        text = f.read().strip()
    return json.loads(text.splitlines()[-1] if text.startswith("{") and "\n" in text and
                      not text.startswith("{\n") else text)


def records(b):
    """Bytes per particle of the per-bond force records, which only static and coupled runs keep
    (results written before explicit runs dropped them carry them in their total)."""
    if "bond_force_records_if_kept" in b:
        return b["total"] + b["bond_force_records_if_kept"]
    return b["total"]


def total_explicit(b):
    return b.get("total_without_force_records", b["total"])


def bonds_explicit(b):
    return b["bonds"] - b.get("bond_force_records", 0)


def m(x):
    return f"{x / 1e6:.1f} M"


yade, yade_cpu = {}, {}
for threads in (1, 2):
    y = load(f"yade_hcp_r2.5mm_threads{threads}.json")
    if y:
        yade[threads] = y["bond_updates_per_second"]
        yade_cpu[threads] = y["bond_updates_per_cpu_second"]

print("| specimen | dashpots | threads | full model (best / median) | plain loop (best / median) "
      "| full / plain | 2 threads / 1 | particle-steps/s | x YADE | per CPU-s: full, plain, x YADE |")
print("|---|---|---|---|---|---|---|---|---|---|")
for name, label in (("dem_hcp_r2.5mm.json", "HCP lattice"),
                    ("dem_random_r2.5mm.json", "random packing"),
                    ("dem_hcp_r2.5mm_no_dashpots.json", "HCP lattice"),
                    ("dem_hcp_r0.74mm.json", "HCP lattice")):
    j = load(name)
    if not j:
        continue
    spec = f"{label}, {j['n_particles']:,} spheres, {j['n_bonds']:,} bonds"
    one = None
    for run in j["runs"]:
        full, plain = run["full"], run.get("plain")
        rate = full["bond_updates_per_second"]
        if run["threads"] == 1:
            one = rate
        scaling = f"{rate / one:.2f}x" if one and run["threads"] > 1 else ""
        peer = (f"{rate / yade[run['threads']]:.1f}x"
                if name == "dem_hcp_r2.5mm.json" and run["threads"] in yade else "")
        cpu = full["bond_updates_per_cpu_second"]
        cpu_peer = (f", {cpu / yade_cpu[run['threads']]:.1f}x"
                    if name == "dem_hcp_r2.5mm.json" and run["threads"] in yade_cpu else "")
        print(f"| {spec} | {'on' if j['bond_damping_ratio'] > 0 else 'off'} | {run['threads']} "
              f"| {m(rate)} / {m(full['bond_updates_per_second_median'])} "
              f"| {m(plain['bond_updates_per_second'])} / "
              f"{m(plain['bond_updates_per_second_median'])} "
              f"| {run.get('ratio_full_to_plain_median', 0):.2f} | {scaling} "
              f"| {m(full['particle_steps_per_second'])} | {peer} "
              f"| {m(cpu)}, {m(plain['bond_updates_per_cpu_second'])}{cpu_peer} |")
for threads, rate in sorted(yade.items()):
    print(f"| YADE 2023.02a, HCP lattice | - | {threads} | {m(rate)} | | | | | "
          f"| {m(yade_cpu[threads])} |")

print()
print("| specimen | bytes per particle | of which bonds | bonds per particle "
      "| + force records (static, coupled runs) |")
print("|---|---|---|---|---|")
for name in ("dem_hcp_r2.5mm.json", "dem_hcp_r0.74mm.json", "dem_random_r2.5mm.json"):
    j = load(name)
    if not j:
        continue
    b = j["bytes_per_particle"]
    print(f"| {j['packing']} r = {j['radius'] * 1e3:g} mm, {j['n_particles']:,} spheres "
          f"| {total_explicit(b):.0f} | {bonds_explicit(b):.0f} | {b['bonds_per_particle']:.2f} "
          f"| {records(b):.0f} |")
