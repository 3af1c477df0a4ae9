#!/usr/bin/env bash
# The test suite: same set-up as tools/main.sh, then ctest (which includes the drift check of
# generated/, the verification of every formula, GLSL validation and the unit tests).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
ctest --test-dir build --output-on-failure -j "$(nproc)" "$@"
