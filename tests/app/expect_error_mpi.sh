#!/usr/bin/env bash
# expect_error_mpi.sh MPIEXEC NP DEMBRIDGE OUTDIR REGEX SUBCOMMAND [args...]
# expect_error.sh under `MPIEXEC -np NP` (Open MPI or MPICH; app/mpi_job.h): exit code 1
# (mpirun passes on the ranks' code; a signal or crash gives another), rank 0's stderr exactly
# one line ended by a newline and matching REGEX, every other rank's stderr empty (the ranks'
# streams are kept apart; mpirun's own notice about the exit code is not the program's), within
# 60 s, and OUTDIR not created.
set -u
mpiexec=$1 np=$2 exe=$3 out=$4 regex=$5
shift 5
rm -rf "$out"
errdir=$(mktemp -d)
trap 'rm -rf "$errdir"' EXIT
start=$(date +%s)
"$mpiexec" -np "$np" --oversubscribe sh -c \
  'exec "$0" "$@" 2>"'"$errdir"'/rank.${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-x}}"' \
  "$exe" "$@" --output-dir "$out" >/dev/null 2>"$errdir/mpirun"
code=$?
seconds=$(($(date +%s) - start))
echo "exit code: $code, $seconds s"
[ "$code" -eq 1 ] || { cat "$errdir"/*; echo "FAIL: exit code $code, expected 1 (a signal or crash is not a refusal)"; exit 1; }
[ "$seconds" -lt 60 ] || { echo "FAIL: the refusal took $seconds s"; exit 1; }
for ((r = 0; r < np; ++r)); do
  f=$errdir/rank.$r
  [ -f "$f" ] || { echo "FAIL: no stderr of rank $r"; exit 1; }
  echo "rank $r: $(cat "$f")"
  if [ "$r" -eq 0 ]; then
    [ "$(wc -l <"$f")" -eq 1 ] && [ "$(tail -c 1 "$f" | od -An -c | tr -d ' ')" = '\n' ] ||
      { echo "FAIL: rank 0: stderr is not one line ended by a newline"; exit 1; }
    grep -qE -- "$regex" "$f" || { echo "FAIL: rank 0: stderr does not match /$regex/"; exit 1; }
  else
    [ ! -s "$f" ] || { echo "FAIL: rank $r printed (rank 0 alone prints the line)"; exit 1; }
  fi
done
[ ! -e "$out" ] || { echo "FAIL: the refused command created $out"; ls -la "$out"; exit 1; }
echo "ok"
