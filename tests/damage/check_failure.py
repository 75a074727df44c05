#!/usr/bin/env python3
"""Checks of the bond-failure specimens that compare runs or read cracks.csv.

    check_failure.py ratio A.json B.json KEY EXPECTED TOL   B[KEY] / A[KEY] = EXPECTED within TOL
                                                           (relative)
    check_failure.py change A.json B.json KEY TOL           |B[KEY] / A[KEY] - 1| < TOL
    check_failure.py first_break_change A.csv B.csv COLUMN TOL
                                                           |B / A - 1| < TOL for |COLUMN| of
                                                           history.csv on the first record with a
                                                           broken bond (the load at first failure)
    check_failure.py differ A.json B.json KEY               the values differ (seed scatter)
    check_failure.py scatter KEY A.json B.json...           the values over runs (seeds): mean,
                                                           standard deviation, range; all differ
    check_failure.py identical DIR_A DIR_B                  same summary.json (but for the run's
                                                           wall times and provenance), same
                                                           history.csv and cracks.csv, byte for byte
    check_failure.py softening HISTORY.csv STRESS STRAIN
                                                           a peak inside the run, then a softening
                                                           branch: at least 5 records between 95 %
                                                           and 25 % of the peak at rising strain,
                                                           and a final stress below 20 % of it
    check_failure.py with_value A.json KEY PARAM -- COMMAND...
                                                           runs COMMAND with --set PARAM=A[KEY]
                                                           added (a run that takes a number from
                                                           another run's summary), its exit code
    check_failure.py printed_figures RUN.out SUMMARY.json KEY...
                                                           the figures `run` printed at its end
                                                           hold each KEY ("  KEY  VALUE [unit]"),
                                                           its value the summary's (to the 8
                                                           printed digits; lists entry by entry)
    check_failure.py notch_crack CRACKS.csv TIP_X TIP_Z LOAD_Z DIAMETER
                                                           the first broken bond within two
                                                           diameters of the notch tip; the crack
                                                           runs up toward the load point

Prints every number it judges; exit 1 on any failed check. Plain python3 (json, csv).
"""
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

failures = []


def check(ok, text):
    print(("ok   " if ok else "FAIL ") + text)
    if not ok:
        failures.append(text)


def value(path, key):
    node = json.load(open(path))
    for part in key.split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    return float(node)


# Keys that describe the run, not its result: wall times, throughput, memory, provenance.
RUN_KEYS = ("seconds", "per_second", "memory", "started", "finished", "command", "host",
            "version", "provenance", "output_dir")


def physics(node):
    if isinstance(node, dict):
        return {k: physics(v) for k, v in node.items()
                if not any(word in k for word in RUN_KEYS)}
    if isinstance(node, list):
        return [physics(v) for v in node]
    return node


