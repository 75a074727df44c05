#!/usr/bin/python3
"""Full-DEM specimen study of the thesis (sections 4-5, Table 1): runs the simulation matrix
packings x radii x bond models x tests (x random seeds) on the example cases through the Python
module (dembridge.run, docs/python.md: the library `dembridge run` is built on, in this process),
collects every run's summary into results.csv and draws the thesis' Figures 29-35.

    /usr/bin/python3 scripts/study.py                         # the whole Table 1 matrix, static
    /usr/bin/python3 scripts/study.py --packings random --radii 5,7.5 --seeds 1-3 \\
        --models pbm --tests compression --solver static,explicit --jobs 2 --out study

Matrix (thesis Table 1): packings cubic (the thesis' "uniform"), hcp, random; radii 2.5, 5,
7.5, 10, 12.5 mm; bond models pbm (parallel bond, thesis calibration k̄_n = E_b/(2 r),
k̄_n/k̄_s = 4.2) and tbbm (Timoshenko beam); tests tension, compression, bending; 5 random
packings (seeds 1-5) per radius. As in the thesis, TBBM bending at r = 2.5 mm is left out
(Table 1: 0 runs) unless --full is given. Any other radius or seed may be asked for.

Runs. Each run is dembridge.run(example, output_dir, set=[...]): the example case with the
overrides below, the same files and figures as `dembridge run EXAMPLE --set ...` (its
summary.json records that command line); what the library prints goes to the run's
dembridge.log. The module is the one of the build that --dembridge names (BUILD/app/dembridge:
BUILD/python). --jobs N runs N specimens at a time in N worker processes (started with
'spawn': each imports the module afresh; a run changes the working directory of its process,
so runs never share one).

Specimens. Each (packing, radius, seed) is generated once by dembridge (the compression example
with `Particles/save file`, end time 0) and stored in OUT/specimens/; every test and bond model
of that specimen reads it back (`Particles/source = file`), as the thesis loaded each packing in
all three tests. Spheres that would not be bonded to the specimen's main bonded cluster (the
rare rattlers of a random packing, which carry no load) are dropped from the stored specimen,
so that the static solver never meets a support or load on a sphere without stiffness.
Porosity (`specimen_porosity`) = 1 - sum of sphere volumes / volume of the specimen's extent
(the bounding box of the spheres, as the thesis' Table 2 reports the HCP dimensions).

Supports. Uniaxial tests: the end groups of the example (spheres within 1.5 r of the end
faces; x- held in x, x+ moved in x), plus exactly three constraints for the rigid-body modes
the ends leave free: the sphere nearest the corner (x-, y-, z-) held in y and z (group
`corner`), the sphere nearest (x-, y+, z-) held in z (group `corner_y`). Statically
determinate: their reactions are zero and the result does not depend on the spheres chosen.
Bending: pin (x-) and roller (x+) are the spheres within 1.5 r of the bottom corner edges, the
1 kN load is shared by the top spheres within 1.5 r of midspan, the deflection averages those
and the bottom midspan spheres (examples/bending_*.prm); the boxes are recomputed from each
specimen's extent. The flexural Poisson's ratio (eq. 67, 69) is the mean of nu_xy and nu_xz
of the same specimen's compression run when there is one.

Resumable: a run whose summary.json exists is skipped; dembridge writes summary.json last, so
an interrupted run has none and is run again. results.csv and the plots are rebuilt from every
run found under OUT/runs at the end (also with --report-only).
Requires numpy and matplotlib (Debian: /usr/bin/python3); nothing else beyond the stdlib.
"""
import argparse
import csv
import json
import math
import os
import re
import shutil
import sys
import time
from pathlib import Path

# the runs (study_runs.py); the names the plots and the bench read as study.NAME come along
from study_runs import (  # noqa: F401
    HCP_IDEAL_POROSITY, MODELS, PACKINGS, RADII_MM, RCP_MIN_POROSITY, ROOT, TESTS, Runner,
    StudyError, execute, module_folder, poisson_for_bending, run_name, specimen_name)

# ----------------------------------------------------------------------------- matrix


