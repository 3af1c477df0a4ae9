#!/usr/bin/env bash
# docs/own_shader.md's commands on a small scene whose GLSL lives outside the repository: blrender
# renders it (plain, MSAA 16, gaussian, ground truth) with no rebuild, blsmooth emits it.
set -euo pipefail
blrender=$1 blsmooth=$2 work=$3
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
echo ok
