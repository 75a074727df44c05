#!/usr/bin/env bash
# expect_error_mpi.sh MPIEXEC NP DEMBRIDGE OUTDIR REGEX SUBCOMMAND [args...]
# expect_error.sh under `MPIEXEC -np NP` (Open MPI or MPICH): exit code 1 (mpirun passes on the
# first failing rank's code; a signal or crash gives another), each rank's stderr (kept apart:
# the ranks' writes would interleave) exactly one line ended by a newline and matching REGEX, no
# summary.json and no staging folder in OUTDIR.
set -u
mpiexec=$1 np=$2 exe=$3 out=$4 regex=$5
shift 5
rm -rf "$out"
errdir=$(mktemp -d)
trap 'rm -rf "$errdir"' EXIT
"$mpiexec" -np "$np" --oversubscribe sh -c \
  'exec "$0" "$@" 2>"'"$errdir"'/rank.${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-x}}"' \
  "$exe" "$@" --output-dir "$out" >/dev/null 2>"$errdir/mpirun"
code=$?
echo "exit code: $code"
[ "$code" -eq 1 ] || { cat "$errdir"/*; echo "FAIL: exit code $code, expected 1 (a signal or crash is not a refusal)"; exit 1; }
for ((r = 0; r < np; ++r)); do
  f=$errdir/rank.$r
  [ -f "$f" ] || { echo "FAIL: no stderr of rank $r"; exit 1; }
  echo "rank $r: $(cat "$f")"
  [ "$(wc -l <"$f")" -eq 1 ] || { echo "FAIL: rank $r: stderr is not one line ended by a newline"; exit 1; }
  grep -qE -- "$regex" "$f" || { echo "FAIL: rank $r: stderr does not match /$regex/"; exit 1; }
done
for f in summary.json history.csv .partial; do
  [ ! -e "$out/$f" ] || { echo "FAIL: $out/$f was written"; exit 1; }
done
echo "ok"