def parse_list(text, conv, allowed=None, name=""):
    out = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        if conv is int and re.fullmatch(r"\d+-\d+", part):
            a, b = (int(v) for v in part.split("-"))
            out.extend(range(a, b + 1))
            continue
        try:
            v = conv(part)
        except ValueError:
            raise StudyError(f"--{name}: cannot read '{part}'")
        if allowed is not None and v not in allowed:
            raise StudyError(f"--{name}: unknown '{part}' (expected one of {', '.join(allowed)})")
        out.append(v)
    if not out:
        raise StudyError(f"--{name}: empty list")
    return list(dict.fromkeys(out))




def build_matrix(a):
    runs = []
    for packing in a.packings:
        for radius in a.radii:
            for seed in a.seeds if packing == "random" else [None]:
                for model in a.models:
                    for test in a.tests:
                        if test == "bending" and model == "tbbm" and radius < 3 and not a.full:
                            continue  # thesis Table 1: no TBBM flexural runs at r = 2.5 mm
                        for solver in a.solver:
                            runs.append(dict(packing=packing, radius_mm=radius, seed=seed,
                                             model=model, test=test, solver=solver))
    # compression before tension before bending within a specimen: bending takes its
    # Poisson's ratio from the compression run
    order = {t: i for i, t in enumerate(("compression", "tension", "bending"))}
    runs.sort(key=lambda r: (specimen_name(r["packing"], r["radius_mm"], r["seed"]),
                             order[r["test"]], r["model"], r["solver"]))
    return runs



# ----------------------------------------------------------------------------- results


def flatten(prefix, v, out):
    if isinstance(v, dict):
        for k, w in v.items():
            flatten(f"{prefix}.{k}" if prefix else k, w, out)
    elif isinstance(v, list):
        if len(v) <= 64:
            for i, w in enumerate(v):
                flatten(f"{prefix}[{i}]", w, out)
    elif isinstance(v, (int, float, str, bool)) or v is None:
        out[prefix] = v


PARAM_COLS = ["run", "packing", "radius_mm", "seed", "model", "test", "solver", "specimen",
              "specimen_particles", "specimen_dropped", "specimen_porosity",
              "specimen_porosity_box", "contact_radius_multiplier", "flexural_poisson_ratio",
              "case"]


def collect(out):
    rows = []
    for rdir in sorted((Path(out) / "runs").glob("*")):
        s, m = rdir / "summary.json", rdir / "run.json"
        if not (s.exists() and m.exists()):
            continue
        row = {k: v for k, v in json.loads(m.read_text()).items() if k in PARAM_COLS}
        summary = json.loads(s.read_text())
        flat = {}
        for k, v in summary.items():
            if k == "groups":  # per-group detail stays in the run's summary.json
                continue
            flatten(k, v, flat)
        row.update(flat)
        rows.append(row)
    return rows


