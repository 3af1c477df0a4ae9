#!/usr/bin/env bash
# cost_model_check re-scores a tuned scene's measured points, the stratified ssN baselines of its
# front.csv included (priced as bltune prices them: N plain samples one after another); it stopped at
# the first ssN row from stop 34 until stop 41. One scene (checkerboard_none, 21 points), a quick
# evaluator-calibrated cost model for this machine.
set -euo pipefail
bltune=$1 check=$2 root=$3 work=$4
rm -rf "$work"
mkdir -p "$work/suite"
cp -r "$root/docs/tuning/suite/checkerboard_none" "$work/suite/"
"$bltune" --calibrate --calibration evaluator --cost-model "$work/cost.json" > "$work/calibrate.log" 2>&1 ||
  { cat "$work/calibrate.log"; exit 1; }
"$check" "$work/suite" "$root/scenes/suite" "$work/cost.json" "$work/cache" > "$work/check.md" 2> "$work/check.err" ||
  { cat "$work/check.err"; exit 1; }
grep -q "^| checkerboard_none | 21 | " "$work/check.md" || { cat "$work/check.md"; exit 1; }
grep -q "^21 points: median abs(model/compiled - 1) " "$work/check.md" || { cat "$work/check.md"; exit 1; }
echo ok
