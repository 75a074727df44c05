#!/usr/bin/env bash
# expect_warning.sh DEMBRIDGE OUTDIR REGEX SUBCOMMAND [args...]
# A case that runs but cannot show what it asks: exit code 0, a "dembridge: warning:" line on
# stderr matching REGEX, and the same warning recorded in summary.json's "warnings".
set -u
exe=$1 out=$2 regex=$3
shift 3
rm -rf "$out"
err=$("$exe" "$@" --output-dir "$out" 2>&1 >/dev/null)
code=$?
echo "exit code: $code"
echo "stderr: $err"
[ "$code" -eq 0 ] || { echo "FAIL: exit code $code, expected 0 (a warning, not a refusal)"; exit 1; }
printf '%s\n' "$err" | grep -E -- "^dembridge: warning: " | grep -qE -- "$regex" ||
  { echo "FAIL: no warning line matches /$regex/"; exit 1; }
grep -qE -- "$regex" "$out/summary.json" || { echo "FAIL: summary.json does not record it"; exit 1; }
echo "ok"
