#!/usr/bin/env python3
"""A DEM run on several MPI ranks against the same case on one rank.

usage: compare_runs.py REF_DIR RUN_DIR [--rtol R] [--history-rtol H] [--history-skip COLUMN]...
                      [--cracks] KEY...

- every KEY of summary.json (a dotted path, e.g. energy.strain) agrees to R relative (default
  1e-10); a key that is a list or an object (a vector, a tensor, the energy terms) agrees to R
  of its largest entry;
- energy_balance_error, a small difference of large energies, agrees to R absolute (a static
  run has none: then neither run may have it);
- both runs wrote the same files (summary.json's output_files; a particle or bond snapshot
  written in pieces, particles_NNNNNN.pvtu over particles_NNNNNN_rR.vtu and bonds_NNNNNN.pvtu
  over bonds_NNNNNN_rR.vtu, counts as particles_NNNNNN.vtu, bonds_...) and history.csv has the same
  header and rows, each column within H (default 1e-6) of the column's largest magnitude (in a
  static run a group's force or displacement: of the run's largest force or displacement):
  history.csv holds ten digits, and the net force of a particle in near-equilibrium is a small
  difference of bond forces, so the time series of such runs differ between one and two
  threads on one rank by about 1e-9 of their scale already; H catches a lost particle, a group
  summed on one rank only or a row out of step. A static run's unbalanced_force_ratio (its
  solve's round-off, different for any two solvers) is at most 1e-9 in both runs instead.
  --history-skip leaves out a column that holds round-off only (a coupled run's tie gap, about
  1e-14 m; the transverse displacement of a beam loaded in its plane of symmetry, about
  1e-15 m), which no scale of its own can compare;
- with --cracks, cracks.csv holds the same cracks in the same order: particles, bond, mode (and
  a microstructure's bond class and grains) equal, time, position and energy within 1e-9 relative (ten printed digits), the axis (a unit
  vector) within 1e-9 absolute.
Prints one line per check; exit code 1 when one fails.
"""
import csv
import json
import re
import sys


def snapshots_as_one_rank(files):
    """The output files, a snapshot in pieces named as one rank names it (sorted)."""
    named = set()
    for f in files:
        if re.fullmatch(r"(particles|bonds)_\d+_r\d+\.vtu", f):
            continue
        named.add(re.sub(r"^((particles|bonds)_\d+)\.pvtu$", r"\1.vtu", f))
    return sorted(named)


def value(summary, key):
    for part in key.split("."):
        summary = summary[int(part)] if isinstance(summary, list) else summary[part]
    return summary


def flat(x):
    if isinstance(x, dict):
        return [v for k in sorted(x) for v in flat(x[k])]
    if isinstance(x, list):
        return [v for item in x for v in flat(item)]
    return [float(x)]


def main(argv):
    args = argv[1:]
    rtol, history_rtol = 1e-10, 1e-6
    keys, skipped = [], set()
    cracks = False
    while args:
        a = args.pop(0)
        if a == "--rtol":
            rtol = float(args.pop(0))
        elif a == "--history-rtol":
            history_rtol = float(args.pop(0))
        elif a == "--history-skip":
            skipped.add(args.pop(0))
        elif a == "--cracks":
            cracks = True
        else:
            keys.append(a)
    ref_dir, run_dir = keys[0], keys[1]
    keys = keys[2:]
    ref = json.load(open(ref_dir + "/summary.json"))
    run = json.load(open(run_dir + "/summary.json"))
    failed = 0

    def check(ok, text):
        nonlocal failed
        print(("ok: " if ok else "FAILED: ") + text)
        failed += 0 if ok else 1

    # a static run (no time steps) has no energy balance: then neither run may have one
    balance = ["energy_balance_error"] if "energy_balance_error" in ref else []
    check(bool(balance) == ("energy_balance_error" in run),
          "energy_balance_error in both runs or in neither")
    for key in keys + balance:
        a, b = flat(value(ref, key)), flat(value(run, key))
        scale = max(abs(v) for v in a) if key != "energy_balance_error" else 1.0
        worst = max(abs(x - y) for x, y in zip(a, b)) / (scale or 1.0)
        check(len(a) == len(b) and worst <= rtol,
              "%s: %s vs %s (difference %.3g%s)" % (key, value(ref, key), value(run, key), worst,
                                                   "" if key == "energy_balance_error"
                                                   else " relative"))
    check(sorted(ref["output_files"]) == snapshots_as_one_rank(run["output_files"]),
          "the same output files (%d)" % len(ref["output_files"]))

    def history(d):
        rows = list(csv.reader(open(d + "/history.csv")))
        return rows[0], [[float(x) for x in r] for r in rows[1:]]

    head_a, rows_a = history(ref_dir)
    head_b, rows_b = history(run_dir)
    check(head_a == head_b and len(rows_a) == len(rows_b),
          "history.csv: the same columns and %d rows" % len(rows_a))
    if head_a == head_b and len(rows_a) == len(rows_b):
        worst, where = 0.0, ""
        # a static run's net force on a free group, or a reaction across the load, is round-off:
        # its force (displacement) columns against the run's largest force (displacement)
        static = ref.get("stop_reason") == "static"

        def scale_of(j):
            columns = [j]
            kind = head_a[j][-3:-1]
            if static and kind in ("_u", "_f") and head_a[j][-1] in "xyz":
                columns = [k for k, n in enumerate(head_a) if n[-3:-1] == kind and n[-1] in "xyz"]
            return max(abs(r[k]) for r in rows_a for k in columns) or 1.0

        for j, name in enumerate(head_a):
            if (name == "energy_balance_error" or name in skipped
                    or (static and name == "unbalanced_force_ratio")):
                continue
            scale = scale_of(j)
            d = max(abs(x[j] - y[j]) for x, y in zip(rows_a, rows_b)) / scale
            if d > worst:
                worst, where = d, name
        check(worst <= history_rtol,
              "history.csv columns within %.3g of their scale (largest %.3g, %s)"
              % (history_rtol, worst, where))
        if static:
            j = head_a.index("unbalanced_force_ratio")
            largest = max(abs(r[j]) for r in rows_a + rows_b)
            check(largest <= 1e-9,
                  "history.csv: static equilibria, unbalanced_force_ratio at most 1e-9 (%.3g)"
                  % largest)
    if cracks:
        rows_a = list(csv.reader(open(ref_dir + "/cracks.csv")))
        rows_b = list(csv.reader(open(run_dir + "/cracks.csv")))
        head = rows_a[0]
        exact = [head.index(k) for k in ("mode", "particle_a", "particle_b", "bond", "class",
                                         "grains") if k in head]
        unit = [j for j, k in enumerate(head) if k.startswith("axis")]
        same = len(rows_a) == len(rows_b) and rows_a[0] == rows_b[0]
        for x, y in zip(rows_a[1:], rows_b[1:]):
            for j in range(len(head)):
                if j in exact:
                    same = same and x[j] == y[j]
                else:
                    a, b = float(x[j]), float(y[j])
                    scale = 1.0 if j in unit else max(abs(a), abs(b), 1e-300)
                    same = same and abs(a - b) <= 1e-9 * scale
        check(same, "cracks.csv: the same %d cracks" % (len(rows_a) - 1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
