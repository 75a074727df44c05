#!/usr/bin/env python3
"""Markdown table of the FE benchmark JSON files (bench/results/fem_q*_*_np*.json)."""
import glob, json, os, sys

here = os.path.dirname(os.path.abspath(__file__))
rows = []
for f in glob.glob(os.path.join(here, "results", "fem_q*_np*.json")):
    rows.append(json.load(open(f)))
rows.sort(key=lambda j: (float(j.get("n_dofs", j.get("target_dofs", 0))), j["degree"], j["n_ranks"]))
print("| DoFs | Q | ranks | cells | setup (s) | assembly (s) | AMG setup (s) | CG (s) | CG its | s / (it · M DoFs) | peak memory, all ranks (GB) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for j in rows:
    if "skipped" in j:
        print("| %.0e | %d | %d | | | | | | | | %s |" % (float(j["target_dofs"]), j["degree"], j["n_ranks"], j["skipped"]))
        continue
    c = j["cells"]
    per = j["cg_seconds"] / j["cg_iterations"] / (j["n_dofs"] / 1e6)
    print("| %s | %d | %d | %d·%d·%d | %.1f | %.1f | %.1f | %.1f | %d | %.2f | %.2f |" % (
        format(j["n_dofs"], ",").replace(",", " "), j["degree"], j["n_ranks"], c[0], c[1], c[2],
        j["setup_seconds"], j["assembly_seconds"], j["amg_setup_seconds"], j["cg_seconds"],
        j["cg_iterations"], per, j["peak_rss_bytes_all_ranks"] / 1e9))
