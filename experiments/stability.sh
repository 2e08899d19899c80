#!/usr/bin/env bash
# The stability experiment: the largest bounded fixed step per
# integrator × model × stretch-modulus multiplier (1, 10, 100, 1000) on the 9×9
# hanging cloth, with results under results/stability/ (stability.csv,
# stability_probes.csv, .json with scene, parameters, git revision and machine;
# stability.png/.svg). A Snakemake workflow (experiments/stability/Snakefile):
# one job per cell, locally on every core, cached by the scene's hash, so a
# rerun only runs what changed. WL_SCENE and WL_OUT change the scene and
# folder, WL_OPTIONS adds options of `weavelab stability` (e.g. "--bisections 6");
# extra arguments go to snakemake (e.g. --profile experiments/common/profiles/cluster).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
config=(scene="${WL_SCENE:-experiments/scenes/stability_9.toml}" out="${WL_OUT:-results/stability}")
if [ -n "${WL_OPTIONS:-}" ]; then config+=(options="$WL_OPTIONS"); fi
start=$(date +%s)
snakemake -s experiments/stability/Snakefile --cores "$(nproc)" --config "${config[@]}" "$@"
echo "stability: $(( $(date +%s) - start )) s wall (without the build); results in ${WL_OUT:-results/stability}"
