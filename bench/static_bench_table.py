#!/usr/bin/env python3
"""Markdown tables of bench/static_bench.sh's JSON (bench/RESULTS_STATIC.md).

usage: static_bench_table.py RESULTS_DIR
Reads packing_random.json, static_hcp.json and static_random.json where present.
"""
import json
import os
import sys


def load(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def packing_table(data):
    print("| r (mm) | spheres | iterations | CPU (s) | wall (s) | ns / (sphere iteration) "
          "| porosity | coordination (1.02) | fingerprint |")
    print("|---|---|---|---|---|---|---|---|---|")
    for p in data["points"]:
        print(f"| {1e3 * p['radius_m']:g} | {p['particles']:,} | {p['iterations']:,} "
              f"| {p['cpu_seconds']:.1f} | {p['wall_seconds']:.1f} "
              f"| {1e3 * p['microseconds_per_particle_iteration']:.0f} "
              f"| {p['porosity']:.4f} | {p['coordination_1.02']:.2f} | `{p['fingerprint']}` |")


def static_table(data):
    print("| r (mm) | particles | unknowns | Jacobi CG: iterations | CPU (s) | wall (s) "
          "| GAMG: iterations | set-up (s) | CPU (s) | wall (s) | peak RSS (GiB) "
          "| E (GPa) | E GAMG / E CG - 1 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for p in data["points"]:
        cg, mg = p.get("cg"), p.get("gamg")
        cells = [f"{1e3 * p['radius_m']:g}", f"{p['particles']:,}", f"{(cg or mg)['unknowns']:,}"]
        for s, setup in ((cg, False), (mg, True)):
            if s is None:
                cells += ["-"] * (4 if setup else 3)
                continue
            cells.append(f"{s['iterations']:,}")
            if setup:
                cells.append(f"{s['setup_seconds']:.1f}")
            cells.append(f"{s['cpu_seconds']:.1f}" if "cpu_seconds" in s else "-")
            cells.append(f"{s['assembly_seconds'] + s['solve_seconds']:.1f}")
        cells.append(f"{(mg or cg)['peak_rss_gib']:.1f}")
        cells.append(f"{(mg or cg)['modulus_pa'] / 1e9:.3f}")
        cells.append(f"{mg['modulus_pa'] / cg['modulus_pa'] - 1:.1e}" if cg and mg else "-")
        print("| " + " | ".join(cells) + " |")


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__),
                                                                 "results")
    packing = load(folder, "packing_random.json")
    if packing:
        print("Random close packing (packing-bench):\n")
        packing_table(packing)
        print()
    for kind in ("hcp", "random"):
        data = load(folder, f"static_{kind}.json")
        if data:
            print(f"Quasi-static compression test, {kind} (static-bench):\n")
            static_table(data)
            print()


if __name__ == "__main__":
    main()
