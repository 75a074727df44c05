#!/usr/bin/env bash
# expect_error.sh DEMBRIDGE CASE OUTDIR REGEX [dembridge args...]
# Bad input must give: a non-zero exit, exactly one line on stderr matching REGEX, and no
# summary.json (nothing that looks like a finished result).
set -u
exe=$1 case=$2 out=$3 regex=$4
shift 4
rm -rf "$out"
err=$("$exe" run "$case" --output-dir "$out" "$@" 2>&1 >/dev/null)
code=$?
echo "exit code: $code"
echo "stderr: $err"
[ "$code" -ne 0 ] || { echo "FAIL: exit code 0"; exit 1; }
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: stderr is not one line"; exit 1; }
printf '%s\n' "$err" | grep -qE -- "$regex" || { echo "FAIL: stderr does not match /$regex/"; exit 1; }
[ ! -e "$out/summary.json" ] || { echo "FAIL: summary.json was written"; exit 1; }
[ ! -e "$out/history.csv" ] || { echo "FAIL: a complete-looking history.csv was written"; exit 1; }
echo "ok"
