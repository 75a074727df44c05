#!/usr/bin/env python3
"""Checks of the bond-failure specimens (issue 8) that compare runs or read cracks.csv.

    check_failure.py ratio A.json B.json KEY EXPECTED TOL   B[KEY] / A[KEY] = EXPECTED within TOL
                                                           (relative)
    check_failure.py change A.json B.json KEY TOL           |B[KEY] / A[KEY] - 1| < TOL
    check_failure.py differ A.json B.json KEY               the values differ (seed scatter)
    check_failure.py identical DIR_A DIR_B                  same summary.json (but for the run's
                                                           wall times and provenance), same
                                                           history.csv and cracks.csv, byte for byte
    check_failure.py notch_crack CRACKS.csv TIP_X TIP_Z LOAD_Z DIAMETER
                                                           the first broken bond within two
                                                           diameters of the notch tip; the crack
                                                           runs up toward the load point

Prints every number it judges; exit 1 on any failed check. Plain python3 (json, csv).
"""
import csv
import json
import math
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
    elif cmd == "differ":
        a, b, key = argv[2], argv[3], argv[4]
        va, vb = value(a, key), value(b, key)
        check(va != vb, f"{key}: {va:.6g} vs {vb:.6g} (difference {vb / va - 1:+.3%})")
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
