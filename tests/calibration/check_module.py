#!/usr/bin/python3
"""dembridge.calibrate from Python against `dembridge calibrate`: the same calibrated values to
the last bit and the same iterations, a target out of reach reported in the returned dict, and
an unphysical target raised as CaseError with the command line's line.

usage: check_module.py DEMBRIDGE TARGETS OUTDIR   (PYTHONPATH: the build's python folder)
"""
import json
import os
import shutil
import subprocess
import sys

import dembridge


def main():
    exe, targets, outdir = sys.argv[1:4]
    shutil.rmtree(outdir, ignore_errors=True)
    cli_dir, py_dir = os.path.join(outdir, "cli"), os.path.join(outdir, "python")
    subprocess.run([exe, "calibrate", targets, "--output-dir", cli_dir, "--no-plot"], check=True)
    with open(os.path.join(cli_dir, "calibration.json")) as f:
        cli = json.load(f)
    report = dembridge.calibrate(targets, output_dir=py_dir, plot=False)
    failures = []
    if not report["reached"] or report["calibrated"] != cli["calibrated"]:
        failures.append(f"calibrated values: {report.get('calibrated')} != {cli['calibrated']}")
    strip = lambda rows: [{k: v for k, v in r.items() if k != "solve_seconds"} for r in rows]
    if strip(report["elastic"]["iterations"]) != strip(cli["elastic"]["iterations"]):
        failures.append("the iterations differ from the command line's")
    if not os.path.isfile(os.path.join(py_dir, "calibrated.prm")):
        failures.append("calibrated.prm not written")
    far = dembridge.calibrate(targets, output_dir=os.path.join(outdir, "far"), plot=False,
                              set={"Calibration/target poisson ratio": 0.45})
    print("out of reach:", far["failure"])
    if far["reached"] or "out of reach" not in far["failure"]:
        failures.append("a target out of reach is not reported")
    try:
        dembridge.calibrate(targets, output_dir=os.path.join(outdir, "bad"),
                            set={"Calibration/target youngs modulus": -1})
        failures.append("E < 0 did not raise")
    except dembridge.CaseError as e:
        print("CaseError:", e)
        if "Calibration/target youngs modulus: -1: must be positive" not in str(e):
            failures.append(f"CaseError does not name the key: {e}")
    if failures:
        raise SystemExit("FAIL: " + "; ".join(failures))
    print("ok")


if __name__ == "__main__":
    main()
