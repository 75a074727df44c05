#!/usr/bin/python3
"""`dembridge calibrate` beside a 20-run design of experiments on the same targets, JSON into
bench/results/calibration.json (or --output).

For each specimen (the HCP and the random packing of examples/calibrate_{hcp,random}.prm, with
their targets E and nu):
 1. calibrate: `dembridge calibrate`, timed end to end; its static-solve count and the E and nu
    of the calibrated case, measured again by `dembridge run calibrated.prm`.
 2. design of experiments, as PFC users calibrate (a 15-30-run design with a response surface):
    20 static runs `dembridge run` on a 5 x 4 grid of the stiffness ratio k_n/k_s (2-12) and the
    bond modulus E_b (2-8 GPa), a full quadratic response surface in both for E and for nu
    (least squares), the surface's best point for the targets (a fine grid search), and one
    more run at that point to measure what it really gives. Timed end to end.
Both: runs, wall seconds, the relative errors of E and nu reached.

    /usr/bin/python3 bench/calibration.py [--dembridge PATH] [--work DIR] [--output FILE]
                                          [--specimens hcp,random]

Run on an otherwise idle machine: the figures are wall-clock times.
"""
import argparse
import itertools
import json
import os
import platform
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
TARGETS = {"hcp": (5.0e9, 0.2), "random": (3.0e9, 0.22)}
RATIOS = np.linspace(2, 12, 5)
MODULI = np.linspace(2e9, 8e9, 4)


def machine():
    cpu = ""
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    return dict(host=platform.node(), cpu=cpu, cores=os.cpu_count(),
                load_average=os.getloadavg())


def run(cmd):
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode:
        raise SystemExit(f"{' '.join(map(str, cmd))} failed:\n{done.stdout}")


def static_run(exe, case, out, sets):
    cmd = [exe, "run", case, "--output-dir", out, "--set", "Output/write vtu=false"]
    for s in sets:
        cmd += ["--set", s]
    run(cmd)
    s = json.loads((Path(out) / "summary.json").read_text())
    nu = [v for k, v in s.items() if k.startswith("poisson_ratio_") and len(k) == 16]
    return s["youngs_modulus"], sum(nu) / len(nu)


def errors(E, nu, targets):
    return dict(youngs_modulus=E, poisson_ratio=nu, youngs_modulus_relative_error=E / targets[0] - 1,
                poisson_ratio_relative_error=nu / targets[1] - 1)


def calibrate(exe, case, work, targets):
    out = work / "calibrate"
    shutil.rmtree(out, ignore_errors=True)
    t0 = time.time()
    run([exe, "calibrate", case, "--output-dir", out, "--no-plot",
         "--set", "Calibration/spread seeds=", "--set", "Calibration/spread box size="])
    wall = time.time() - t0
    report = json.loads((out / "calibration.json").read_text())
    E, nu = static_run(exe, out / "calibrated.prm", work / "calibrate_check", [])
    return dict(static_solves=report["elastic"]["static_solves"], wall_seconds=wall,
                calibrated={k: v for k, v in report["calibrated"].items()},
                **errors(E, nu, targets))


def quadratic_features(kappa, modulus):
    k, m = np.asarray(kappa, float), np.asarray(modulus, float) / 1e9
    return np.stack([np.ones_like(k), k, m, k * k, k * m, m * m], axis=-1)


def design_of_experiments(exe, case, work, targets):
    t0 = time.time()
    points, E, nu = [], [], []
    for i, (kappa, modulus) in enumerate(itertools.product(RATIOS, MODULI)):
        e, n = static_run(exe, case, work / f"doe_{i:02d}",
                          [f"Bonds/stiffness ratio={kappa!r}", f"Bonds/youngs modulus={modulus!r}"])
        points.append((kappa, modulus)), E.append(e), nu.append(n)
    X = quadratic_features(*zip(*points))
    cE = np.linalg.lstsq(X, np.array(E), rcond=None)[0]
    cnu = np.linalg.lstsq(X, np.array(nu), rcond=None)[0]
    kk, mm = np.meshgrid(np.linspace(RATIOS[0], RATIOS[-1], 801),
                         np.linspace(MODULI[0], MODULI[-1], 801))
    G = quadratic_features(kk, mm)
    misfit = ((G @ cE) / targets[0] - 1) ** 2 + ((G @ cnu) / targets[1] - 1) ** 2
    best = np.unravel_index(np.argmin(misfit), misfit.shape)
    kappa, modulus = float(kk[best]), float(mm[best])
    e, n = static_run(exe, case, work / "doe_check",
                      [f"Bonds/stiffness ratio={kappa!r}", f"Bonds/youngs modulus={modulus!r}"])
    return dict(runs=len(points) + 1, design="5 x 4 grid: stiffness ratio 2-12, E_b 2-8 GPa",
                response_surface="full quadratic in (k_n/k_s, E_b), least squares",
                wall_seconds=time.time() - t0,
                calibrated={"Bonds/stiffness ratio": kappa, "Bonds/youngs modulus": modulus},
                **errors(e, n, targets))


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--dembridge", default=str(ROOT / "build" / "app" / "dembridge"))
    a.add_argument("--work", default="/tmp/dembridge_calibration_bench")
    a.add_argument("--output", default=str(ROOT / "bench" / "results" / "calibration.json"))
    a.add_argument("--specimens", default="hcp,random")
    o = a.parse_args()
    result = dict(machine=machine(), specimens={})
    for name in o.specimens.split(","):
        case = ROOT / "examples" / f"calibrate_{name}.prm"
        work = Path(o.work) / name
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir(parents=True)
        targets = TARGETS[name]
        result["specimens"][name] = dict(
            targets=dict(youngs_modulus=targets[0], poisson_ratio=targets[1]),
            calibrate=calibrate(o.dembridge, case, work, targets),
            design_of_experiments=design_of_experiments(o.dembridge, case, work, targets))
        print(json.dumps(result["specimens"][name], indent=1), flush=True)
    Path(o.output).parent.mkdir(parents=True, exist_ok=True)
    Path(o.output).write_text(json.dumps(result, indent=1) + "\n")
    print("wrote", o.output)


if __name__ == "__main__":
    main()
