#!/usr/bin/env bash
# The search's spread at MSAA-16's error: tunes each named suite scene again with other search seeds
# (the default run is seed 1) under the same cost model, and prints each scene's speed-up at MSAA-16's
# error (model / measured) per seed and at the median over the seeds, with the count at >= 10x by the
# model. A scene within ~15% of 10x crosses the line or not from one seed to the next (docs/tuning.md,
# stop 31): count it at its median.
#
#   tools/seed_spread.sh SUITE_DIR OUT_DIR "2 3" scene_a scene_b ...
#
# SUITE_DIR: a `bltune --suite` output (seed 1; its summary.csv is read, not rerun); OUT_DIR gets
# s<seed>/<scene>/ and s<seed>/summary.csv (`bltune --summarize`; a scene already there is not tuned
# again). Speed-ups are read from the summaries' speedup16_model / speedup16_measured columns (0: MSAA-16's
# error not reached); with SPREAD_WITH_LOD=1, from the footprint-LOD pair's columns where it is faster
# (lod_speedup16_model / _measured; docs/runtime.md "Footprint LOD"). Uses build/bin/bltune,
# build/cost_model.json (the calibration SUITE_DIR was tuned with: recalibrating between the runs
# mixes the calibration's spread into the search's) and $BL_TRUTH_CACHE (default build/truth_cache).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
# Paths as the caller wrote them, before moving to the repository root.
suite=$(realpath -m "$1") out=$(realpath -m "$2") seeds=$3
cache=$(realpath -m "${BL_TRUTH_CACHE:-$(dirname "$0")/../build/truth_cache}")
shift 3
cd "$(dirname "$0")/.."
[ -x build/bin/bltune ] || { echo "seed_spread: build/bin/bltune missing (bash tools/build.sh)" >&2; exit 1; }
mkdir -p "$out"
# "model measured" speed-ups at MSAA-16's error of scene $2 in summary.csv $1 (columns by name), "- -"
# when not reached; an error when the scene has no row.
at16() {
  awk -F, -v scene="$2" -v file="$1" -v lod="${SPREAD_WITH_LOD:-0}" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
              if (!col["speedup16_model"] || !col["speedup16_measured"]) { print "seed_spread: " file " has no speedup16 columns" > "/dev/stderr"; bad = 1; exit 1 }
              if (lod == 1 && !col["lod_speedup16_model"]) { print "seed_spread: " file " has no lod_speedup16 columns" > "/dev/stderr"; bad = 1; exit 1 } next }
    $1 == scene { m = $col["speedup16_model"]; c = $col["speedup16_measured"]
                  if (lod == 1 && $col["lod_speedup16_model"] + 0 > m + 0) { m = $col["lod_speedup16_model"]; c = $col["lod_speedup16_measured"] }
                  if (m + 0 > 0) printf "%.1f %.1f\n", m, c; else print "- -"; found = 1; exit }
    END { if (!bad && !found) { print "seed_spread: no row for " scene " in " file > "/dev/stderr"; exit 1 } }' "$1"
}
for s in "$@"; do
  [ -f "scenes/suite/$s.json" ] || { echo "seed_spread: no scene scenes/suite/$s.json" >&2; exit 1; }
  [ -f "$suite/summary.csv" ] || { echo "seed_spread: $suite/summary.csv missing (not a suite output?)" >&2; exit 1; }
  for k in $seeds; do
    d="$out/s$k/$s"
    [ -f "$d/result.json" ] && continue
    echo "[seed_spread] $s seed $k" >&2
    mkdir -p "$out/s$k"
    build/bin/bltune "scenes/suite/$s.json" --seed "$k" --out "$d" --cache "$cache" \
      --cost-model build/cost_model.json >"$d.log" 2>&1 || { echo "seed_spread: $s seed $k failed, see $d.log" >&2; exit 1; }
    [ -f "$d/result.json" ] || { echo "seed_spread: $s seed $k wrote no result.json, see $d.log" >&2; exit 1; }
  done
done
for k in $seeds; do
  build/bin/bltune --summarize "$out/s$k" >/dev/null || { echo "seed_spread: bltune --summarize $out/s$k failed" >&2; exit 1; }
done
echo "| scene | seed 1 | $(for k in $seeds; do printf 'seed %s | ' "$k"; done)median (model) | >= 10x |"
echo "|---|---|$(for k in $seeds; do printf -- '---|'; done)---|---|"
count=0
for s in "$@"; do
  row="| $s |" vals=""
  read -r m c < <(at16 "$suite/summary.csv" "$s") || exit 1
  row+=" ${m}x / ${c}x |"
  vals+="$m "
  for k in $seeds; do
    read -r m c < <(at16 "$out/s$k/summary.csv" "$s") || exit 1
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
