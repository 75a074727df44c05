#!/usr/bin/env python3
"""A case as a .json file runs as its .prm does.

usage: json_round_trip.py DEMBRIDGE CASE.prm OUTDIR [PRM_RUN]

Runs CASE.prm (or takes the finished run of it in PRM_RUN, an example test's folder), writes its complete parameter set (summary.json's "parameters": deal.II's
ParameterHandler printed, every entry after --set; the form of its print_parameters(ShortJSON))
as OUTDIR/CASE.json, runs that, and compares the two summaries: every figure equal, exactly
(the runs are deterministic), except what differs between any two runs (wall time, rates,
memory available, provenance, the case file's name). Values that are JSON numbers or
true/false are written as such (as written in the .prm: 1e9 stays 1e9), the rest as strings,
so that the reader's three kinds of value are used.
"""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

# what two runs of one case may differ in: times and their ratios, memory, provenance
IGNORED = {"coupling_share", "peak_memory_bytes", "available_bytes", "version", "git_commit",
           "command_line", "host", "started_at", "case"}
IGNORED_SUFFIXES = ("_seconds", "_per_second")
NUMBER = re.compile(r"-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?")


def as_json(value, indent=0):
    """JSON text of the parameter tree; number-like values as number tokens."""
    pad = "  " * (indent + 1)
    if isinstance(value, dict):
        items = [pad + json.dumps(k) + ": " + as_json(v, indent + 1) for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if NUMBER.fullmatch(value) or value in ("true", "false"):
        return value
    return json.dumps(value)


def differences(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key in IGNORED or key.endswith(IGNORED_SUFFIXES):
                continue
            where = path + "/" + key if path else key
            if key not in a or key not in b:
                yield where + ": only in the " + ("json" if key in b else "prm") + " run"
            else:
                yield from differences(a[key], b[key], where)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, path + "." + str(i))
    elif a != b and not (isinstance(a, float) and isinstance(b, float)
                         and math.isnan(a) and math.isnan(b)):
        yield f"{path}: prm {a!r}, json {b!r}"


def leaves(a):
    """The number of values compared in a summary."""
    if isinstance(a, dict):
        return sum(leaves(v) for k, v in a.items()
                   if not (k in IGNORED or k.endswith(IGNORED_SUFFIXES)))
    if isinstance(a, list):
        return sum(leaves(v) for v in a)
    return 1


def run(exe, case, out):
    done = subprocess.run([exe, "run", str(case), "--output-dir", str(out)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: {case} exited {done.returncode}: {done.stderr.strip()}")
    return json.loads((out / "summary.json").read_text())


def main():
    exe, case, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    if len(sys.argv) > 4:
        prm = json.loads((Path(sys.argv[4]) / "summary.json").read_text())
        if Path(prm["case"]).name != case.name or "--set" in prm["command_line"]:
            sys.exit(f"FAIL: {sys.argv[4]} is not a run of {case.name} as it is")
    else:
        prm = run(exe, case, out / "prm")
    out.mkdir(parents=True, exist_ok=True)
    json_case = out / (case.stem + ".json")
    json_case.write_text(as_json(prm["parameters"]) + "\n")
    js = run(exe, json_case, out / "json")
    found = list(differences(prm, js))
    print(f"{case.name}: {leaves(prm)} summary values compared, {len(found)} differ")
    for d in found:
        print("  " + d)
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
