#!/usr/bin/env bash
# The quick start: builds weavelab (tools/setup.sh), then runs the main job
# (experiments/main_job/, about.md there): the continuum calibrated on the yarn
# level and the first-guess continuum, each compared with the yarn level on
# hanging_wind_damped.toml, every run with its estimated time error, and prints
# the table: each distance beside the two runs' time errors, with the verdict.
# The workflow writes experiments/main_job/RESULTS.md; its knobs are in
# experiments/main_job/config.yaml. Arguments are passed on to snakemake (e.g.
# --config 'main_job={rtol: 1e-4}'). A rerun skips the calibration and the runs
# that have not changed.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/setup.sh
snakemake -s experiments/main_job/Snakefile --cores 2 "$@"
echo
echo "Yarn level against the continuum (mean RMS over the frames, mm) and each run's time error:"
cat results/main_job/budget.txt
echo "(experiments/main_job/RESULTS.md; the runs under results/main_job/cells/)"
