"""Plots of the specimen study in the style of the thesis' Figures 29-35, drawn from the
results rows that scripts/study.py collects (separate so the runner stays readable)."""
import math
import os
from pathlib import Path

import numpy as np

from study import HCP_IDEAL_POROSITY, MODELS, PACKINGS, RCP_MIN_POROSITY, wang_mora_E

PLOTS = ("youngs_modulus.png", "poisson_ratio.png", "flexural_modulus.png",
         "flexural_vs_axial.png")
COLORS = {"cubic": "tab:blue", "hcp": "tab:gray", "random": "tab:orange"}
LABELS = {"cubic": "uniform (cubic)", "hcp": "HCP", "random": "RCP"}
MARKERS = {"pbm": "o", "tbbm": "s"}


def fnum(v):
    try:
        f = float(v)
        return f if math.isfinite(f) else None
    except (TypeError, ValueError):
        return None


def label_radius_panel(ax, packing, ylabel):
    """Title, axes, grid and legend of one packing's panel over the particle radius."""
    ax.set_title(LABELS[packing])
    ax.set_xlabel("particle radius $r_p$ (mm)")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def plots(out, rows, solver_pref="static"):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out)
    made = []

    def sel(test, packing=None, model=None):
        got = [r for r in rows if r["test"] == test and (packing is None or r["packing"] == packing)
               and (model is None or r["model"] == model)]
        # one solver per point: the preferred one where both ran
        keyf = lambda r: (r["packing"], r["radius_mm"], r.get("seed"), r["model"], r["test"])
        best = {}
        for r in got:
            k = keyf(r)
            if k not in best or r["solver"] == solver_pref:
                best[k] = r
        return list(best.values())

    uni = [r for r in rows if r["test"] in ("compression", "tension")]
    packings = [p for p in PACKINGS if any(r["packing"] == p for r in rows)]
    models = [m for m in MODELS if any(r["model"] == m for r in rows)]

    def save(fig, name):
        fig.tight_layout()
        path = out / name
        fig.savefig(str(path) + ".tmp.png", dpi=110)
        os.replace(str(path) + ".tmp.png", path)
        plt.close(fig)
        made.append(path)

    def axial(test_rows):
        return [(fnum(r["radius_mm"]), fnum(r.get("specimen_porosity")), fnum(r.get("youngs_modulus")),
                 fnum(r.get("specimen_particles")), r) for r in test_rows
                if fnum(r.get("youngs_modulus")) is not None]

    # Figs. 29/30/32: E vs radius, number of particles, porosity (compression; tension hollow)
    if uni:
        fig, axs = plt.subplots(1, 3, figsize=(15, 4.5))
        for p in packings:
            for m in models:
                for test, fill in (("compression", True), ("tension", False)):
                    pts = axial(sel(test, p, m))
                    if not pts:
                        continue
                    kw = dict(color=COLORS[p], marker=MARKERS[m], linestyle="none",
                              markerfacecolor=COLORS[p] if fill else "none", alpha=0.85)
                    axs[0].plot([a[0] for a in pts], [a[2] / 1e9 for a in pts], **kw)
                    axs[1].plot([a[3] for a in pts], [a[2] / 1e9 for a in pts], **kw)
                    axs[2].plot([a[1] for a in pts], [a[2] / 1e9 for a in pts], **kw)
            # linear fits in radius and porosity over all seeds (Figs. 29a, 29c, 30a, 30b)
            pts = axial(sel("compression", p, "pbm") or sel("compression", p))
            if p != "cubic" and len({a[0] for a in pts}) >= 2:
                rr = np.array([a[0] for a in pts]); pp = np.array([a[1] for a in pts])
                ee = np.array([a[2] for a in pts]) / 1e9
                c = np.polyfit(rr, ee, 1)
                xs = np.linspace(0, rr.max(), 50)
                axs[0].plot(xs, np.polyval(c, xs), color=COLORS[p], lw=0.8)
                c = np.polyfit(pp, ee, 1)
                target = HCP_IDEAL_POROSITY if p == "hcp" else RCP_MIN_POROSITY
                xs = np.linspace(min(target, pp.min()), pp.max(), 50)
                axs[2].plot(xs, np.polyval(c, xs), color=COLORS[p], lw=0.8)
                axs[2].plot([target], [np.polyval(c, target)], marker="*", color=COLORS[p],
                            ms=12, linestyle="none",
                            label=f"{LABELS[p]} fit at p = {target:.4f}: "
                                  f"{np.polyval(c, target):.3f} GPa")
        if any(r["packing"] == "hcp" for r in uni):
            for ax in (axs[0], axs[2]):
                ax.axhline(wang_mora_E() / 1e9, color="k", ls=":", lw=0.8,
                           label="Wang & Mora (2008), eq. 2: 5.843 GPa" if ax is axs[2] else None)
        from matplotlib.lines import Line2D
        proxies = [Line2D([], [], color=COLORS[p], lw=2, label=LABELS[p]) for p in packings]
        proxies += [Line2D([], [], color="k", marker=MARKERS[m], linestyle="none",
                           label=m.upper()) for m in models]
        if any(r["test"] == "tension" for r in uni):
            proxies.append(Line2D([], [], color="k", marker="o", markerfacecolor="none",
                                  linestyle="none", label="open: tension"))
        axs[0].legend(handles=proxies, fontsize=7)
        axs[0].set_xlabel("particle radius $r_p$ (mm)")
        axs[1].set_xlabel("number of particles $N_p$")
        axs[1].set_xscale("log")
        axs[2].set_xlabel("porosity $p$")
        for ax in axs:
            ax.set_ylabel("Young's modulus $E_x$ (GPa)")
            ax.grid(alpha=0.3)
        axs[2].legend(fontsize=7)
        fig.suptitle("Young's modulus of the specimens (thesis Figs. 29, 30, 32, 33)")
        save(fig, "youngs_modulus.png")

        # Figs. 30c-d, 31: Poisson's ratios vs radius
        fig, axs = plt.subplots(1, len(packings), figsize=(5 * len(packings), 4.2), squeeze=False)
        for ax, p in zip(axs[0], packings):
            for m in models:
                pts = [r for r in sel("compression", p, m) if fnum(r.get("poisson_ratio_xy")) is not None]
                for key, col in (("poisson_ratio_xy", "tab:red"), ("poisson_ratio_xz", "tab:green")):
                    ax.plot([fnum(r["radius_mm"]) for r in pts], [fnum(r[key]) for r in pts],
                            marker=MARKERS[m], color=col, linestyle="none",
                            label=f"$\\nu_{{{key[-2:]}}}$ {m.upper()}")
            label_radius_panel(ax, p, "Poisson's ratio")
        fig.suptitle("Poisson's ratios from the uniaxial compression tests (thesis Figs. 30, 31)")
        save(fig, "poisson_ratio.png")

    bend = [r for r in rows if r["test"] == "bending" and fnum(r.get("flexural_modulus")) is not None]
    if bend:
        # Fig. 35: flexural modulus vs radius, three evaluations
        fig, axs = plt.subplots(1, len(packings), figsize=(5 * len(packings), 4.2), squeeze=False)
        for ax, p in zip(axs[0], packings):
            for m in models:
                pts = [r for r in sel("bending", p, m) if fnum(r.get("flexural_modulus")) is not None]
                for key, col, lab in (("flexural_modulus_point_load", "tab:blue", "point load (eq. 67)"),
                                      ("flexural_modulus", "tab:orange", "distributed load (eq. 69)"),
                                      ("flexural_modulus_bottom", "tab:green", "bottom deflection, DL")):
                    v = [(fnum(r["radius_mm"]), fnum(r.get(key))) for r in pts if fnum(r.get(key)) is not None]
                    ax.plot([a for a, _ in v], [b / 1e9 for _, b in v], marker=MARKERS[m], color=col,
                            linestyle="none", label=f"{lab} {m.upper()}")
            label_radius_panel(ax, p, "flexural modulus $E_f$ (GPa)")
        fig.suptitle("Three-point bending: flexural modulus (thesis Fig. 35)")
        save(fig, "flexural_modulus.png")

        # Fig. 34: flexural vs axial modulus of the same specimens
        fig, ax = plt.subplots(figsize=(5.5, 5))
        comp = {(r["packing"], r["radius_mm"], r.get("seed"), r["model"]): r for r in sel("compression")}
        hi = 0
        for r in sel("bending"):
            c = comp.get((r["packing"], r["radius_mm"], r.get("seed"), r["model"]))
            if c is None or fnum(c.get("youngs_modulus")) is None or fnum(r.get("flexural_modulus")) is None:
                continue
            e, ef = fnum(c["youngs_modulus"]) / 1e9, fnum(r["flexural_modulus"]) / 1e9
            hi = max(hi, e, ef)
            ax.plot(e, ef, marker=MARKERS[r["model"]], color=COLORS[r["packing"]], linestyle="none")
        for p in packings:
            ax.plot([], [], marker="o", color=COLORS[p], linestyle="none", label=LABELS[p])
        ax.plot([0, hi * 1.05], [0, hi * 1.05], "k:", lw=0.8, label="$E_f = E_x$")
        ax.set_xlabel("axial Young's modulus $E_x$ (GPa, compression)")
        ax.set_ylabel("flexural modulus $E_f$ (GPa, eq. 69)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("Axial vs flexural modulus (thesis Fig. 34)")
        save(fig, "flexural_vs_axial.png")
    return made
