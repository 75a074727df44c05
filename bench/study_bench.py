#!/usr/bin/python3
"""Benchmark of the specimen study, JSON into bench/results/:

 1. study_hcp_r2.5mm.json: uniaxial compression of the r = 2.5 mm HCP specimen (26,004
    spheres, the thesis' largest) with the static and the explicit solver: wall time,
    bond-updates per second (explicit: measured; static: the explicit run's bond updates divided
    by the static wall time, i.e. the rate at which it delivers the same answer), E from each.
 2. study_matrix_static.json: the thesis' Table 1 matrix (scripts/study.py defaults: 3 packings
    x 5 radii x 2 bond models x 3 tests, 5 seeds for random; 203 runs) with the static solver,
    timed end to end (packing generation included), and the estimated explicit total: for each
    run, steps x bonds / measured explicit bond-update rate (steps = end time / time step for
    the uniaxial tests; for bending the measured ratio of bending to compression steps).
    With --matrix subset only seed 1 of the random packings runs and the other seeds are
    extrapolated (random runs x 5); the JSON says which.

    /usr/bin/python3 bench/study_bench.py [--dembridge PATH] [--matrix full|subset|none]
                                          [--work DIR] [--skip-explicit]

Run on an otherwise idle machine: the figures are wall-clock times.
"""
import argparse
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import study  # noqa: E402


def machine():
    cpu = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return dict(host=platform.node(), cpu=cpu, cores=os.cpu_count(),
                load_average=os.getloadavg())


def summary(out, run):
    return json.loads((Path(out) / "runs" / study.run_name(run) / "summary.json").read_text())


def timed_run(runner, run):
    spec = runner.specimen(run["packing"], run["radius_mm"], run["seed"])
    poisson = study.poisson_for_bending(runner.out, run) if run["test"] == "bending" else None
    t0 = time.time()
    status, _ = runner.run(spec, run, poisson)
    wall = time.time() - t0
    return spec, summary(runner.out, run), wall if status == "ran" else None


