#!/usr/bin/env bash
# The default experiment: the published hanging cloth in the wind (physics.md
# §5.1), simulated at yarn level, with results under results/hanging_wind/.
set -euo pipefail
cd "$(dirname "$0")/.."
experiments/setup.sh
scene=experiments/scenes/hanging_wind.toml
out=results/hanging_wind
build/weavelab run "$scene" --model yarn --out "$out/yarn"
/usr/bin/python3 experiments/plot_run.py "$out/yarn" --out "$out/yarn_energy"
echo "results in $out (open $out/yarn/run.pvd in ParaView)"
