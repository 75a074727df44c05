#!/usr/bin/env bash
# output_folder.sh DEMBRIDGE CASE OUTDIR
# A results folder never shows a failed or killed run's files as current (app/output_folder.h):
#  1. a run fills OUTDIR (many snapshots); a user's own file sits beside the results;
#  2. a rerun that fails inside the run (time step above the stability limit, found while
#     building) exits 1 and leaves every file as it was, and no staging folder;
#  3. a rerun killed with SIGKILL while it writes snapshots leaves every visible file as it was;
#  4. a successful rerun with fewer snapshots replaces the results: the first run's extra
#     snapshots are gone, the user's file is kept, and summary.json's output_files lists exactly
#     the files of the folder that are not the user's.
set -u
exe=$1 case=$2 out=$3
fail() { echo "FAIL: $*"; exit 1; }
files() { (cd "$out" && find . -path ./.partial -prune -o -type f -print | sort | xargs md5sum); }
rm -rf "$out"
mkdir -p "$out"
echo "my notes" >"$out/notes.txt"

"$exe" run "$case" --output-dir "$out" --set "Output/snapshot interval=2000" >/dev/null ||
  fail "the first run failed"
before=$(files)
n_first=$(ls "$out"/particles_*.vtu | wc -l)
[ "$n_first" -gt 10 ] || fail "expected more than 10 snapshots, got $n_first"

"$exe" run "$case" --output-dir "$out" --set "Simulation/time step=1" >/dev/null 2>&1
code=$?
[ "$code" -eq 1 ] || fail "the failing rerun exited with $code, expected 1"
[ "$(files)" = "$before" ] || fail "a failed rerun changed the folder"
[ ! -e "$out/.partial" ] || fail "a failed rerun left its staging folder"
echo "ok   failed rerun: folder unchanged"

"$exe" run "$case" --output-dir "$out" --set "Simulation/quasi-static speed=0" \
  --set "Simulation/end time=1e4" --set "Output/snapshot interval=100" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do # until it has written snapshots (up to 60 s on a loaded machine)
  [ -e "$out/.partial/particles_000003.vtu" ] && break
  sleep 0.1
done
[ -e "$out/.partial/particles_000003.vtu" ] || { kill -9 $pid; fail "the long rerun wrote no snapshot"; }
kill -9 $pid
wait $pid 2>/dev/null
[ "$(files)" = "$before" ] || fail "a killed rerun changed the folder"
echo "ok   killed rerun: folder unchanged"

"$exe" run "$case" --output-dir "$out" >/dev/null || fail "the second run failed"
[ ! -e "$out/.partial" ] || fail "a successful run left its staging folder"
[ "$(cat "$out/notes.txt")" = "my notes" ] || fail "the user's file was touched"
n_second=$(ls "$out"/particles_*.vtu | wc -l)
[ "$n_second" -lt "$n_first" ] || fail "expected fewer snapshots: $n_second vs $n_first"
listed=$(python3 -c 'import json, sys; print("\n".join(sorted(json.load(open(sys.argv[1]))["output_files"])))' "$out/summary.json")
present=$(cd "$out" && ls -1 | grep -vx notes.txt | sort)
[ "$listed" = "$present" ] || fail "the folder's files differ from output_files: $(diff <(echo "$listed") <(echo "$present") | tr '\n' ' ')"
echo "ok   successful rerun: $n_first -> $n_second snapshots, nothing stale, notes.txt kept"
