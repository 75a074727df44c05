#!/usr/bin/env bash
# verify_outputs.sh DIR QUANTITY...
# The verification report is complete: summary.json, comparison.csv and comparison.png exist,
# and each QUANTITY has a CSV row with the DEM value, the FE value and their difference.
set -u
dir=$1
shift
for f in summary.json comparison.csv comparison.png dem/summary.json fem/summary.json fem/case.prm; do
  [ -s "$dir/$f" ] || { echo "FAIL: $dir/$f missing"; exit 1; }
done
for q in "$@"; do
  row=$(grep -E "^(scalar|layer),$q," "$dir/comparison.csv") || { echo "FAIL: no row $q"; exit 1; }
  echo "$row"
  # kind,quantity,unit,axis,position,dem,fem,difference,relative_difference
  IFS=, read -r _ _ _ _ _ dem fem diff rel <<<"$row"
  for v in "$dem" "$fem" "$diff" "$rel"; do
    [[ "$v" =~ ^[-+0-9.eE]+$ ]] || { echo "FAIL: $q: '$v' is not a number"; exit 1; }
  done
done
echo "ok"
