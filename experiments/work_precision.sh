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
# A Snakemake workflow (experiments/work_precision/Snakefile): one job per model
# and integrator, locally on every core, cached by the scene's hash, so a rerun
# only runs what changed. WL_SCENE and WL_OUT change the scene and folder,
# WL_OPTIONS replaces the options of `weavelab work-precision` below (e.g. WL_SCENE=
# experiments/scenes/work_precision_17.toml WL_OPTIONS=" " WL_INTEGRATORS=be-linear,sdirk2,ida,symplectic);
# extra arguments go to snakemake (e.g. --profile experiments/common/profiles/cluster).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
config=(scene="${WL_SCENE:-experiments/scenes/hanging_wind_frozen.toml}" out="${WL_OUT:-results/work_precision}")
if [ -n "${WL_OPTIONS:-}" ]; then config+=(options="$WL_OPTIONS"); fi
if [ -n "${WL_INTEGRATORS:-}" ]; then config+=(integrators="$WL_INTEGRATORS"); fi
start=$(date +%s)
snakemake -s experiments/work_precision/Snakefile --cores "$(nproc)" --config "${config[@]}" "$@"
echo "work-precision: $(( $(date +%s) - start )) s wall (without the build); results in ${WL_OUT:-results/work_precision}"
