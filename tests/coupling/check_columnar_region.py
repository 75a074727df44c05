#!/usr/bin/env python3
"""A coupled run whose particle region is columnar ice takes the region's own tensor.

usage: check_columnar_region.py COUPLED_SUMMARY ELASTICITY_JSON E_TOL

- the continuum's tensor (summary.json's continuum_tensor) is the one `dembridge elasticity`
  measures on the region's packing with its grains and grain-boundary bonds (elasticity.json's
  stiffness_tensor), entry by entry to 1e-12 of its largest entry: the same packing, the same
  six static solves;
- the specimen's Young's modulus along x (the coupled compression across the columns) is the
  region's E_x = 1 / S_11 (elasticity.json's compliance) within E_TOL relative: continuum and
  particles are then one material, as a specimen of the region's packing alone would be.
Prints one line per check; exit code 1 when one fails.
"""
import json
import sys


def main(argv):
    summary = json.load(open(argv[1]))
    elasticity = json.load(open(argv[2]))
    tol = float(argv[3])
    failed = 0
    C = [v for row in summary["continuum_tensor"] for v in row]
    M = [v for row in elasticity["stiffness_tensor"] for v in row]
    scale = max(abs(v) for v in M)
    worst = max(abs(a - b) for a, b in zip(C, M)) / scale
    ok = len(C) == len(M) == 36 and worst <= 1e-12
    print(("ok: " if ok else "FAILED: ") +
          "the continuum's tensor is the region's measured one (difference %.3g of C_max)" % worst)
    failed += 0 if ok else 1
    e_x = 1.0 / elasticity["compliance"][0][0]
    e = summary["youngs_modulus"]
    ok = abs(e / e_x - 1) <= tol
    print(("ok: " if ok else "FAILED: ") +
          "E = %.6g Pa against the region's E_x = %.6g Pa (%+.2f %%, tolerance %.1f %%)"
          % (e, e_x, 100 * (e / e_x - 1), 100 * tol))
    failed += 0 if ok else 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
