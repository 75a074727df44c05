#!/usr/bin/python3
"""The Python module's tutorial sweep (docs/python.md): Young's modulus and Poisson's ratio of
the HCP compression specimen (examples/compression_hcp.prm, r = 5 mm, parallel bonds) against
the bond stiffness ratio k_n / k_s, one dembridge.Model static solve per point, beside Wang and
Mora's E_x of the ideal HCP lattice (thesis eq. 2). Prints the numbers and draws the figure:

    PYTHONPATH=build/python /usr/bin/python3 scripts/study_sweep.py [--out docs/python_sweep.png]

The specimen is softer than the infinite lattice (its boundary layers are looser; the thesis
extrapolates to the ideal porosity, docs/specimens.md), so the two curves are compared in shape:
E falls as the shear stiffness falls (ratio up) in both.
"""
import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
from study import wang_mora_E  # noqa: E402


def sweep(case, ratios):
    """E and the mean of nu_xy, nu_xz at each stiffness ratio: a Model solved statically."""
    import dembridge
    rows = []
    for ratio in ratios:
        model = dembridge.Model(case, set={"Bonds/stiffness ratio": ratio})
        model.solve_static()
        figures = model.figures()
        rows.append(dict(ratio=ratio, youngs_modulus=figures["youngs_modulus"],
                         poisson_ratio_xy=figures["poisson_ratio_xy"],
                         poisson_ratio_xz=figures["poisson_ratio_xz"],
                         wang_mora_youngs_modulus=wang_mora_E(4e9, ratio)))
    return rows


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    k = [r["ratio"] for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(8, 3.2), dpi=80)
    left.plot(k, [r["youngs_modulus"] / 1e9 for r in rows], "o-", label="HCP specimen, r = 5 mm")
    left.plot(k, [r["wang_mora_youngs_modulus"] / 1e9 for r in rows], "--",
              label="ideal HCP lattice (Wang-Mora)")
    left.set_xlabel("bond stiffness ratio $k_n / k_s$")
    left.set_ylabel("$E$ (GPa)")
    left.legend(fontsize=8)
    right.plot(k, [r["poisson_ratio_xy"] for r in rows], "o-", label=r"$\nu_{xy}$")
    right.plot(k, [r["poisson_ratio_xz"] for r in rows], "s-", label=r"$\nu_{xz}$")
    right.set_xlabel("bond stiffness ratio $k_n / k_s$")
    right.set_ylabel("Poisson's ratio")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", default=str(ROOT / "examples" / "compression_hcp.prm"))
    ap.add_argument("--ratios", default="1,1.5,2,3,4.2,6,8", help="k_n / k_s values")
    ap.add_argument("--out", default="python_sweep.png", help="the figure (PNG)")
    a = ap.parse_args()
    ratios = [float(v) for v in a.ratios.split(",")]
    t0 = time.time()
    rows = sweep(a.case, ratios)
    seconds = time.time() - t0
    for r in rows:
        print(f"k_n/k_s = {r['ratio']:4.1f}: E = {r['youngs_modulus'] / 1e9:.4f} GPa "
              f"(Wang-Mora {r['wang_mora_youngs_modulus'] / 1e9:.4f}), "
              f"nu_xy = {r['poisson_ratio_xy']:.4f}, nu_xz = {r['poisson_ratio_xz']:.4f}")
    print(f"{len(rows)} static solves in {seconds:.1f} s")
    plot(rows, a.out)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
