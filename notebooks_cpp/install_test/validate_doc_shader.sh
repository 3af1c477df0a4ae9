#!/usr/bin/env bash
# Extracts the fragment shader body from docs/linking.md (the ```glsl block after the line
# "<!-- example-shader -->") and validates it as the doc says to assemble it: #version line,
# generated/bandlimit.glsl, then the body; for #version 450 and #version 320 es.
set -euo pipefail
validator=$1 doc=$2 glsl=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
awk '/<!-- example-shader -->/ {armed=1; next}
     armed && /^```glsl/ {inside=1; next}
     inside && /^```/ {exit}
     inside {print}' "$doc" > "$tmp/body.frag"
[ -s "$tmp/body.frag" ] || { echo "no example shader found in $doc"; exit 1; }
for v in "450" "320 es"; do
  f="$tmp/shader_${v// /_}.frag"
  {
    echo "#version $v"
    [[ $v == *es ]] && echo "precision highp float;"
    cat "$glsl" "$tmp/body.frag"
  } > "$f"
  "$validator" "$f" || { echo "glslangValidator failed for #version $v"; exit 1; }
  echo "ok: example shader of $(basename "$doc") validates as #version $v"
done
