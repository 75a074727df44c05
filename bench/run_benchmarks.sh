#!/usr/bin/env bash
# Runs the DEM core benchmark with 1 and 2 threads and collects the JSON figures in
# bench/results/. Run on an otherwise idle machine: the numbers are wall-clock throughput.
# --damage: also the damage benchmark (bench/damage_bench.py: compression to failure of 23,746
# spheres and contacts against YADE, 1 and 2 threads; about 15 minutes, bench/RESULTS_DAMAGE.md).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe="$here/build/bench/dembridge-bench"
[ -x "$exe" ] || { echo "build first: bash scripts/setup.sh" >&2; exit 1; }
mkdir -p "$here/bench/results"
for threads in 1 2; do
  for damping in 0.05 0; do
    out="$here/bench/results/hcp_r2.5mm_threads${threads}_damping${damping}.json"
    "$exe" --threads "$threads" --damping "$damping" --steps 500 --json "$out"
  done
done
if [ "${1:-}" = "--damage" ]; then
  for threads in 1 2; do
    python3 "$here/bench/damage_bench.py" --build "$here/build" --threads "$threads"
  done
fi
