#!/usr/bin/env python3
"""Checks a columnar specimen's strength anisotropy from two finished runs (plain python3).

    check_along_across.py ACROSS_DIR ALONG_DIR LOW HIGH

ACROSS_DIR and ALONG_DIR are the same case loaded across and along the columns. Asserts:
- along/across of summary.json's peak_stress in [LOW, HIGH] (Timco & Weeks 2010: about 3 in
  tension, about 4 in compression);
- across the columns the crack runs between the columns: at least 90 % of the broken bonds
  intergranular (broken_bonds_intergranular / n_broken_bonds);
- along the columns it has to cut through them: a larger transgranular share than across.
Prints what it compares; exit 1 on any failed check.
"""
import json
import sys
from pathlib import Path

across_dir, along_dir = Path(sys.argv[1]), Path(sys.argv[2])
low, high = float(sys.argv[3]), float(sys.argv[4])
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def summary(folder):
    return json.loads((folder / "summary.json").read_text())


across, along = summary(across_dir), summary(along_dir)
ratio = along["peak_stress"] / across["peak_stress"]
check(low <= ratio <= high,
      f"along/across peak stress {along['peak_stress']:.6g} / {across['peak_stress']:.6g} Pa = "
      f"{ratio:.4f} in [{low}, {high}]")


def transgranular_share(s):
    return s["broken_bonds_transgranular"] / max(s["n_broken_bonds"], 1)


check(across["n_broken_bonds"] > 0 and transgranular_share(across) <= 0.1,
      f"across: {across['broken_bonds_intergranular']} of {across['n_broken_bonds']} broken bonds "
      f"intergranular (at least 90 %)")
check(transgranular_share(along) > transgranular_share(across),
      f"transgranular share along {transgranular_share(along):.3f} > across "
      f"{transgranular_share(across):.3f}")
sys.exit(1 if failures else 0)
