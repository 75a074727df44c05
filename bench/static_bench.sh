#!/bin/sh
# Quasi-static benchmarks: random close packing time against the sphere count (packing-bench) and the
# quasi-static solver's linear solve, Jacobi CG beside CG + GAMG in the same run (static-bench),
# on the thesis specimen. JSON into bench/results/, tables by bench/static_bench_table.py
# (bench/RESULTS_STATIC.md).
#   sh bench/static_bench.sh BUILD_DIR [hcp radii] [random radii] [packing radii]
# Defaults: HCP 2.5, 1.575, 1.0 mm (26 k, 107 k, 432 k particles); random 2.5, 1.575 mm (24 k,
# 95 k spheres); packing 5, 2.5, 1.575, 1.0 mm (2.9 k to 370 k spheres). One point of 1 M
# particles needs 16 GiB for GAMG (measured) and about 16 min of packing on one thread: add it
# where the machine has them (HCP: 0.00074; packing: 0.00072).
set -e
build=${1:?usage: static_bench.sh BUILD_DIR [hcp radii] [random radii] [packing radii]}
hcp=${2:-"0.0025 0.001575 0.001"}
random=${3:-"0.0025 0.001575"}
packing=${4:-"0.005 0.0025 0.001575 0.001"}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/results
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# shellcheck disable=SC2086 # the radii lists split into arguments
"$build/bench/packing-bench" --radii $packing --json "$out/packing_random.json" > /dev/null
# shellcheck disable=SC2086
"$build/bench/static-bench" --packing hcp --radii $hcp --json "$out/static_hcp.json" > /dev/null
# shellcheck disable=SC2086
"$build/bench/static-bench" --packing random --radii $random \
  --json "$out/static_random.json" > /dev/null
python3 "$here/static_bench_table.py" "$out"
