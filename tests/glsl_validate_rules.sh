#!/usr/bin/env bash
# Validates generated/bandlimit_bivariate.glsl (included after bandlimit.glsl, as documented) as a
# fragment shader in #version 450 and #version 320 es, calling every vec2 rule so none is dropped.
set -euo pipefail
validator=$1 table=$2 rules=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
calls=$(grep -oE '^vec2 bl_[a-z0-9_]+\([^)]*\)' "$rules" | sed -E 's/^vec2 (bl_[a-z0-9_]+)\((.*)\)/\1 \2/' |
  while read -r name args; do
    n=$(echo "$args" | tr ',' '\n' | wc -l)
    a=$(for i in $(seq 1 "$n"); do printf 'v.%s' "$(echo xyzw | cut -c$(( (i - 1) % 4 + 1 )))"; [[ $i -lt $n ]] && printf ', '; done)
    echo "  acc += $name($a);"
  done)
[[ -n $calls ]] || { echo "no vec2 rules found in $rules"; exit 1; }
for v in "450" "320 es"; do
  f="$tmp/test_${v// /_}.frag"
  {
    echo "#version $v"
    [[ $v == *es ]] && echo "precision highp float; precision highp int;"
    cat "$table" "$rules"
    echo "layout(location = 0) out vec4 color;"
    echo "uniform vec4 v;"
    echo "void main() {"
    echo "  vec2 acc = vec2(0.0);"
    echo "$calls"
    echo "  color = vec4(acc, 0.0, 1.0);"
    echo "}"
  } > "$f"
  if ! out=$("$validator" -l "$f" 2>&1); then
    echo "glslangValidator failed for #version $v on $rules:"
    echo "$out" | head -40
    exit 1
  fi
  echo "ok: #version $v ($(echo "$calls" | wc -l) rules called)"
done
