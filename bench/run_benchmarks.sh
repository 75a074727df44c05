#!/usr/bin/env bash
# DEM core benchmark, JSON in bench/results/. In one run, on one machine:
#  - dembridge-bench on the 26,004-sphere HCP lattice (r = 2.5 mm) and on a random packing of
#    the same box (seed 1, contact radius multiplier 1.04), 1 and 2 threads, dashpots on
#    (xi = 0.05): the full model and the plain parallel-bond loop (bench/plain_bond_loop.h)
#    alternate in rounds in the same process; then dashpots off on the lattice;
#  - the same lattice with r = 0.74 mm (1,059,194 spheres, 6.25 M bonds): a few steps, for
#    particle-steps per second and bytes per particle at a million particles;
#  - YADE (bench/peers/yade_hcp_bench.py, bonds_only) on the 26,004-sphere lattice, 1 and 2
#    threads, right after (skipped when yade is not installed). For the ratio to YADE, whose
#    single runs swing with the host independently of ours, bench/yade_alternating.py
#    alternates the two round by round (about 5 minutes; bench/results/yade_alternating_*.json).
# Run on an otherwise idle machine: the figures are wall-clock throughput (the JSON also holds
# rates per CPU-second). BUILD=dir picks the build (default build/).
# --damage: also the damage benchmark (bench/damage_bench.py: compression to failure of 23,746
# spheres and contacts against YADE, 1 and 2 threads; about 15 minutes, bench/RESULTS_DAMAGE.md).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD:-$here/build}
exe="$build/bench/dembridge-bench"
[ -x "$exe" ] || { echo "build first: bash scripts/setup.sh" >&2; exit 1; }
out="$here/bench/results"
mkdir -p "$out"
rcp="$build/bench/rcp_r2.5mm_seed1.csv" # the random packing, generated once and reused
"$exe" --packing hcp --threads 1 2 --steps 100 --rounds 7 --json "$out/dem_hcp_r2.5mm.json"
"$exe" --packing random --particles-file "$rcp" --threads 1 2 --steps 100 --rounds 7 \
  --json "$out/dem_random_r2.5mm.json"
"$exe" --packing hcp --threads 1 2 --damping 0 --steps 100 --rounds 5 \
  --json "$out/dem_hcp_r2.5mm_no_dashpots.json"
"$exe" --packing hcp --radius 0.74e-3 --threads 1 2 --steps 5 --rounds 2 \
  --json "$out/dem_hcp_r0.74mm.json"
if command -v yade > /dev/null; then
  for threads in 1 2; do
    yade -j"$threads" -n -x "$here/bench/peers/yade_hcp_bench.py" --mode bonds_only --steps 200 \
      --timing-steps 0 --json-out "$here/bench/peers/yade_results.json" | grep '^{' \
      > "$out/yade_hcp_r2.5mm_threads$threads.json"
  done
else
  # why: the table would otherwise show an earlier run's YADE rows beside this run's as if new
  echo "run_benchmarks.sh: yade not installed (apt-get install --no-install-recommends yade):" \
    "the YADE rows below are an earlier run's (bench/results/yade_*.json)" >&2
fi
/usr/bin/python3 "$here/bench/dem_results_table.py" "$out"
if [ "${1:-}" = "--damage" ]; then
  for threads in 1 2; do
    python3 "$here/bench/damage_bench.py" --build "$build" --threads "$threads"
  done
fi
