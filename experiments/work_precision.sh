#!/usr/bin/env bash
# The work-precision experiment: error against CPU time for every
# integrator on the hanging cloth, yarn and FEM models, with results under
# results/work_precision/ (work_precision.csv, .json with scene, parameters, git
# revision and machine; work_precision.png/.svg; slopes.csv). The IDA reference
# is cached under results/reference/, so a rerun skips it.
# Extra arguments go to `weavelab work-precision` (e.g. --integrators ida,be-linear).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
scene=${WL_SCENE:-experiments/scenes/work_precision_17.toml}
out=${WL_OUT:-results/work_precision}
start=$(date +%s)
build/weavelab work-precision "$scene" --out "$out" "$@"
/usr/bin/python3 experiments/plot_work_precision.py "$out"
echo "work-precision: $(( $(date +%s) - start )) s wall (without the build); results in $out"
