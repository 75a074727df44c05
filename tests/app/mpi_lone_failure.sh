#!/usr/bin/env bash
# mpi_lone_failure.sh MPIEXEC DEMBRIDGE CASE OUTDIR
# An error that one rank meets alone ends the whole job (app/mpi_job.h): with
# DEMBRIDGE_TEST_FAIL_ON_RANK=R, rank R of `MPIEXEC -np 2 dembridge run CASE` (an FE or coupled
# case) fails just before the run while the other rank goes on into the run's collective calls.
# For R = 0 and R = 1: the job ends with a non-zero exit code within 60 s (the failing rank waits
# MpiJob::fail_grace_seconds for the others, then aborts the job), and rank R's stderr names it.
set -u
mpiexec=$1 exe=$2 case=$3 out=$4
errdir=$(mktemp -d)
trap 'rm -rf "$errdir"' EXIT
for rank in 0 1; do
  rm -rf "$out" "$errdir"/*
  start=$(date +%s)
  DEMBRIDGE_TEST_FAIL_ON_RANK=$rank timeout -s KILL 120 "$mpiexec" -np 2 --oversubscribe sh -c \
    'exec "$0" "$@" 2>"'"$errdir"'/rank.${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-x}}"' \
    "$exe" run "$case" --output-dir "$out" >/dev/null 2>"$errdir/mpirun"
  code=$?
  seconds=$(($(date +%s) - start))
  echo "rank $rank fails alone: exit code $code after $seconds s; its stderr: $(cat "$errdir/rank.$rank" 2>/dev/null)"
  [ "$code" -ne 0 ] || { echo "FAIL: exit code 0"; exit 1; }
  [ "$seconds" -lt 60 ] || { echo "FAIL: the job took $seconds s to end"; exit 1; }
  grep -q "dembridge: error: rank $rank: .*DEMBRIDGE_TEST_FAIL_ON_RANK: this rank fails alone" \
    "$errdir/rank.$rank" || { echo "FAIL: rank $rank did not report its error"; exit 1; }
done
echo "ok"
