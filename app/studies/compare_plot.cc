// The matplotlib script `dembridge compare` writes beside comparison.csv and runs
// (compare_plot.h).
#include "app/studies/compare_plot.h"

namespace dembridge::app
{
const char* const compare_plot_script = R"PY(
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

# then one NAME=PATH per crack panel (a run's cracks.csv)
comparison_csv, png, title, axis_h, axis_v, v_lo, v_hi = sys.argv[1:8]
panels = [a.split("=", 1) for a in sys.argv[8:]]
h, v = int(axis_h), int(axis_v)
v_lo, v_hi = float(v_lo), float(v_hi)
curves = {}
with open(comparison_csv) as f:
    for row in csv.DictReader(f):
        curves.setdefault(row["model"], ([], []))
        curves[row["model"]][0].append(1e3 * float(row["deflection"]))
        curves[row["model"]][1].append(float(row["load"]))

def cracks(path):
    xs, ys, modes = [], [], []
    try:
        with open(path) as f:
            for row in csv.DictReader(f):
                p = [float(row["x"]), float(row["y"]), float(row["z"])]
                xs.append(p[h]); ys.append(p[v]); modes.append(row["mode"])
    except FileNotFoundError:
        pass
    return xs, ys, modes

fig, axes = plt.subplots(1, 1 + len(panels), figsize=(5 * (1 + len(panels)), 4.5))
style = {"coupled": "C0-", "coupled_fixed": "C2-.", "full_dem": "C1--", "full_fem": "k:"}
for name, (d, F) in curves.items():
    axes[0].plot(d, F, style.get(name, "-"), label=name.replace("_", " "))
axes[0].set_xlabel("deflection (mm)"); axes[0].set_ylabel("load (N)")
axes[0].legend(); axes[0].grid(alpha=0.3)
sets = [cracks(path) for _, path in panels]
every_x = [x for s in sets for x in s[0]]
for ax, (xs, ys, modes), (name, _) in zip(axes[1:], sets, panels):
    name = name.replace("_", " ")
    for mode, colour in (("tension", "C3"), ("shear", "C2")):
        sel = [k for k, m in enumerate(modes) if m == mode]
        ax.scatter([xs[k] for k in sel], [ys[k] for k in sel], s=6, c=colour, label=mode)
    ax.set_title(f"{name}: {len(xs)} broken bonds")
    ax.set_xlabel("xyz"[h] + " (m)"); ax.set_ylabel("xyz"[v] + " (m)")
    # the same window in both: the whole depth, the span of every crack point
    if every_x:
        pad = 0.5 * (v_hi - v_lo)
        ax.set_xlim(min(every_x) - pad, max(every_x) + pad)
    ax.set_ylim(v_lo, v_hi)
    ax.set_aspect("equal"); ax.grid(alpha=0.3)
    if xs:
        ax.legend(loc="upper right")
fig.suptitle(title)
fig.tight_layout()
fig.savefig(png, dpi=110)
)PY";
} // namespace dembridge::app
