#!/usr/bin/env python3
"""`dembridge elasticity --interface-estimate` on a columnar case: what elasticity.json reports.

usage: check_interface_estimate.py ELASTICITY_JSON RATIO_TOL

- S_v (boundary_area_per_volume, 1/m), B_N and B_T (normal_compliance, shear_compliance, m/Pa)
  and the grain-free E are positive;
- youngs_modulus_estimate is 1 / (1/E + S_v (3 B_N + B_T) / 8) of the reported figures, and
  youngs_modulus_across the mean of 1/S_11 and 1/S_22 of the reported compliance (the column
  axis z), measured_over_estimate their ratio, each to 1e-12 (the file agrees with itself);
- measured over estimate within RATIO_TOL of 1 (docs/columnar_ice.md: the particle boundaries are
  a few per cent more compliant than the estimate on random packings).
Prints one line per check; exit code 1 when one fails.
"""
import json
import sys


def main(argv):
    e = json.load(open(argv[1]))
    tol = float(argv[2])
    c = e["columns"]
    failed = 0

    def check(ok, text):
        nonlocal failed
        print(("ok: " if ok else "FAILED: ") + text)
        failed += 0 if ok else 1

    s_v, b_n, b_t = c["boundary_area_per_volume"], c["normal_compliance"], c["shear_compliance"]
    e0 = c["youngs_modulus_without_grains"]
    check(s_v > 0 and b_n > 0 and b_t > 0 and e0 > 0,
          "S_v %.6g 1/m, B_N %.6g m/Pa, B_T %.6g m/Pa, E %.6g Pa positive" % (s_v, b_n, b_t, e0))
    estimate = 1.0 / (1.0 / e0 + s_v * (3 * b_n + b_t) / 8)
    check(abs(c["youngs_modulus_estimate"] / estimate - 1) <= 1e-12,
          "estimate %.9g Pa = 1/(1/E + S_v (3 B_N + B_T)/8) = %.9g Pa"
          % (c["youngs_modulus_estimate"], estimate))
    S = e["compliance"]
    across = 0.5 * (1 / S[0][0] + 1 / S[1][1])
    check(abs(c["youngs_modulus_across"] / across - 1) <= 1e-12,
          "E across %.9g Pa = the mean of 1/S_11 and 1/S_22 = %.9g Pa"
          % (c["youngs_modulus_across"], across))
    ratio = c["youngs_modulus_across"] / c["youngs_modulus_estimate"]
    check(abs(c["measured_over_estimate"] / ratio - 1) <= 1e-12,
          "measured_over_estimate %.6g = E across / estimate" % c["measured_over_estimate"])
    check(abs(ratio - 1) <= tol, "measured / estimate %.4f within %.2f of 1" % (ratio, tol))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
