#!/usr/bin/env bash
# expect_error.sh DEMBRIDGE OUTDIR REGEX SUBCOMMAND [args...]
# Bad input must give: exit code 1 (a refusal, not a crash: a signal gives 128 + its number, an
# uncaught exception 134), exactly one line on stderr matching REGEX, and nothing that looks
# like a finished result in OUTDIR (no summary.json, no complete-looking history.csv, no
# staging folder left behind; for `verify` also no comparison files and no DEM or FE summary:
# inputs are checked first).
set -u
exe=$1 out=$2 regex=$3
shift 3
rm -rf "$out"
err=$("$exe" "$@" --output-dir "$out" 2>&1 >/dev/null)
code=$?
echo "exit code: $code"
echo "stderr: $err"
[ "$code" -eq 1 ] || { echo "FAIL: exit code $code, expected 1 (a signal or crash is not a refusal)"; exit 1; }
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: stderr is not one line"; exit 1; }
printf '%s\n' "$err" | grep -qE -- "$regex" || { echo "FAIL: stderr does not match /$regex/"; exit 1; }
for f in summary.json history.csv comparison.csv comparison.png dem/summary.json fem/summary.json .partial; do
  [ ! -e "$out/$f" ] || { echo "FAIL: $out/$f was written"; exit 1; }
done
echo "ok"
