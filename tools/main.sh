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
# The demo renders a tuned point that wins honestly: the fastest point of a suite scene's Pareto front
# (docs/tuning/suite, bltune's defaults) whose error is at most MSAA 16's, next to plain, MSAA 4/16
# (random jitter) and stratified supersampling with 8 samples (ss8: as accurate as MSAA 16 on every
# suite scene, docs/tuning.md "Stop 34"), all as compiled C++ (and the point's GLSL on the GL driver).
demo_scene=quadratic_sine_none
demo_point=front04
echo "[main] rendering a demo scene: a tuned schedule vs plain, MSAA 4/16 and ss8, ground truth (build/demo)"
./build/bin/blrender "scenes/suite/$demo_scene.json" --schedule "docs/tuning/suite/$demo_scene/front.csv:$demo_point" \
  --msaa 4 16 --supersample 8 --glsl --out build/demo --cache build/truth_cache
# Error and compiled time (ms per frame; the evaluator's when no compiler) summed over the scene's
# views, from the report's table.
awk -F'|' -v pt="$demo_point" -v sc="$demo_scene" '$3 ~ ("msaa16|ss8|" pt) { gsub(/ /, "", $3); ms = ($5 ~ /-/) ? $7 : $5; t[$3] += ms; e[$3] += $8 }
  END { if (e["msaa16"] > 0 && t[pt] > 0)
          printf "[main] demo (%s, tuned point %s, RMS summed over views): %.4f vs MSAA 16 %.4f (%.2fx its error) at %.1fx its speed (compiled C++)\n",
                 sc, pt, e[pt], e["msaa16"], e[pt] / e["msaa16"], t["msaa16"] / t[pt]
        if (e["ss8"] > 0 && t[pt] > 0)
          printf "[main] against stratified supersampling (ss8, 8 fixed samples): %.4f vs %.4f (%.2fx its error) at %.1fx its speed\n",
                 e[pt], e["ss8"], e[pt] / e["ss8"], t["ss8"] / t[pt] }' \
  build/demo/report.md
