#!/usr/bin/env python3
"""Runs `dembridge calibrate TARGETS` and checks calibration.json against the targets, then runs
the calibrated case files through `dembridge run` and checks them independently.

usage: check_calibration.py DEMBRIDGE TARGETS OUTDIR --youngs-modulus E --poisson-ratio NU
       --tolerance T --max-solves N [--tensile-strength S --strength-tolerance TS --max-runs M]
       [--set KEY=VALUE ...]

Asserted: every target within its relative tolerance, measured by the last solve (or run) of
the iteration and again by an ordinary run of the calibrated case; at most N static solves (M
tension runs); calibration.png written. Printed, not asserted: the iterations and the spread
over further packings when the targets file asks for one.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys


def run(cmd):
    print("$", " ".join(cmd), flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(done.stdout, flush=True)
    return done.returncode


def within(name, measured, target, tolerance, failures):
    error = abs(measured - target) / abs(target)
    ok = error <= tolerance
    print(f"{name}: {measured:.6g} (target {target:.6g}, relative error {error:.2e}, "
          f"tolerance {tolerance:g}): {'ok' if ok else 'FAIL'}")
    if not ok:
        failures.append(name)


def mean_lateral_poisson_ratio(summary):
    ratios = [v for k, v in summary.items() if k.startswith("poisson_ratio_") and len(k) == 16]
    if len(ratios) != 2:
        raise SystemExit(f"FAIL: summary.json has {len(ratios)} lateral Poisson's ratios")
    return sum(ratios) / 2


def main():
    a = argparse.ArgumentParser()
    a.add_argument("dembridge")
    a.add_argument("targets")
    a.add_argument("outdir")
    a.add_argument("--youngs-modulus", type=float, required=True)
    a.add_argument("--poisson-ratio", type=float, required=True)
    a.add_argument("--tolerance", type=float, required=True)
    a.add_argument("--max-solves", type=int, required=True)
    a.add_argument("--tensile-strength", type=float)
    a.add_argument("--strength-tolerance", type=float)
    a.add_argument("--max-runs", type=int)
    a.add_argument("--set", action="append", default=[])
    o = a.parse_args()
    shutil.rmtree(o.outdir, ignore_errors=True)
    cmd = [o.dembridge, "calibrate", o.targets, "--output-dir", o.outdir]
    for s in o.set:
        cmd += ["--set", s]
    if run(cmd) != 0:
        raise SystemExit("FAIL: dembridge calibrate exited non-zero")
    with open(os.path.join(o.outdir, "calibration.json")) as f:
        j = json.load(f)
    failures = []
    if not j["reached"]:
        failures.append("reached")
    elastic = j["elastic"]
    last = elastic["iterations"][-1]
    solves = len(elastic["iterations"])
    print(f"static solves: {solves} (at most {o.max_solves})")
    for it in elastic["iterations"]:
        print("  ", {k: it[k] for k in it if k != "poisson_ratio_lateral"})
    if solves > o.max_solves or elastic["static_solves"] != solves:
        failures.append("static solves")
    within("E (calibration.json)", last["youngs_modulus"], o.youngs_modulus, o.tolerance, failures)
    within("nu (calibration.json)", last["poisson_ratio"], o.poisson_ratio, o.tolerance, failures)
    if "spread" in j:
        print("spread (reported, not asserted):", json.dumps(j["spread"], indent=1))
    if not os.path.isfile(os.path.join(o.outdir, "calibration.png")):
        failures.append("calibration.png")

    # the calibrated case, run as any case: its own E and nu
    check = os.path.join(o.outdir, "check_run")
    if run([o.dembridge, "run", os.path.join(o.outdir, "calibrated.prm"), "--output-dir", check]):
        raise SystemExit("FAIL: dembridge run calibrated.prm exited non-zero")
    with open(os.path.join(check, "summary.json")) as f:
        s = json.load(f)
    within("E (dembridge run calibrated.prm)", s["youngs_modulus"], o.youngs_modulus, o.tolerance,
           failures)
    within("nu (dembridge run calibrated.prm)", mean_lateral_poisson_ratio(s), o.poisson_ratio,
           o.tolerance, failures)

    if o.tensile_strength:
        strength = j["strength"]
        runs = len(strength["iterations"])
        print(f"tension runs: {runs} (at most {o.max_runs})")
        for it in strength["iterations"]:
            print("  ", it)
        if runs > o.max_runs:
            failures.append("tension runs")
        within("sigma_t (calibration.json)", strength["iterations"][-1]["peak_stress"],
               o.tensile_strength, o.strength_tolerance, failures)
        check = os.path.join(o.outdir, "check_strength_run")
        if run([o.dembridge, "run", os.path.join(o.outdir, "calibrated_strength.prm"),
                "--output-dir", check]):
            raise SystemExit("FAIL: dembridge run calibrated_strength.prm exited non-zero")
        with open(os.path.join(check, "summary.json")) as f:
            s = json.load(f)
        within("sigma_t (dembridge run calibrated_strength.prm)", s["peak_stress"],
               o.tensile_strength, o.strength_tolerance, failures)
    if "compression" in j:
        print("compression (reported, not asserted):", json.dumps(j["compression"], indent=1))
    if failures:
        raise SystemExit("FAIL: " + ", ".join(failures))
    print("ok")


if __name__ == "__main__":
    main()
