#!/usr/bin/env bash
# blsmooth end to end: a GLSL pattern and a scene to GLSL (validated by glslangValidator inside a
# fragment shader, as 450 and 320 es) and to C++ (compiled against generated/ and run); the example
# patterns with the prelude are valid GLSL; bad arguments exit non-zero and leave no output file.
set -euo pipefail
blsmooth=$1 validator=$2 cxx=$3 src=$4 work=$5
rm -rf "$work" && mkdir -p "$work"
"$blsmooth" "$src/scenes/glsl/fire.glsl" --rules gaussian --out "$work/fire.glsl"
"$blsmooth" "$src/scenes/glsl/circles.json" --rules dorn --out "$work/circles.glsl"
"$blsmooth" "$src/scenes/glsl/fire.glsl" --rules gaussian --out "$work/fire.hpp"
for f in fire circles; do
  for v in "450" "320 es"; do
    { echo "#version $v"; echo "precision highp float;"; cat "$work/$f.glsl"
      echo "layout(location = 0) out vec4 frag;"
      echo "void main() { float m[NI], s[NI], o[3]; for (int i = 0; i < NI; ++i) { m[i] = 0.3; s[i] = 0.1; }"
      echo "  shade(m, s, s, s, o); frag = vec4(o[0], o[1], o[2], 1.0); }"; } |
      sed "s/NI/$(grep -o 'bl_m\[[0-9]*\]' "$work/$f.glsl" | head -1 | tr -dc 0-9)/g" > "$work/${f}_${v% *}.frag"
    "$validator" -S frag "$work/${f}_${v% *}.frag" > /dev/null || { echo "FAILED: $f as $v"; cat "$work/${f}_${v% *}.frag" | head -40; exit 1; }
  done
done
cat > "$work/main.cpp" <<'CPP'
#include <cmath>
#include <cstdio>
#include "fire.hpp"
int main() {
  const float m[3] = {0.3f, -1.2f, 0.5f}, s[3] = {0.05f, 0.05f, 0.0f}, g[3] = {0, 0, 0};
  float out[3];
  bl_shaders::shade(m, s, g, g, out);
  for (float x : out) if (!std::isfinite(x) || x < -0.01f || x > 1.01f) return 1;
  std::printf("fire smoothed at (0.3, -1.2, t=0.5): %g %g %g\n", out[0], out[1], out[2]);
}
CPP
"$cxx" -std=c++17 -O1 -I"$src/generated" -I"$work" "$work/main.cpp" -o "$work/main" && "$work/main"
# Every example pattern is valid GLSL 450 once the prelude (blsmooth --prelude) is in front of it.
for f in "$src"/scenes/glsl/*.glsl; do
  { echo "#version 450"; "$blsmooth" --prelude; grep -v "^#version" "$f"
    echo "layout(location = 0) out vec4 frag;"
    echo "void main() { frag = vec4(shade(vec2(0.3, 0.7), 0.5), 1.0); }"; } > "$work/example.frag"
  "$validator" -S frag "$work/example.frag" > /dev/null || { echo "FAILED: $f with the prelude"; exit 1; }
done
# Errors: exit non-zero, nothing written.
if "$blsmooth" "$src/scenes/glsl/fire.glsl" --out "$work/bad.txt" 2> /dev/null; then echo "bad extension accepted"; exit 1; fi
printf 'vec3 shade(vec2 uv, float time) {\n  if (uv.x < 0.0) discard;\n  return vec3(1.0);\n}\n' > "$work/bad.glsl"
if msg=$("$blsmooth" "$work/bad.glsl" --out "$work/bad_out.glsl" 2>&1); then echo "discard accepted"; exit 1; fi
echo "$msg" | grep -q "bad.glsl:2:19: unsupported discard" || { echo "unexpected message: $msg"; exit 1; }
[ ! -e "$work/bad_out.glsl" ] && [ ! -e "$work/bad.txt" ] || { echo "half-written output"; exit 1; }
echo "ok"
