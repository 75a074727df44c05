"""check_provenance.py OUTDIR [Section/key=value ...]: summary.json records where the results
come from: the version and git commit of the binary, the command line, host, threads,
start time, the complete effective parameter set (every section of print-parameters), the list of
the files it wrote (each present), and parameters.prm beside it. Each Section/key=value (a --set
of the run) must be in the command line, in summary.json's parameters and in parameters.prm.
Plain python3 (no numpy)."""
import json
import os
import re
import sys

out = sys.argv[1]
expected = [a.split("=", 1) for a in sys.argv[2:]]
summary = json.load(open(os.path.join(out, "summary.json")))
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


check(re.fullmatch(r"\d+\.\d+\.\d+", summary.get("version", "")) is not None, "version x.y.z")
check(re.fullmatch(r"([0-9a-f]{40}(-dirty)?|unknown)", summary.get("git_commit", "")) is not None,
      "git_commit: 40 hex digits (+ -dirty) or unknown")
words = summary.get("command_line", [])
check(isinstance(words, list) and len(words) >= 3 and words[1] == "run", "command_line: [exe, run, ...]")
check(bool(summary.get("host")), "host")
check(isinstance(summary.get("threads"), int) and summary["threads"] >= 1, "threads >= 1")
check(re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", summary.get("started_at", "")) is not None,
      "started_at in UTC")
parameters = summary.get("parameters", {})
check(parameters.get("Mode") in ("dem", "fem", "coupled"), "parameters: Mode")
for section in ("Particles", "Bonds", "Simulation", "Output", "FEM"):
    check(isinstance(parameters.get(section), dict) and len(parameters[section]) > 0,
          "parameters: section " + section)
files = summary.get("output_files", [])
check("summary.json" in files and "parameters.prm" in files, "output_files lists summary.json, parameters.prm")
missing = [f for f in files if not os.path.isfile(os.path.join(out, f))]
check(not missing, "every listed file exists " + str(missing))
prm = open(os.path.join(out, "parameters.prm")).read()
check("set Mode" in prm and "subsection Simulation" in prm, "parameters.prm holds the parameter set")


def prm_entries(text):
    """Section/key -> value of a parameter file (subsection ... end, set key = value)."""
    entries, path = {}, []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if line.startswith("subsection "):
            path.append(line[len("subsection "):].strip())
        elif line == "end":
            path.pop()
        elif line.startswith("set ") and "=" in line:
            key, value = line[4:].split("=", 1)
            entries["/".join(path + [key.strip()])] = value.strip()
    return entries


in_prm = prm_entries(prm)
for path, value in expected:
    check(path + "=" + value in words, "command_line holds --set " + path + "=" + value)
    node = parameters
    for part in path.split("/"):
        node = node.get(part, {}) if isinstance(node, dict) else {}
    check(node == value, "summary.json parameters: %s = %s (found %r)" % (path, value, node))
    check(in_prm.get(path) == value, "parameters.prm: %s = %s (found %r)" % (path, value, in_prm.get(path)))
estimate = summary.get("memory_estimate")
if parameters.get("Mode") != "fem":
    check(isinstance(estimate, dict) and estimate.get("bytes", 0) > 0, "memory_estimate")
sys.exit(1 if failures else 0)
