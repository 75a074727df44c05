#!/usr/bin/env bash
# expect_error.sh DEMBRIDGE OUTDIR REGEX SUBCOMMAND [args...]
# Bad input must give: exit code 1 (a refusal, not a crash: a signal gives 128 + its number, an
# uncaught exception 134), exactly one line on stderr, ended by a newline, matching REGEX, with
# no control characters (never a binary file's bytes), and nothing that looks like a finished
# result in OUTDIR (no summary.json, no complete-looking history.csv, no staging folder left
# behind; for `verify` also no comparison files and no DEM or FE summary: inputs are checked
# first); indeed no OUTDIR at all: a refused command creates nothing.
set -u
exe=$1 out=$2 regex=$3
shift 3
rm -rf "$out"
errfile=$(mktemp)
trap 'rm -f "$errfile"' EXIT
"$exe" "$@" --output-dir "$out" 2>"$errfile" >/dev/null
code=$?
err=$(cat "$errfile")
echo "exit code: $code"
echo "stderr: $err"
[ "$code" -eq 1 ] || { echo "FAIL: exit code $code, expected 1 (a signal or crash is not a refusal)"; exit 1; }
[ "$(wc -l <"$errfile")" -eq 1 ] || { echo "FAIL: stderr is not one line ended by a newline"; exit 1; }
[ "$(tail -c 1 "$errfile" | od -An -c | tr -d ' ')" = '\n' ] || { echo "FAIL: stderr does not end with a newline"; exit 1; }
printf '%s\n' "$err" | grep -qE -- "$regex" || { echo "FAIL: stderr does not match /$regex/"; exit 1; }
# never the bytes of a binary file: no control characters besides the final newline
! tr -d '\n' <"$errfile" | LC_ALL=C grep -q '[[:cntrl:]]' || { echo "FAIL: stderr holds control characters"; exit 1; }
for f in summary.json history.csv comparison.csv comparison.png dem/summary.json fem/summary.json .partial; do
  [ ! -e "$out/$f" ] || { echo "FAIL: $out/$f was written"; exit 1; }
done
[ ! -e "$out" ] || { echo "FAIL: the refused command left the folder $out"; ls -la "$out"; exit 1; }
echo "ok"
