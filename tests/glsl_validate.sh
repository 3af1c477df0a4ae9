#!/usr/bin/env bash
# Validates a generated GLSL include as a fragment shader in #version 450 and #version 320 es
# (the ES front end catches integer/float mix-ups that 450 lets through, see TOOLCHAIN.md).
set -euo pipefail
validator=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A main() that calls every entry so nothing is dead-code eliminated before checking.
calls=$(grep -oE '^float bl_[a-z0-9_]+\(float x, float sigma\)' "$src" | sed -E 's/^float (bl_[a-z0-9_]+)\(.*/  acc += \1(v.x, v.y);/')
for v in "450" "320 es"; do
  f="$tmp/test_${v// /_}.frag"
  {
    echo "#version $v"
    [[ $v == *es ]] && echo "precision highp float; precision highp int;"
    cat "$src"
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
  echo "ok: #version $v ($(echo "$calls" | wc -l) entries called)"
done
