#!/usr/bin/env bash
# Every C++ header of a tree `rulegen emit` wrote compiles (g++ -fsyntax-only, one translation unit
# that includes them all): an emitted rule never calls a table entry the catalog did not derive
# (rulegen/emit_rules.cpp emits div and mod only with inv and fract).
# Usage: emit_compiles.sh CXX TREE
set -euo pipefail
cxx=$1 tree=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
headers=$(cd "$tree" && ls bandlimit/*.hpp)
[[ -n $headers ]] || { echo "no headers in $tree/bandlimit"; exit 1; }
for h in $headers; do echo "#include <$h>"; done > "$tmp/all.cpp"
echo "int main() { return 0; }" >> "$tmp/all.cpp"
if ! out=$("$cxx" -std=c++17 -fsyntax-only -I"$tree" "$tmp/all.cpp" 2>&1); then
  echo "the headers of $tree do not compile:"
  echo "$out" | head -40
  exit 1
fi
echo "ok: $(echo "$headers" | wc -l) headers of $tree compile"
