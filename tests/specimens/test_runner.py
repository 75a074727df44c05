#!/usr/bin/python3
"""ctest of scripts/study.py on a tiny subset (two runs: the r = 12.5 mm cubic specimen in
compression and bending, PBM, static solver):

  - results.csv has one row per run with the run's parameters, and every summary value in it
    equals the run's summary.json; the compression row gives E = pi E_b / 4 (1e-6);
  - the four PNG figures exist and are PNG images;
  - resumable: a second call runs nothing ("skipped"), and after a run's summary.json is
    removed (an interrupted run) exactly that run is run again;
  - a missing dembridge executable is one clear error and exit code 2.

    test_runner.py DEMBRIDGE OUTDIR
"""
import csv
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
STUDY = HERE.parents[1] / "scripts" / "study.py"
failures = []


def check(ok, text):
    print(("ok   " if ok else "FAIL ") + text, flush=True)
    if not ok:
        failures.append(text)


def study(exe, out, *extra):
    cmd = [sys.executable, str(STUDY), "--dembridge", str(exe), "--out", str(out),
           "--packings", "cubic", "--radii", "12.5", "--models", "pbm",
           "--tests", "compression,bending", "--solver", "static", *extra]
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(p.stdout + p.stderr, flush=True)
    return p


def main(exe, out):
    out = Path(out)
    shutil.rmtree(out, ignore_errors=True)
    p = study(exe, out)
    check(p.returncode == 0, f"study.py exit code {p.returncode}")
    rows = list(csv.DictReader(open(out / "results.csv")))
    check(len(rows) == 2, f"results.csv has {len(rows)} rows (2 expected)")
    by_test = {r["test"]: r for r in rows}
    check(set(by_test) == {"compression", "bending"}, f"tests {sorted(by_test)}")
    for r in rows:
        check(r["packing"] == "cubic" and float(r["radius_mm"]) == 12.5 and r["model"] == "pbm"
              and r["solver"] == "static", f"{r['run']}: parameters in the row")
        summary = json.loads((out / "runs" / r["run"] / "summary.json").read_text())
        bad = [k for k, v in summary.items() if isinstance(v, (int, float)) and
               not isinstance(v, bool) and (k not in r or not math.isclose(float(r[k]), v,
                                                                            rel_tol=1e-12))]
        check(not bad, f"{r['run']}: every scalar of summary.json in the row"
                       + (f" (differ: {bad})" if bad else ""))
        check(int(r["n_particles"]) == int(r["specimen_particles"]) == 10 * 4 * 4,
              f"{r['run']}: {r['n_particles']} spheres = 10 x 4 x 4")
        # the cubic specimen fills its extent: porosity 1 - pi/6
        check(abs(float(r["specimen_porosity"]) - (1 - math.pi / 6)) < 1e-12,
              f"{r['run']}: porosity {r['specimen_porosity']} = 1 - pi/6")
    e = float(by_test["compression"]["youngs_modulus"])
    check(abs(e / (math.pi * 4e9 / 4) - 1) < 1e-6, f"cubic E = {e:.6g} Pa = pi E_b / 4 (1e-6)")
    ef = float(by_test["bending"]["flexural_modulus"])
    check(0 < ef < e, f"E_f = {ef:.4g} Pa below E (thesis Fig. 34)")
    for png in ("youngs_modulus.png", "poisson_ratio.png", "flexural_modulus.png",
                "flexural_vs_axial.png"):
        path = out / png
        ok = path.exists() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and \
            path.stat().st_size > 5000
        check(ok, f"{png} written")

    # resumable
    before = (out / "results.csv").read_text()
    p = study(exe, out)
    check(p.returncode == 0 and p.stdout.count("skipped") == 2,
          "second call skips both runs")
    check((out / "results.csv").read_text() == before, "results.csv unchanged by the second call")
    (out / "runs" / by_test["bending"]["run"] / "summary.json").unlink()
    p = study(exe, out)
    check(p.returncode == 0 and p.stdout.count("skipped") == 1 and "bending_static: " in p.stdout
          and "E_f =" in p.stdout, "an interrupted run (no summary.json) is run again, alone")

    # missing executable
    p = study(out / "no-such-dembridge", out / "x")
    check(p.returncode == 2 and "dembridge executable was not found" in p.stderr
          and len(p.stderr.strip().splitlines()) == 1, "missing dembridge: one-line error, exit 2")

    print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