def rec(**kw):
    return dict(packing="hcp", radius_mm=2.5, seed=None, model="pbm", test="compression",
                solver="static") | kw


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dembridge", default="")
    ap.add_argument("--matrix", choices=("full", "subset", "none"), default="full")
    ap.add_argument("--work", default="/tmp/dembridge_study_bench",
                    help="scratch folder for the runs (emptied first)")
    ap.add_argument("--skip-explicit", action="store_true",
                    help="skip the explicit r = 2.5 mm HCP run (about 3-4 min)")
    ap.add_argument("--results", default=str(ROOT / "bench" / "results"))
    a = ap.parse_args()
    exe = study.find_dembridge(a.dembridge)
    work = Path(a.work)
    shutil.rmtree(work, ignore_errors=True)
    res = Path(a.results)
    res.mkdir(parents=True, exist_ok=True)
    date = time.strftime("%Y-%m-%d %H:%M")

    # --- 1. HCP r = 2.5 mm, both solvers -------------------------------------------------
    r1 = study.Runner(exe, work / "hcp")
    t0 = time.time()
    spec = r1.specimen("hcp", 2.5, None)
    gen = time.time() - t0
    out = dict(date=date, machine=machine(), dembridge=str(exe), specimen=dict(
        packing="hcp", radius_mm=2.5, spheres=spec["n_particles"],
        porosity=spec["porosity"], generate_and_prepare_seconds=round(gen, 2)))
    _, s_st, w_st = timed_run(r1, rec())
    out["static"] = dict(wall_seconds=round(w_st, 2), solver_seconds=s_st.get("solver_seconds"),
                         iterations=s_st.get("solver", {}).get("iterations"),
                         n_bonds=s_st.get("n_bonds"), youngs_modulus=s_st.get("youngs_modulus"))
    print(f"HCP r = 2.5 mm: {spec['n_particles']} spheres, {s_st.get('n_bonds')} bonds; "
          f"static: {w_st:.1f} s wall (solve {s_st.get('solver_seconds', 0):.1f} s), "
          f"E = {s_st['youngs_modulus'] / 1e9:.4f} GPa", flush=True)
    rate = None
    if not a.skip_explicit:
        _, s_ex, w_ex = timed_run(r1, rec(solver="explicit"))
        updates = s_ex["steps"] * s_ex["n_bonds"]
        rate = s_ex.get("bond_updates_per_second")
        out["explicit"] = dict(wall_seconds=round(w_ex, 2), steps=s_ex["steps"],
                               bond_updates=updates, bond_updates_per_second=rate,
                               youngs_modulus=s_ex.get("youngs_modulus"),
                               energy_balance_error=s_ex.get("energy_balance_error"))
        out["static"]["equivalent_bond_updates_per_second"] = updates / w_st
        out["speedup_static_over_explicit"] = w_ex / w_st
        out["relative_difference_E"] = s_ex["youngs_modulus"] / s_st["youngs_modulus"] - 1
        print(f"  explicit: {w_ex:.1f} s wall, {s_ex['steps']} steps, {rate / 1e6:.1f} M "
              f"bond-updates/s, E = {s_ex['youngs_modulus'] / 1e9:.4f} GPa "
              f"({out['relative_difference_E'] * 100:+.4f} %); static is {w_ex / w_st:.0f}x "
              f"faster ({updates / w_st / 1e6:.0f} M equivalent bond-updates/s)", flush=True)
    (res / "study_hcp_r2.5mm.json").write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {res / 'study_hcp_r2.5mm.json'}", flush=True)
    if a.matrix == "none":
        return 0

    # --- 2. Table 1 matrix, static ---------------------------------------------------------
    # explicit rates and the bending/compression step ratio, measured on r = 7.5 mm specimens
    cal = study.Runner(exe, work / "calibration")
    calib = {}
    for model in ("pbm", "tbbm"):
        for packing in ("hcp", "random"):
            c = dict(packing=packing, radius_mm=7.5, seed=1 if packing == "random" else None,
                     model=model, solver="explicit")
            _, sc, _ = timed_run(cal, dict(c, test="compression"))
            _, sb, _ = timed_run(cal, dict(c, test="bending"))
            calib[f"{packing}_{model}"] = dict(rate=sc["bond_updates_per_second"],
                                               bend_steps_ratio=sb["steps"] / sc["steps"])
    rates = {m: min(v["rate"] for k, v in calib.items() if k.endswith(m))
             for m in ("pbm", "tbbm")}
    if rate and rate < rates["pbm"]:  # the large specimen runs slower (out of cache): use it
        rates = {m: v * rate / rates["pbm"] for m, v in rates.items()}
    bend_ratio = max(v["bend_steps_ratio"] for v in calib.values())

    seeds = "1-5" if a.matrix == "full" else "1"
    mout = work / "matrix"
    args = ["--out", str(mout), "--solver", "static", "--seeds", seeds, "--no-plots",
            "--dembridge", str(exe)]
    t0 = time.time()
    p = subprocess.run([sys.executable, str(ROOT / "scripts" / "study.py"), *args])
    wall = time.time() - t0
    rows = study.collect(mout)
    gen = sum(json.loads(f.read_text()).get("generate_seconds", 0)
              for f in (mout / "specimens").glob("*.json"))
    explicit_est = 0.0
    for r in rows:
        dt = 0.8 * float(r["critical_time_step"])
        end = 0.02 if r["test"] != "bending" else 0.02 * bend_ratio
        steps = math.ceil(end / dt)
        explicit_est += steps * float(r["n_bonds"]) / rates[r["model"]] + 1.0
    n_rand = sum(1 for r in rows if r["packing"] == "random")
    total_runs = len(rows) + (4 * n_rand if a.matrix == "subset" else 0)
    m = dict(date=date, machine=machine(), matrix=a.matrix, runs=len(rows),
             runs_in_table1=total_runs, exit_code=p.returncode,
             static_wall_seconds=round(wall, 1),
             packing_generation_seconds=round(gen, 1),
             explicit_rates_bond_updates_per_second=rates,
             explicit_bending_steps_per_compression_steps=bend_ratio,
             explicit_calibration=calib,
             explicit_estimated_seconds=round(explicit_est, 0))
    if a.matrix == "subset":
        # random cells run with one seed: the other four cost the same (generation included)
        rand_share = sum(1 for r in rows if r["packing"] == "random") / max(len(rows), 1)
        m["static_wall_seconds_extrapolated"] = round(wall * (1 + 4 * rand_share), 1)
        m["explicit_estimated_seconds_extrapolated"] = round(explicit_est * (1 + 4 * rand_share), 0)
        m["note"] = ("random packings with seed 1 only; the *_extrapolated figures count 5 seeds "
                     "(random share of the runs x 5)")
    (res / "study_matrix_static.json").write_text(json.dumps(m, indent=1) + "\n")
    print(f"Table 1 matrix ({a.matrix}): {len(rows)} runs, static {wall:.0f} s wall "
          f"(packing generation {gen:.0f} s); explicit estimated {explicit_est / 3600:.1f} h "
          f"at {rates['pbm'] / 1e6:.1f} (PBM) / {rates['tbbm'] / 1e6:.1f} (TBBM) M "
          "bond-updates/s", flush=True)
    print(f"wrote {res / 'study_matrix_static.json'}")
    return 0 if p.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
