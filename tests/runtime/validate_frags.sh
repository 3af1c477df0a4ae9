#!/usr/bin/env bash
# Validates every compiled fixture fragment shader (tests/runtime/emit_fixtures.cpp) with glslangValidator.
set -euo pipefail
validator=$1
dir=$2
n=0
for f in "$dir"/*.frag; do
  if ! out=$("$validator" -l -S frag "$f" 2>&1); then
    echo "FAILED: $f"
    echo "$out" | head -20
    exit 1
  fi
  n=$((n + 1))
done
[ "$n" -gt 0 ] || { echo "no fragment shaders in $dir"; exit 1; }
echo "ok: $n fragment shaders validate"
