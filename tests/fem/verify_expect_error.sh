#!/usr/bin/env bash
# verify_expect_error.sh DEMBRIDGE OUTDIR REGEX [verify args...]
# Bad input to `dembridge verify` must give: a non-zero exit, exactly one line on stderr that
# matches REGEX, and nothing written that looks like a result (no summary.json, comparison.csv
# or comparison.png, and no DEM summary: the inputs are checked before anything runs).
set -u
exe=$1 out=$2 regex=$3
shift 3
rm -rf "$out"
err=$("$exe" verify "$@" --output-dir "$out" 2>&1 >/dev/null)
code=$?
echo "exit code: $code"
echo "stderr: $err"
[ "$code" -ne 0 ] || { echo "FAIL: exit code 0"; exit 1; }
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: stderr is not one line"; exit 1; }
printf '%s\n' "$err" | grep -qE -- "$regex" || { echo "FAIL: stderr does not match /$regex/"; exit 1; }
for f in summary.json comparison.csv comparison.png dem/summary.json fem/summary.json; do
  [ ! -e "$out/$f" ] || { echo "FAIL: $out/$f was written"; exit 1; }
done
echo "ok"
