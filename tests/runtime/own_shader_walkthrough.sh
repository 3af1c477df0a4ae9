#!/usr/bin/env bash
# docs/own_shader.md's commands on a small scene whose GLSL lives outside the repository: blrender
# renders it (plain, MSAA 16, gaussian, ground truth) with no rebuild, blsmooth emits it, a tiny
# bltune writes every front point as code, and --schedule rebuilds a front point in both tools;
# docs/gpu_timing.md's pack and timer run the tuned scene on this machine's GL driver.
set -euo pipefail
blrender=$1 blsmooth=$2 work=$3 bltune=$4 blgpu_pack=$5 blgpu_time=$6
rm -rf "$work" && mkdir -p "$work/my"
cat > "$work/my/stripes.glsl" <<'GLSL'
#version 450
vec3 shade(vec2 uv, float time) {
  float s = step(0.5, fract(uv.x * 3.0 + uv.y));
  return mix(vec3(0.1, 0.2, 0.8), vec3(0.9, 0.8, 0.1), s);
}
GLSL
cat > "$work/my/stripes.json" <<'JSON'
{ "shader": "stripes.glsl", "parallax": "bumps", "lighting": "phong",
  "image": {"width": 24, "height": 16}, "ground_truth": {"samples": 16} }
JSON
"$blrender" "$work/my/stripes.json" --rules gaussian --msaa 16 --out "$work/out" --cache "$work/cache" > "$work/render.log"
grep -q "| v0_t0.000 | gaussian |" "$work/out/report.md" || { cat "$work/render.log"; exit 1; }
grep -q "| v0_t0.000 | msaa16 |" "$work/out/report.md"
ls "$work/out/v0_t0.000_truth.png" "$work/out/shader.glsl" "$work/out/shader.hpp" > /dev/null
"$blsmooth" "$work/my/stripes.glsl" --rules gaussian --out "$work/stripes_smooth.glsl"
"$blsmooth" "$work/my/stripes.json" --rules gaussian --out "$work/stripes_smooth.hpp"
grep -q "void shade(in float bl_m\[2\]" "$work/stripes_smooth.glsl"
grep -q "inline void shade(" "$work/stripes_smooth.hpp"
# Section 5: tune (tiny settings, quick evaluator-calibrated cost model), then use a front point.
"$bltune" "$work/my/stripes.json" --out "$work/tune" --cache "$work/cache" --cost-model "$work/cost.json" \
  --calibration evaluator --jit-cache "$work/jit" --population 6 --generations 1 --restarts 1 --pixels 120 \
  --nm-evals 3 --max-points 3 > "$work/tune.log" 2>&1 || { cat "$work/tune.log"; exit 1; }
label=$(awk -F, '$1 == "front" { l = $2 } END { print l }' "$work/tune/front.csv")
[ -n "$label" ] || { echo "no front point in front.csv"; exit 1; }
ls "$work/tune/front/$label.glsl" "$work/tune/front/$label.hpp" > /dev/null
# The report explains the point it reads the speed-up at MSAA-16's error from, when one reaches it.
if grep -q "^| 16 | [0-9.]* | front" "$work/tune/report.md"; then
  grep -q "^### Where front[0-9]*'s model time goes" "$work/tune/report.md" || { cat "$work/tune/report.md"; exit 1; }
fi
# Where the point's model time goes: a table whose rows sum to the throughput, the point against plain.
"$bltune" "$work/my/stripes.json" --explain "$work/tune/front.csv:$label" --cache "$work/cache" \
  --cost-model "$work/cost.json" --calibration evaluator > "$work/explain.md" || { cat "$work/explain.md"; exit 1; }
grep -q "^| \*\*throughput T\*\* | | " "$work/explain.md" || { cat "$work/explain.md"; exit 1; }
awk -F'|' '/^\| (bl::|inline|values|pixel)/ { sum += $4 } /throughput T/ { t = $4 }
  END { if (t <= 0 || sum < t - 0.02 * NR || sum > t + 0.02 * NR) { print "parts " sum " vs T " t; exit 1 } }' "$work/explain.md"
grep -q "x plain, " "$work/explain.md"
if "$bltune" "$work/my/stripes.json" --explain "$work/tune/front.csv:nosuchpoint" --cache "$work/cache" \
  --cost-model "$work/cost.json" --calibration evaluator > /dev/null 2> "$work/err0.txt"; then
  echo "--explain accepted an unknown label"; exit 1
fi
grep -q "nosuchpoint" "$work/err0.txt" || { cat "$work/err0.txt"; exit 1; }
"$blrender" "$work/my/stripes.json" --schedule "$work/tune/front.csv:$label" --msaa 4 --out "$work/out_$label" \
  --cache "$work/cache" > "$work/render_$label.log"
grep -q "| v0_t0.000 | $label |" "$work/out_$label/report.md" || { cat "$work/render_$label.log"; exit 1; }
"$blsmooth" "$work/my/stripes.json" --schedule "$work/tune/front.csv:$label" --out "$work/stripes_$label.glsl"
# The code bltune wrote and the code blsmooth rebuilds from the schedule are the same function.
diff <(grep -v '^//' "$work/tune/front/$label.glsl") <(grep -v '^//' "$work/stripes_$label.glsl")
# A schedule is refused for another graph (an edited shader), naming both graph hashes.
sed 's/0\.5, fract/0.25, fract/' "$work/my/stripes.glsl" > "$work/my/edited.glsl"
sed 's/stripes.glsl/edited.glsl/' "$work/my/stripes.json" > "$work/my/edited.json"
if "$blsmooth" "$work/my/edited.json" --schedule "$work/tune/front.csv:$label" --out "$work/x.glsl" 2> "$work/err.txt"; then
  echo "a schedule for another graph was accepted"; exit 1
fi
grep -q "tuned for graph" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
[ ! -e "$work/x.glsl" ]
# GPU timing of your own tuned scene (here on whatever GL driver there is: llvmpipe in CI): every
# baseline and front point packed, drawn on a 2 x 2 tiling, reported with no failure.
"$blgpu_pack" --suite "$work/tune" --scene "$work/my/stripes.json" --tile 2 --out "$work/gpu_pack" > "$work/pack.log"
grep -q "1 scenes" "$work/pack.log" || { cat "$work/pack.log"; exit 1; }
ls "$work/gpu_pack/stripes/plain.frag" "$work/gpu_pack/stripes/msaa16.frag" "$work/gpu_pack/stripes/$label.frag" > /dev/null
"$blgpu_time" "$work/gpu_pack" --out "$work/gpu" --budget-ms 2 > "$work/gpu.log" 2> "$work/gpu.err" ||
  { cat "$work/gpu.err"; exit 1; }
grep -q "^| stripes | [0-9.]* | [0-9.]* (" "$work/gpu/report.md" || { cat "$work/gpu/report.md"; exit 1; }
grep -q "0 program(s) failed" "$work/gpu/report.md" || { cat "$work/gpu/report.md"; exit 1; }
# A --scene that is not the one tuned is refused, naming the graph hashes.
if "$blgpu_pack" --suite "$work/tune" --scene "$work/my/edited.json" --out "$work/gpu_bad" 2> "$work/err2.txt"; then
  echo "blgpu_pack accepted another scene's graph"; exit 1
fi
grep -q "tuned for graph" "$work/err2.txt" || { cat "$work/err2.txt"; exit 1; }
echo ok
