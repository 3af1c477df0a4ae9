#!/usr/bin/env bash
# The search's spread at MSAA-16's error: tunes each named suite scene again with other search seeds
# (the default run is seed 1) under the same cost model, and prints each scene's speed-up at MSAA-16's
# error (model / measured) per seed and at the median over the seeds, with the count at >= 10x by the
# model. A scene within ~15% of 10x crosses the line or not from one seed to the next (docs/tuning.md,
# stop 31): count it at its median.
#
#   tools/seed_spread.sh SUITE_DIR OUT_DIR "2 3" scene_a scene_b ...
#
# SUITE_DIR: a `bltune --suite` output (seed 1; its <scene>/report.md is read, not rerun); OUT_DIR gets
# <scene>_s<seed>/ (a scene already there is not tuned again). Uses build/bin/bltune,
# build/cost_model.json (the calibration SUITE_DIR was tuned with: recalibrating between the runs
# mixes the calibration's spread into the search's) and $BL_TRUTH_CACHE (default build/truth_cache).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
# Paths as the caller wrote them, before moving to the repository root.
suite=$(realpath -m "$1") out=$(realpath -m "$2") seeds=$3
cache=$(realpath -m "${BL_TRUTH_CACHE:-$(dirname "$0")/../build/truth_cache}")
shift 3
cd "$(dirname "$0")/.."
[ -x build/bin/bltune ] || { echo "seed_spread: build/bin/bltune missing (bash tools/build.sh)" >&2; exit 1; }
mkdir -p "$out"
# "| 16 | rms | point | 11.1x | 12.7x compiled |" -> "11.1 12.7"; "- -" when MSAA-16's error is not reached.
at16() {
  awk -F'|' '/^\| 16 \|/ { m = $5; c = $6; gsub(/[ x]/, "", m); sub(/x.*/, "", c); gsub(/ /, "", c);
    if (m == "-" || m == "") { m = "-"; c = "-" } print m, c; found = 1; exit }
    END { if (!found) print "- -" }' "$1"
}
for s in "$@"; do
  [ -f "scenes/suite/$s.json" ] || { echo "seed_spread: no scene scenes/suite/$s.json" >&2; exit 1; }
  [ -f "$suite/$s/report.md" ] || { echo "seed_spread: $suite/$s/report.md missing (not a suite output?)" >&2; exit 1; }
  for k in $seeds; do
    d="$out/${s}_s$k"
    [ -f "$d/report.md" ] && continue
    echo "[seed_spread] $s seed $k" >&2
    build/bin/bltune "scenes/suite/$s.json" --seed "$k" --out "$d" --cache "$cache" \
      --cost-model build/cost_model.json >"$d.log" 2>&1 || { echo "seed_spread: $s seed $k failed, see $d.log" >&2; exit 1; }
    [ -f "$d/report.md" ] || { echo "seed_spread: $s seed $k wrote no report, see $d.log" >&2; exit 1; }
  done
done
echo "| scene | seed 1 | $(for k in $seeds; do printf 'seed %s | ' "$k"; done)median (model) | >= 10x |"
echo "|---|---|$(for k in $seeds; do printf -- '---|'; done)---|---|"
count=0
for s in "$@"; do
  row="| $s |" vals=""
  read -r m c < <(at16 "$suite/$s/report.md")
  row+=" ${m}x / ${c}x |"
  vals+="$m "
  for k in $seeds; do
    read -r m c < <(at16 "$out/${s}_s$k/report.md")
    row+=" ${m}x / ${c}x |"
    vals+="$m "
  done
  # Median of the model speed-ups; a seed that did not reach MSAA-16's error counts as 0.
  med=$(echo "$vals" | tr ' ' '\n' | sed '/^$/d; s/^-$/0/' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
  yes=$(awk -v m="$med" 'BEGIN { print (m >= 10) ? "yes" : "no" }')
  [ "$yes" = yes ] && count=$((count + 1))
  echo "$row ${med}x | $yes |"
done
echo
echo "$count of $# scene(s) at >= 10x less model time at the median over seeds 1 $seeds"
