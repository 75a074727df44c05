#!/usr/bin/python3
"""Checks of the specimen study on the results.csv that scripts/study.py writes.

    check_study.py hcp_wang_mora RESULTS.csv     E(porosity) of HCP specimens -> Wang-Mora
    check_study.py random_trend RESULTS.csv      seed spread of E, nu shrinks as r falls
    check_study.py solvers RESULTS.csv           static vs explicit, energy balance
    check_study.py less A.json KEY_A B.json KEY_B   value A < value B (two summaries)

Prints every number it judges; exit 1 on any failed check (each tolerance is stated where it
is checked and in tests/specimens/CMakeLists.txt).
"""
import csv
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
import study  # noqa: E402  (wang_mora_E, HCP_IDEAL_POROSITY)

failures = []


def check(ok, text):
    print(("ok   " if ok else "FAIL ") + text)
    if not ok:
        failures.append(text)


def rows_of(path, **match):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        if all(r.get(k) == v for k, v in match.items()):
            out.append(r)
    return out


def num(r, key):
    v = r.get(key, "")
    if v == "":
        raise SystemExit(f"FAIL run {r.get('run')}: no '{key}' in results.csv")
    return float(v)


def hcp_wang_mora(path, fit_max_mm=5.0, tol=0.01):
    """Thesis section 5.1, Fig. 30b: E of finite HCP specimens rises linearly as their porosity
    falls towards the ideal lattice's; the linear fit E(p) extrapolated to p = 1 - pi/(3 sqrt 2)
    = 0.25952 is the ideal lattice's modulus, Wang and Mora's eq. 2 (5.843 GPa for the PBM with
    k̄_n = E_b/(2 r), k̄_n/k̄_s = 4.2). Fit over the specimens with r <= fit_max_mm (at least 20
    spheres across the 0.1 m section, where the looser boundary layer is thin compared with the
    specimen and E(p) is linear); tolerance tol relative."""
    rows = rows_of(path, packing="hcp", test="compression", model="pbm", solver="static")
    pts = sorted((num(r, "specimen_porosity"), num(r, "youngs_modulus"), num(r, "radius_mm"),
                  int(num(r, "specimen_particles"))) for r in rows)
    print(f"{'r (mm)':>7} {'spheres':>8} {'porosity':>9} {'E (GPa)':>9}")
    for p, e, rad, n in sorted(pts, key=lambda t: t[2]):
        print(f"{rad:7.2f} {n:8d} {p:9.4f} {e / 1e9:9.4f}")
    check(len(pts) >= 4, f"{len(pts)} HCP specimens (need 4 or more)")
    # Fig. 30: E rises as the porosity falls, over every radius run (strictly monotone)
    es = [e for _, e, _, _ in pts]
    check(all(a > b for a, b in zip(es, es[1:])),
          "E falls strictly as the porosity rises, over all " + str(len(pts)) + " specimens")
    fit = [(p, e) for p, e, rad, _ in pts if rad <= fit_max_mm + 1e-9]
    check(len(fit) >= 3, f"{len(fit)} specimens with r <= {fit_max_mm} mm in the fit (need 3)")
    P = np.array([p for p, _ in fit])
    E = np.array([e for _, e in fit])
    slope, icpt = np.polyfit(P, E, 1)
    resid = E - (slope * P + icpt)
    p0 = study.HCP_IDEAL_POROSITY
    e_ext = slope * p0 + icpt
    e_wm = study.wang_mora_E()
    err = (e_ext - e_wm) / e_wm
    print(f"linear fit over r <= {fit_max_mm} mm: E = {icpt / 1e9:.4f} GPa + "
          f"({slope / 1e9:.4f} GPa) p, largest residual {np.abs(resid).max() / 1e9:.4f} GPa")
    print(f"extrapolated to the ideal HCP porosity {p0:.5f}: E = {e_ext / 1e9:.4f} GPa")
    print(f"Wang and Mora (2008), thesis eq. 2: E = {e_wm / 1e9:.4f} GPa "
          f"(thesis: 5.843; its own extrapolation 5.855, +0.21 %)")
    check(slope < 0, "E rises as the porosity falls (slope < 0)")
    check(abs(err) <= tol, f"extrapolated E within {tol * 100:g} % of Wang-Mora "
                           f"(error {err * 100:+.3f} %)")
    # for information: the fit over every radius run (the thesis' 2.5-12.5 mm)
    if len(pts) > len(fit):
        s2, i2 = np.polyfit([p for p, *_ in pts], es, 1)
        print(f"(for information, not checked) fit over all {len(pts)} radii: "
              f"{(s2 * p0 + i2) / 1e9:.4f} GPa ({((s2 * p0 + i2) / e_wm - 1) * 100:+.2f} %); the "
              "specimens with only 4-5 spheres across bend the line")