def write_csv(path, rows):
    keys = list(PARAM_COLS)
    extra = sorted({k for r in rows for k in r} - set(keys))
    keys += extra
    tmp = Path(str(path) + ".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in keys})
    os.replace(tmp, path)


def wang_mora_E(youngs=4e9, ratio=4.2):
    """Thesis eq. 2 (Wang and Mora 2008) for the thesis' PBM: k_n = k̄_n pi r^2, k̄_n = E_b/(2r),
    k_s = k_n / ratio; E_x is independent of r."""
    r = 1.0
    kn = youngs / (2 * r) * math.pi * r * r
    ks = kn / ratio
    return (3 * math.sqrt(2) * kn * (kn + ks) * (3 * kn ** 2 + 23 * ks ** 2 + 22 * kn * ks) /
            (r * (18 * kn ** 3 + 119 * kn ** 2 * ks + 128 * kn * ks ** 2 + 23 * ks ** 3)))


# ----------------------------------------------------------------------------- main


def find_dembridge(arg):
    cands = [Path(arg)] if arg else []
    if not arg and os.environ.get("DEMBRIDGE"):
        cands.append(Path(os.environ["DEMBRIDGE"]))
    if not cands:
        cands = [ROOT / "build" / "app" / "dembridge"]
    for c in cands:
        if c.is_file() and os.access(c, os.X_OK):
            return c.resolve()
    raise StudyError("the dembridge executable was not found (looked for "
                     + ", ".join(str(c) for c in cands)
                     + "); build it first (bash scripts/setup.sh) or pass --dembridge PATH")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--packings", default=",".join(PACKINGS), help="cubic,hcp,random")
    ap.add_argument("--radii", default=",".join(f"{r:g}" for r in RADII_MM),
                    help="particle radii in mm (default 2.5,5,7.5,10,12.5)")
    ap.add_argument("--models", default="pbm,tbbm", help="pbm,tbbm")
    ap.add_argument("--tests", default=",".join(TESTS), help="tension,compression,bending")
    ap.add_argument("--seeds", default="1-5", help="random packings: seeds, e.g. 1-5 or 1,3")
    ap.add_argument("--solver", default="static", help="static, explicit or static,explicit")
    ap.add_argument("--full", action="store_true",
                    help="also TBBM bending at r < 3 mm (left out in the thesis' Table 1)")
    ap.add_argument("--jobs", type=int, default=1, help="specimens run in parallel (default 1)")
    ap.add_argument("--out", default="study", help="output folder (default ./study)")
    ap.add_argument("--dembridge", default="", help="the build to use, named by its dembridge "
                    "executable: the runs go through that build's Python module (BUILD/python; "
                    "default $DEMBRIDGE, else build/app/dembridge)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="extra override passed to every run (e.g. 'Simulation/threads=2')")
    ap.add_argument("--dry-run", action="store_true", help="list the runs and stop")
    ap.add_argument("--report-only", action="store_true",
                    help="rebuild results.csv and the plots from the runs in --out")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--fresh", action="store_true",
                    help="first delete what an earlier call wrote into --out (runs, specimens, "
                         "results.csv, the plots): nothing is reused")
    a = ap.parse_args(argv)
    try:
        a.packings = parse_list(a.packings, str, PACKINGS, "packings")
        a.radii = parse_list(a.radii, float, None, "radii")
        if any(not (r > 0) for r in a.radii):
            raise StudyError("--radii: radii must be positive (mm)")
        a.models = parse_list(a.models, str, tuple(MODELS), "models")
        a.tests = parse_list(a.tests, str, TESTS, "tests")
        a.seeds = parse_list(a.seeds, int, None, "seeds")
        a.solver = parse_list(a.solver, str, ("static", "explicit"), "solver")
        runs = build_matrix(a)
        if a.dry_run:
            for r in runs:
                print(run_name(r))
            print(f"{len(runs)} runs")
            return 0
        # the plots module reads this module's constants, so it is imported once both exist
        from study_plots import PLOTS, plots

        out = Path(a.out)
        if a.fresh and not a.report_only:
            for d in ("runs", "specimens"):
                shutil.rmtree(out / d, ignore_errors=True)
            for f in ["results.csv", *PLOTS]:
                (out / f).unlink(missing_ok=True)
        failures = []
        if not a.report_only:
            exe = find_dembridge(a.dembridge)
            folder = module_folder(exe)
            runner = Runner(exe, out, extra_sets=a.set)
            print(f"study: {len(runs)} runs into {out.resolve()} with the dembridge module in "
                  f"{folder} ({a.jobs} job(s))", flush=True)
            t0 = time.time()
            failures = execute(runner, runs, a.jobs)
            print(f"study: finished in {time.time() - t0:.1f} s", flush=True)
        rows = collect(out)
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / "results.csv", rows)
        print(f"study: {len(rows)} runs in {out / 'results.csv'}")
        if not a.no_plots and rows:
            for p in plots(out, rows, a.solver[0]):
                print(f"study: wrote {p}")
        if failures:
            print(f"study: {len(failures)} run(s) failed:", file=sys.stderr)
            for n, e in failures:
                print(f"  {n}: {e}", file=sys.stderr)
            return 1
        return 0
    except StudyError as e:
        print(f"study.py: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
