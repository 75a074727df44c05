#!/usr/bin/env python3
"""A target the bond model cannot reach: `dembridge calibrate` must exit 1 with one line on
stderr that names the key and the reachable limit, record the reason in calibration.json, and
write no calibrated case.

usage: check_out_of_reach.py DEMBRIDGE TARGETS OUTDIR REGEX [--written] [--set KEY=VALUE ...]

--written: the target is sigma_c / sigma_t, which calibrate measures and does not iterate on;
the calibrated cases (E, nu and sigma_t reached) are then written, and must be.
"""
import json
import os
import re
import shutil
import subprocess
import sys


def main():
    exe, targets, outdir, regex = sys.argv[1:5]
    sets = sys.argv[5:]
    written = "--written" in sets
    if written:
        sets.remove("--written")
    shutil.rmtree(outdir, ignore_errors=True)
    cmd = [exe, "calibrate", targets, "--output-dir", outdir] + sets
    print("$", " ".join(cmd), flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    print(done.stdout)
    print("stderr:", done.stderr)
    if done.returncode != 1:
        raise SystemExit(f"FAIL: exit code {done.returncode}, expected 1")
    if done.stderr.count("\n") != 1 or not done.stderr.endswith("\n"):
        raise SystemExit("FAIL: stderr is not one line")
    if not re.search(regex, done.stderr):
        raise SystemExit(f"FAIL: stderr does not match /{regex}/")
    with open(os.path.join(outdir, "calibration.json")) as f:
        j = json.load(f)
    if j["reached"] or j["failure"] not in done.stderr:
        raise SystemExit("FAIL: calibration.json does not record the reason")
    names = ["calibrated.prm"] + (["calibrated_strength.prm"] if written else [])
    for name in names:
        if os.path.exists(os.path.join(outdir, name)) != written:
            raise SystemExit(f"FAIL: {name} was {'not ' if written else ''}written")
    print("ok")


if __name__ == "__main__":
    main()