def main(argv):
    cmd = argv[1]
    if cmd == "ratio":
        a, b, key, expected, tol = argv[2], argv[3], argv[4], float(argv[5]), float(argv[6])
        va, vb = value(a, key), value(b, key)
        r = vb / va
        check(abs(r / expected - 1) < tol,
              f"{key}: {vb:.6g} / {va:.6g} = {r:.5f}, expected {expected} within {tol:.2%} "
              f"(error {r / expected - 1:+.3%})")
    elif cmd == "change":
        a, b, key, tol = argv[2], argv[3], argv[4], float(argv[5])
        va, vb = value(a, key), value(b, key)
        check(abs(vb / va - 1) < tol,
              f"{key}: {va:.6g} -> {vb:.6g}, change {vb / va - 1:+.3%} (limit {tol:.2%})")
    elif cmd == "first_break_change":
        a, b, column, tol = argv[2], argv[3], argv[4], float(argv[5])

        def first_break(path):
            for row in csv.DictReader(open(path)):
                if float(row["n_broken_bonds"]) > 0:
                    return abs(float(row[column])), float(row["time"])
            raise SystemExit(f"FAIL {path}: no record with a broken bond")

        (va, ta), (vb, tb) = first_break(a), first_break(b)
        check(abs(vb / va - 1) < tol,
              f"|{column}| at the first break: {va:.6g} (t = {ta:.6g} s) -> {vb:.6g} "
              f"(t = {tb:.6g} s), change {vb / va - 1:+.3%} (limit {tol:.2%})")
    elif cmd == "differ":
        a, b, key = argv[2], argv[3], argv[4]
        va, vb = value(a, key), value(b, key)
        check(va != vb, f"{key}: {va:.6g} vs {vb:.6g} (difference {vb / va - 1:+.3%})")
    elif cmd == "scatter":
        key, paths = argv[2], argv[3:]
        vs = [value(p, key) for p in paths]
        mean = sum(vs) / len(vs)
        std = math.sqrt(sum((v - mean) ** 2 for v in vs) / (len(vs) - 1))
        print(f"{key} over {len(vs)} runs: " + ", ".join(f"{v:.6g}" for v in vs))
        check(len(set(vs)) == len(vs),
              f"{key}: mean {mean:.6g}, standard deviation {std:.4g} ({std / mean:.2%}), "
              f"range {min(vs):.6g}-{max(vs):.6g} ({(max(vs) - min(vs)) / mean:.2%}); all differ")
    elif cmd == "identical":
        da, db = Path(argv[2]), Path(argv[3])
        sa = physics(json.load(open(da / "summary.json")))
        sb = physics(json.load(open(db / "summary.json")))
        diff = sorted(k for k in set(sa) | set(sb) if sa.get(k) != sb.get(k))
        check(not diff, f"summary.json equal but for run times and provenance"
              + (f" (differ: {', '.join(diff)})" if diff else f" ({len(sa)} keys)"))
        for name in ("history.csv", "cracks.csv"):
            same = (da / name).read_bytes() == (db / name).read_bytes()
            check(same, f"{name} byte for byte ({(da / name).stat().st_size} bytes)")
    elif cmd == "printed_figures":
        out, summary, keys = argv[2], json.load(open(argv[3])), argv[4:]
        text = open(out).read()
        print(text)
        table = text.split("figures of this run (summary.json):\n")[-1]
        printed = {}
        for line in table.splitlines():
            if not line.startswith("  "):
                break
            words = line.split(None, 1)
            printed[words[0]] = words[1].strip() if len(words) > 1 else ""
        for key in keys:
            node = summary
            for part in key.split("."):
                node = node[int(part)] if isinstance(node, list) else node.get(part)
            if key not in printed:
                check(False, f"{key}: not printed (summary.json: {node})")
                continue
            # the value, less a unit word at its end
            words = printed[key].replace(",", " ").split()
            numbers = [float(w) for w in words if w[0].isdigit() or w[0] in "+-."]
            expected = node if isinstance(node, list) else [node]
            same = len(numbers) == len(expected) and all(
                abs(a - float(b)) <= 1e-7 * abs(float(b)) for a, b in zip(numbers, expected))
            check(same, f"{key}: printed {printed[key]}, summary.json {node}")
    elif cmd == "softening":
        path, stress_key, strain_key = argv[2], argv[3], argv[4]
        rows = list(csv.DictReader(open(path)))
        stress = [float(r[stress_key]) for r in rows]
        strain = [float(r[strain_key]) for r in rows]
        k = max(range(len(stress)), key=lambda n: stress[n])
        peak = stress[k]
        check(0 < k < len(rows) - 1 and peak > 0,
              f"peak {peak:.6g} Pa at strain {strain[k]:.4g}, record {k} of {len(rows)}")
        # the branch: records after the peak between 95 % and 25 % of it, the strain rising
        branch = [n for n in range(k + 1, len(rows)) if 0.25 * peak <= stress[n] <= 0.95 * peak]
        rising = all(strain[b] > strain[a] for a, b in zip(range(k, len(rows) - 1),
                                                           range(k + 1, len(rows))))
        span = (strain[branch[-1]] - strain[k]) if branch else 0.0
        check(len(branch) >= 5 and rising,
              f"softening branch: {len(branch)} records from 95 % to 25 % of the peak over a "
              f"strain of {span:.3g} ({span / strain[k]:.1%} of the strain at the peak; "
              f"limit 5 records), strain rising: {rising}")
        check(stress[-1] < 0.2 * peak, f"final stress {stress[-1]:.4g} Pa = "
              f"{stress[-1] / peak:.1%} of the peak (limit 20 %)")
    elif cmd == "with_value":
        a, key, param = argv[2], argv[3], argv[4]
        command = argv[argv.index("--") + 1:]
        v = value(a, key)
        print(f"{param} = {v!r} ({key} of {a})", flush=True)
        return subprocess.call(command + ["--set", f"{param}={v!r}"])
    elif cmd == "notch_crack":
        path = argv[2]
        tip_x, tip_z, load_z, d = (float(v) for v in argv[3:7])
        rows = list(csv.DictReader(open(path)))
        check(len(rows) > 0, f"{len(rows)} broken bonds")
        if rows:
            first = rows[0]
            dist = math.hypot(float(first["x"]) - tip_x, float(first["z"]) - tip_z)
            check(dist <= 2 * d, f"first broken bond at x = {float(first['x']):.4f}, z = "
                  f"{float(first['z']):.4f} m, {dist / d:.2f} diameters from the notch tip "
                  f"(limit 2)")
            band = [r for r in rows if abs(float(r["x"]) - tip_x) <= 2.5 * d]
            share = len(band) / len(rows)
            check(share >= 0.7, f"{share:.1%} of the broken bonds within 2.5 diameters of the "
                  f"notch plane (limit 70 %)")
            top = max(float(r["z"]) for r in band) if band else tip_z
            reach = (top - tip_z) / (load_z - tip_z)
            check(reach >= 0.5, f"the crack reaches z = {top:.4f} m, {reach:.0%} of the way from "
                  f"the notch tip to the load point (limit 50 %)")
            # it grows upward: the later half of the band's breaks lies higher than the earlier
            half = len(band) // 2
            if half > 0:
                early = sum(float(r["z"]) for r in band[:half]) / half
                late = sum(float(r["z"]) for r in band[half:]) / (len(band) - half)
                check(late > early, f"mean height of the first half of the breaks {early:.4f} m, "
                      f"of the second half {late:.4f} m: it runs toward the load point")
    else:
        raise SystemExit(f"unknown check '{cmd}'")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
