#!/usr/bin/env python3
"""Checks the microstructure's outputs of a finished run (plain python3: json, csv).

    check_microstructure.py OUTPUT_DIR [COLUMN_AXIS]

- the last particles_*.vtu has point data grain_id, the last bonds_*.vtu cell data class and
  the field data class_names;
- cracks.csv has the columns class and grains; a crack of a grain_boundary bond is
  intergranular, of an intra_grain bond transgranular;
- summary.json: broken_bonds_per_class adds up to n_broken_bonds and counts what cracks.csv
  lists per class; broken_bonds_intergranular + broken_bonds_transgranular = n_broken_bonds
  and the intergranular ones are the rows of cracks.csv saying so; bonds_per_class adds up to
  n_bonds (when given);
- a crack of a basal bond is transgranular; with COLUMN_AXIS (x, y or z; a case whose basal
  bonds are smooth joints) there is at least one, and each lies in its grain's basal plane: its
  normal, the grain's c-axis, has no component along the column axis.
Prints what it compares; exit 1 on any failed check.
"""
import csv
import json
import sys
from collections import Counter
from pathlib import Path

out = Path(sys.argv[1])
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def last(pattern):
    files = sorted(out.glob(pattern))
    return files[-1].read_text(errors="replace") if files else ""


particles, bonds = last("particles_*.vtu"), last("bonds_*.vtu")
check('Name="grain_id"' in particles, "particles VTU has grain_id")
check('Name="class"' in bonds, "bonds VTU has class")
check('Name="class_names"' in bonds, "bonds VTU names the classes")

summary = json.loads((out / "summary.json").read_text())
with open(out / "cracks.csv", newline="") as f:
    rows = list(csv.DictReader(f))
check(len(rows) == summary["n_broken_bonds"],
      f"cracks.csv rows {len(rows)} = n_broken_bonds {summary['n_broken_bonds']}")
check(rows == [] or ("class" in rows[0] and "grains" in rows[0]), "cracks.csv has class, grains")
per_class = Counter(r["class"] for r in rows)
broken = summary["broken_bonds_per_class"]
print("broken bonds per class:", broken, "; cracks.csv:", dict(per_class))
check(sum(broken.values()) == summary["n_broken_bonds"], "broken_bonds_per_class adds up")
check(all(per_class.get(k, 0) == v for k, v in broken.items()),
      "cracks.csv per class = broken_bonds_per_class")
inter = sum(r["grains"] == "intergranular" for r in rows)
print("intergranular", summary["broken_bonds_intergranular"], "transgranular",
      summary["broken_bonds_transgranular"], "; cracks.csv intergranular", inter)
check(summary["broken_bonds_intergranular"] + summary["broken_bonds_transgranular"]
      == summary["n_broken_bonds"], "intergranular + transgranular = n_broken_bonds")
check(inter == summary["broken_bonds_intergranular"], "cracks.csv intergranular rows")
check(all(r["grains"] == "intergranular" for r in rows if r["class"] == "grain_boundary"),
      "grain_boundary cracks are intergranular")
check(all(r["grains"] == "transgranular" for r in rows if r["class"] == "intra_grain"),
      "intra_grain cracks are transgranular")
check(all(r["grains"] == "transgranular" for r in rows if r["class"] == "basal"),
      "basal cracks are transgranular")
if len(sys.argv) > 2:
    axis = "axis_" + sys.argv[2]
    basal = [r for r in rows if r["class"] == "basal"]
    along = max((abs(float(r[axis])) for r in basal), default=0.0)
    check(len(basal) > 0 and along < 1e-9,
          f"{len(basal)} basal cracks, normals along the column axis at most {along:.3g}")
if "n_bonds" in summary:
    check(sum(summary["bonds_per_class"].values()) == summary["n_bonds"],
          "bonds_per_class adds up to n_bonds")
sys.exit(1 if failures else 0)
