#!/usr/bin/env bash
# The stability experiment: the largest bounded fixed step per
# integrator × model × stretch-modulus multiplier (1, 10, 100, 1000) on the 9×9
# hanging cloth, with results under results/stability/ (stability.csv,
# stability_probes.csv, .json with scene, parameters, git revision and machine;
# stability.png/.svg). Extra arguments go to `weavelab stability`.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
scene=${WL_SCENE:-experiments/scenes/stability_9.toml}
out=${WL_OUT:-results/stability}
start=$(date +%s)
build/weavelab stability "$scene" --out "$out" "$@"
/usr/bin/python3 experiments/plot_stability.py "$out"
echo "stability: $(( $(date +%s) - start )) s wall (without the build); results in $out"
