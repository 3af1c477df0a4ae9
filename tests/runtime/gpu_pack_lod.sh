#!/usr/bin/env bash
# blgpu_pack packs bltune's footprint-LOD pair (result.json "lod") as <scene>/lod.frag beside the
# front points (and the adaptive supersampler, "adaptive_ss", as adaptive_ss.frag, and the GPU truth
# as truth.frag), and blgpu_time compiles, draws and reports them beside the single points (here on
# whatever GL driver there is: llvmpipe in CI), and measures each program's error against the
# truth it drew. The scene is the record's first with a pair.
set -euo pipefail
blgpu_pack=$1 blgpu_time=$2 root=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
scene=""
for r in "$root"/docs/tuning/suite/*/result.json; do
  if grep -q '"lod": {' "$r"; then
    scene=$(basename "$(dirname "$r")")
    break
  fi
done
[ -n "$scene" ] || { echo "no scene of docs/tuning/suite has a footprint-LOD pair"; exit 1; }
"$blgpu_pack" --suite "$root/docs/tuning/suite" --scenes "$root/scenes/suite" --only "$scene" --tile 1 \
  --fronts 1 --baselines plain,msaa16 --truth-samples 256 --out "$work/pack" > "$work/pack.log" 2>&1 ||
  { cat "$work/pack.log"; exit 1; }
# plain, MSAA-16, the fastest front point at MSAA-16's error, the pair, the adaptive supersampler and
# the truth.
grep -q "1 scenes, 6 fragment shaders" "$work/pack.log" || { cat "$work/pack.log"; exit 1; }
grep -q '"kind": "lod"' "$work/pack/manifest.json" || { echo "manifest.json has no lod entry"; exit 1; }
grep -q '"kind": "adaptive"' "$work/pack/manifest.json" || { echo "manifest.json has no adaptive entry"; exit 1; }
for frag in lod adaptive_ss; do
  for f in "void bl_shade_near(" "void bl_shade_far(" "void bl_shade(" "void main()"; do
    grep -qF "$f" "$work/pack/$scene/$frag.frag" || { echo "$frag.frag lacks '$f'"; exit 1; }
  done
done
"$blgpu_time" "$work/pack" --out "$work/gpu" --budget-ms 2 > "$work/gpu.log" 2> "$work/gpu.err" ||
  { cat "$work/gpu.err"; exit 1; }
report="$work/gpu/report.md"
grep -q "0 program(s) failed" "$report" || { cat "$report"; exit 1; }
# The pair's column (the 10th field of the scene's row) holds a time, the next its speed-ups.
row=$(grep -m1 "^| $scene |" "$report") || { cat "$report"; exit 1; }
echo "$row" | awk -F'|' '{ if ($10 !~ /^ [0-9]+\.[0-9]+ $/ || $11 !~ /x \/ [0-9.]+x/) exit 1 }' ||
  { echo "no timed pair in: $row"; exit 1; }
grep -q "^With the footprint-LOD pair where it is faster (1 scene(s)" "$report" || { cat "$report"; exit 1; }
grep -q "^Against footprint-adaptive supersampling at MSAA-16's error (1 scene(s))" "$report" || { cat "$report"; exit 1; }
# Errors on the driver: against its own truth (256 samples here, the CPU's 1024), the plain program
# and MSAA-16 land where bltune's evaluator put them (an independent check of both: another jitter
# hash, another arithmetic): within 3% for plain, 10% for MSAA-16 (its own 16 random samples).
grep -q "^## Errors on this GPU" "$report" || { cat "$report"; exit 1; }
python3 - "$work/gpu/gpu_times.json" <<'PY' || { cat "$report"; exit 1; }
import json, sys
rows = {p["label"]: p for p in json.load(open(sys.argv[1]))["programs"]}
for label, tol in (("plain", 0.03), ("msaa16", 0.10)):
    cpu, gpu = rows[label]["error"], rows[label]["gpu_error"]
    assert gpu is not None and abs(gpu / cpu - 1) <= tol, (label, cpu, gpu)
    assert rows[label]["nonfinite_pixels"] == 0, label
assert rows["truth"]["gpu_error"] is None and rows["truth"]["gpu_ms"] < 0  # drawn, never timed
PY
echo ok
