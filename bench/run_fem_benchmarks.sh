#!/usr/bin/env bash
# FEM speed benchmark: static solve of the cantilever (bench/fem_bench.cc) with Q1 and
# Q2 at 0.1, 1 and 5 million DoFs, on 1 and 2 MPI ranks; one JSON per run in bench/results/
# (fem_q<degree>_<dofs>_np<ranks>.json). A run whose estimated memory exceeds 80 % of the
# memory available now is skipped and recorded as skipped (the estimate is per DoF, from the
# 0.1 M runs: about 6 kB/DoF for Q1 and 11 kB/DoF for Q2, all ranks together).
#   bench/run_fem_benchmarks.sh [BUILD_DIR] [SIZES...]       default: build 1e5 1e6 5e6
# Runs under `nice -n 10`; timings on a shared machine are noisy (see bench/RESULTS_FEM.md).
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
shift || true
sizes=${*:-1e5 1e6 5e6}
exe="$build/bench/fem-bench"
[ -x "$exe" ] || { echo "build first: cmake --build $build --target fem-bench" >&2; exit 1; }
mkdir -p "$here/bench/results"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
for dofs in $sizes; do
  for degree in 1 2; do
    for ranks in 1 2; do
      out="$here/bench/results/fem_q${degree}_${dofs}_np${ranks}.json"
      per_dof=$([ "$degree" = 1 ] && echo 6000 || echo 11000)
      avail=$(awk '/MemAvailable/ {print $2 * 1024}' /proc/meminfo)
      msg=$(python3 -c "
need, avail = float('$dofs') * $per_dof, float('$avail')
if need > 0.8 * avail:
    print('skipped: estimated %.0f GB > 80 %% of the %.0f GB available' % (need / 1e9, avail / 1e9))")
      if [ -n "$msg" ]; then
        echo "Q$degree, $dofs DoFs, $ranks rank(s): $msg"
        printf '{"degree": %s, "target_dofs": %s, "n_ranks": %s, "skipped": "%s"}\n' \
          "$degree" "$dofs" "$ranks" "$msg" > "$out"
        continue
      fi
      echo "Q$degree, $dofs DoFs, $ranks rank(s) ..."
      if [ "$ranks" = 1 ]; then
        nice -n 10 "$exe" --degree "$degree" --dofs "$dofs" --json "$out" | tail -1
      else
        nice -n 10 mpirun -np "$ranks" --oversubscribe "$exe" --degree "$degree" --dofs "$dofs" \
          --json "$out" | tail -1
      fi
    done
  done
done
