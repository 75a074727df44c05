#!/usr/bin/env bash
# output_folder_lock.sh DEMBRIDGE CASE OUTDIR
# The output folder is locked while a run uses it, and a refused run leaves nothing behind
# (app/output_folder.h). CASE is the explicit cantilever (examples/cantilever.prm).
#  1. a second run into a folder a run is using is refused at once (exit code 1, one line naming
#     the folder) while the first is held mid-run (SIGSTOP); the first then finishes complete:
#     summary.json lists exactly the folder's files, no staging folder;
#  2. the lock of a killed run (SIGKILL) dies with it: the next run into its folder succeeds;
#  3. a run killed after its first checkpoint: a --resume refused (its .partial/history.csv.part
#     moved away) leaves every staged file as it was; with the file back --resume succeeds;
#  4. --output-dir '' is refused, and no output/ appears in the current folder;
#  5. a run refused while it builds the model (after the folder was locked), into a folder two
#     levels below one that does not exist, leaves no folder.
set -u
exe=$1 case=$2 out=$3
fail() { echo "FAIL: $*"; exit 1; }
staged() { (cd "$1" && find . -type f | sort | xargs md5sum); }
rm -rf "$out"
mkdir -p "$out"
cd "$out" || exit 1
long=(--set "Simulation/quasi-static speed=0" --set "Simulation/end time=1e4"
      --set "Output/snapshot interval=100")

# 1. a second run into a folder in use
"$exe" run "$case" --output-dir first --set "Simulation/quasi-static speed=0" \
  --set "Simulation/end time=3" --set "Output/snapshot interval=2000" >first.out 2>&1 &
pid=$!
for _ in $(seq 600); do # until it writes snapshots (up to 60 s on a loaded machine)
  [ -e first/.partial/particles_000002.vtu ] && break
  sleep 0.1
done
kill -STOP $pid
[ -e first/.partial/particles_000002.vtu ] || { kill -9 $pid; fail "the first run wrote no snapshot"; }
start=$(date +%s.%N)
"$exe" run "$case" --output-dir first >second.out 2>second.err
code=$?
seconds=$(echo "$(date +%s.%N) - $start" | bc)
kill -CONT $pid
echo "second run: exit code $code after $seconds s: $(cat second.err)"
[ "$code" -eq 1 ] || { kill -9 $pid; fail "the second run exited with $code, expected 1"; }
[ "$(wc -l <second.err)" -eq 1 ] || { kill -9 $pid; fail "the second run's stderr is not one line"; }
grep -qF "$PWD/first: another dembridge run is using this output folder" second.err ||
  { kill -9 $pid; fail "the refusal does not name the folder"; }
awk "BEGIN { exit !($seconds < 30) }" || { kill -9 $pid; fail "the refusal took $seconds s"; }
wait $pid || { cat first.out; fail "the first run failed after the second was refused"; }
[ ! -e first/.partial ] || fail "the first run left its staging folder"
listed=$(python3 -c 'import json, sys; print("\n".join(sorted(json.load(open(sys.argv[1]))["output_files"])))' first/summary.json)
present=$(cd first && ls -1 | sort)
[ "$listed" = "$present" ] || fail "the first run's files differ from its output_files"
echo "ok   second run refused at once; the first run complete ($(echo "$present" | wc -l) files)"

# 2. a killed run's lock
"$exe" run "$case" --output-dir killed "${long[@]}" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do
  [ -e killed/.partial/particles_000003.vtu ] && break
  sleep 0.1
done
kill -9 $pid
wait $pid 2>/dev/null
[ -e killed/.partial ] || fail "the killed run left no staging folder (killed too early?)"
"$exe" run "$case" --output-dir killed >/dev/null || fail "a run after a killed one was refused"
[ -s killed/summary.json ] || fail "no summary.json after the killed run's successor"
echo "ok   the next run after a killed one succeeds"

# 3. a refused --resume keeps .partial; a --resume then succeeds
DEMBRIDGE_TEST_KILL_AFTER_STEP=15000 "$exe" run "$case" --output-dir resumed \
  --set "Output/checkpoint interval=0.5" >/dev/null 2>&1
[ -e resumed/checkpoint.h5 ] && [ -e resumed/.partial/history.csv.part ] ||
  fail "the run was not killed after its first checkpoint"
before=$(staged resumed/.partial)
mv resumed/.partial/history.csv.part history.csv.part
after_move=$(staged resumed/.partial)
"$exe" run "$case" --resume resumed >/dev/null 2>resume.err
code=$?
echo "refused resume: exit code $code: $(cat resume.err)"
[ "$code" -eq 1 ] || fail "the resume without history.csv.part exited with $code, expected 1"
# every staged file still there, unchanged (the resume's history file, opened for appending
# before the refusal, may appear empty where it was moved away)
now=$(staged resumed/.partial 2>/dev/null)
while read -r line; do
  grep -qxF -- "$line" <<<"$now" || fail "the refused resume changed or removed ${line##* }"
done <<<"$after_move"
[ "$(grep -vxF -f <(echo "$after_move") <<<"$now" | grep -v ' ./history.csv.part$')" = "" ] ||
  fail "the refused resume added files to .partial"
mv history.csv.part resumed/.partial/history.csv.part
[ "$(staged resumed/.partial)" = "$before" ] || fail ".partial differs after the file came back"
"$exe" run "$case" --resume resumed >/dev/null || fail "the resume failed"
[ -s resumed/summary.json ] && [ ! -e resumed/checkpoint.h5 ] || fail "the resumed run is incomplete"
echo "ok   a refused resume keeps .partial ($(echo "$before" | wc -l) files); the resume succeeds"

# 4. an empty output path
mkdir empty && (cd empty && "$exe" run "$case" --output-dir '' >/dev/null 2>../empty.err)
code=$?
echo "empty path: exit code $code: $(cat empty.err)"
[ "$code" -eq 1 ] || fail "--output-dir '' exited with $code, expected 1"
grep -qF -- "--output-dir: the path is empty" empty.err || fail "unexpected message"
[ -z "$(ls -A empty)" ] || fail "--output-dir '' wrote $(ls -A empty)"
echo "ok   --output-dir '' refused, nothing written"

# 5. a refused run creates no folder
"$exe" run "$case" --output-dir new/deeper/folder --set "Simulation/time step=1" \
  >/dev/null 2>refused.err
code=$?
echo "refused run: exit code $code: $(cat refused.err)"
[ "$code" -eq 1 ] || fail "the refused run exited with $code, expected 1"
[ ! -e new ] || fail "the refused run left $(find new)"
echo "ok   a refused run creates no folder"
