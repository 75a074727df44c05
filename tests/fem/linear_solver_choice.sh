#!/bin/sh
# Simulation/static linear solver in a run (app/runs/dem_run.cc): the thesis compression test on
# HCP (examples/compression_hcp.prm) with gamg and with cg gives the same Young's modulus to
# 1e-6, and summary.json names the solver each used.
#   linear_solver_choice.sh DEMBRIDGE CHECK_SUMMARY CASE.prm OUTPUT_DIR
set -e
app=$1
check=$2
case=$3
out=$4
rm -rf "$out"
mkdir -p "$out"
for solver in cg gamg; do
  "$app" run "$case" --set "Simulation/static linear solver=$solver" \
    --output-dir "$out/$solver" > "$out/$solver.log"
done
grep -q '"method": "PETSc CG+GAMG"' "$out/gamg/summary.json"
grep -q '"method": "ConjugateGradient+Jacobi"' "$out/cg/summary.json"
"$check" "$out/gamg/summary.json" youngs_modulus near_in "$out/cg/summary.json" 1e-6