def random_trend(path):
    """Thesis Figs. 29 and 31: random packings' E and Poisson's ratios vary between packings
    (seeds) and the spread shrinks as the radius falls; E rises and the porosity and nu fall as
    r falls (Figs. 29a, 29c, 31). Monotone over all radii run; spreads compared between the
    smallest and the largest radius."""
    rows = rows_of(path, packing="random", test="compression", model="pbm", solver="static")
    by_r = {}
    for r in rows:
        by_r.setdefault(num(r, "radius_mm"), []).append(r)
    radii = sorted(by_r)
    stats = {}
    print(f"{'r (mm)':>7} {'seeds':>5} {'porosity':>9} {'E mean':>8} {'E sd':>7} "
          f"{'nu_xy':>6} {'sd':>6} {'nu_xz':>6} {'sd':>6} {'|nu_xy-nu_xz|':>13}")
    for rad in radii:
        g = by_r[rad]
        E = np.array([num(r, "youngs_modulus") for r in g]) / 1e9
        nxy = np.array([num(r, "poisson_ratio_xy") for r in g])
        nxz = np.array([num(r, "poisson_ratio_xz") for r in g])
        por = np.array([num(r, "specimen_porosity") for r in g])
        nu = np.concatenate([nxy, nxz])
        stats[rad] = dict(n=len(g), E=E.mean(), sE=E.std(ddof=1) / E.mean(), nu=nu.mean(),
                          snu=nu.std(ddof=1), aniso=np.abs(nxy - nxz).mean(), p=por.mean())
        print(f"{rad:7.2f} {len(g):5d} {por.mean():9.4f} {E.mean():8.4f} {E.std(ddof=1):7.4f} "
              f"{nxy.mean():6.3f} {nxy.std(ddof=1):6.3f} {nxz.mean():6.3f} {nxz.std(ddof=1):6.3f} "
              f"{np.abs(nxy - nxz).mean():13.4f}")
    check(len(radii) >= 3 and all(stats[r]["n"] >= 3 for r in radii),
          f"{len(radii)} radii with 3 or more seeds each")
    small, large = radii[0], radii[-1]
    # Fig. 29a: mean E rises as r falls (monotone over the radii run)
    means = [stats[r]["E"] for r in radii]
    check(all(a > b for a, b in zip(means, means[1:])),
          "mean E rises as r falls: " + ", ".join(f"{m:.3f}" for m in means) + " GPa")
    # Fig. 29c: the porosity falls with r
    pm = [stats[r]["p"] for r in radii]
    check(all(a < b for a, b in zip(pm, pm[1:])),
          "mean porosity falls as r falls: " + ", ".join(f"{v:.4f}" for v in pm))
    # Fig. 31: the Poisson's ratios fall as r falls (towards just below 0.2)
    nus = [stats[r]["nu"] for r in radii]
    check(all(a < b for a, b in zip(nus, nus[1:])),
          "mean nu (xy and xz pooled) falls as r falls: " + ", ".join(f"{v:.4f}" for v in nus))
    # Figs. 29, 31: the seed-to-seed spread shrinks from the largest to the smallest radius
    check(stats[small]["sE"] < stats[large]["sE"],
          f"relative sd of E: {stats[small]['sE'] * 100:.2f} % at r = {small:g} mm < "
          f"{stats[large]['sE'] * 100:.2f} % at r = {large:g} mm")
    check(stats[small]["snu"] < stats[large]["snu"],
          f"sd of nu (xy and xz pooled): {stats[small]['snu']:.4f} at r = {small:g} mm < "
          f"{stats[large]['snu']:.4f} at r = {large:g} mm")
    # Fig. 31: the difference between nu_xy and nu_xz shrinks (more isotropic)
    check(stats[small]["aniso"] < stats[large]["aniso"],
          f"mean |nu_xy - nu_xz|: {stats[small]['aniso']:.4f} at r = {small:g} mm < "
          f"{stats[large]['aniso']:.4f} at r = {large:g} mm")


def solvers(path, tol=1e-3, energy_tol=0.01):
    """The static solver against the explicit one on the same specimens: E, nu_xy,
    nu_xz (uniaxial) and the midspan deflection and E_f (bending) within tol relative; every
    explicit run's energy balance error (thesis eq. 53) below energy_tol."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    key = lambda r: (r["packing"], r["radius_mm"], r["seed"], r["model"], r["test"])
    static = {key(r): r for r in rows if r["solver"] == "static"}
    pairs = [(static[key(r)], r) for r in rows if r["solver"] == "explicit" and key(r) in static]
    check(len(pairs) >= 1, f"{len(pairs)} static/explicit pairs")
    for s, x in pairs:
        name = x["run"].replace("_explicit", "")
        keys = (["youngs_modulus", "poisson_ratio_xy", "poisson_ratio_xz"]
                if x["test"] != "bending" else ["midspan_deflection", "flexural_modulus"])
        for k in keys:
            a, b = num(s, k), num(x, k)
            d = (b - a) / a
            check(abs(d) <= tol, f"{name}: {k} static {a:.6g}, explicit {b:.6g} "
                                 f"({d * 100:+.4f} %, limit {tol * 100:g} %)")
        ebe = num(x, "energy_balance_error")
        check(ebe < energy_tol, f"{name}: explicit energy_balance_error {ebe:.2e} < {energy_tol}")
        print(f"     {name}: explicit {num(x, 'steps'):.0f} steps, {num(x, 'wall_seconds'):.1f} s; "
              f"static {num(s, 'wall_seconds'):.2f} s")


def less(a_path, a_key, b_path, b_key):
    a = json.loads(Path(a_path).read_text())[a_key]
    b = json.loads(Path(b_path).read_text())[b_key]
    check(a < b, f"{a_key} = {a:.6g} ({a_path}) < {b_key} = {b:.6g} ({b_path})")


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    cmd, args = sys.argv[1], sys.argv[2:]
    {"hcp_wang_mora": hcp_wang_mora, "random_trend": random_trend, "solvers": solvers,
     "less": less}[cmd](*args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
