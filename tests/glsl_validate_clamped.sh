#!/usr/bin/env bash
# Validates generated/bandlimit_clamped.glsl (included after bandlimit.glsl) as a fragment shader in
# #version 450 and #version 320 es, calling every entry: derivatives float f(float x), rules
# vec2 f(float mu, float sigma) and truncnorm helpers.
set -euo pipefail
validator=$1 base=$2 src=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
calls=$(grep -oE '^float bl_deriv_[a-z0-9_]+\(float x\)' "$src" | sed -E 's/^float (bl_[a-z0-9_]+)\(.*/  acc += \1(v.x);/')
calls+=$'\n'$(grep -oE '^vec2 bl_(rule1|rule3|bimodal)_[a-z0-9_]+\(float mu, float sigma\)' "$src" |
  sed -E 's/^vec2 (bl_[a-z0-9_]+)\(.*/  acc += dot(\1(v.x, v.y), vec2(1.0));/' || true)
calls+=$'\n'$(grep -oE '^float bl_compact_[a-z0-9_]+\(float x, float sigma\)' "$src" |
  sed -E 's/^float (bl_[a-z0-9_]+)\(.*/  acc += \1(v.x, v.y);/' || true)
n=$(echo "$calls" | grep -c acc || true)
for v in "450" "320 es"; do
  f="$tmp/test_${v// /_}.frag"
  {
    echo "#version $v"
    [[ $v == *es ]] && echo "precision highp float; precision highp int;"
    cat "$base" "$src"
    echo "layout(location = 0) out vec4 color;"
    echo "uniform vec2 v;"
    echo "void main() {"
    echo "  float acc = 0.0;"
    echo "$calls"
    echo "  color = vec4(acc);"
    echo "}"
  } > "$f"
  if ! out=$("$validator" -l "$f" 2>&1); then
    echo "glslangValidator failed for #version $v on $src:"
    echo "$out" | head -40
    exit 1
  fi
  echo "ok: #version $v ($n entries called)"
done
