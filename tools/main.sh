#!/usr/bin/env bash
# The main job: install missing packages, build, regenerate generated/ from the catalog, verify
# every formula against quadrature (recording the results in generated/manifest.json), and print
# a summary.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
echo "[main] building rulegen"
cmake --build build -j "$(nproc)" --target rulegen
echo "[main] deriving and emitting generated/"
./build/bin/rulegen emit --out generated --quiet
echo "[main] building the rest (verifier, tests, benchmarks)"
cmake --build build -j "$(nproc)"
echo "[main] verifying every emitted formula against quadrature"
./build/bin/blverify --generated generated --record "$@"
echo "[main] rendering a demo scene: plain, MSAA 4/16, adaptive Gaussian, ground truth (build/demo)"
./build/bin/blrender scenes/suite/checkerboard_bumps.json --rules gaussian --msaa 4 16 --glsl \
  --out build/demo --cache build/truth_cache
