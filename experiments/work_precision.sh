#!/usr/bin/env bash
# The work-precision experiment over the whole motion: error against CPU time
# on the published hanging cloth in wind with the sliding coordinates frozen
# (0.5 s, yarn and FEM models), for be-linear (dt ladder, the published 1 ms
# step marked), sdirk2 (dt and rtol ladders) and ida (rtol ladder), against an
# IDA reference at rtol 1e-8 (README, Error budgets). Results under
# results/work_precision/ (work_precision.csv, .json with scene, parameters, git
# revision and machine; work_precision.png/.svg; slopes.csv). The references are
# cached under results/reference/ (about 13 min each the first time), so a rerun
# only runs the ladders (about 15 min on the 2-core machine).
# WL_SCENE and WL_OUT change the scene and folder; extra arguments replace the
# options below and go to `weavelab work-precision` (e.g. WL_SCENE=
# experiments/scenes/work_precision_17.toml with no options: every integrator
# over 8 ms).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
scene=${WL_SCENE:-experiments/scenes/hanging_wind_frozen.toml}
out=${WL_OUT:-results/work_precision}
start=$(date +%s)
defaults=(--models yarn,fem --integrators be-linear,sdirk2,ida --rtols 1e-3,1e-4,1e-5,1e-6 --dt-max 0.002
          --dt-min 0.0000625 --budget 90 --reference-rtols 1e-8)
if [ $# -gt 0 ]; then defaults=(); fi  # extra arguments replace the defaults above
build/weavelab work-precision "$scene" --out "$out" "${defaults[@]}" "$@"
/usr/bin/python3 experiments/plot_work_precision.py "$out"
echo "work-precision: $(( $(date +%s) - start )) s wall (without the build); results in $out"
