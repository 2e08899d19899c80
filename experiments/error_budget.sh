#!/usr/bin/env bash
# The error budget of the hanging cloth in wind (README, Error budgets;
# docs/models.md §7.10): runs of the yarn model on a ladder of integrators and
# steps, each with its estimated time error (weavelab run --error-estimate), set
# beside its true distance to a converged reference (IDA at rtol 1e-8, run once
# and kept). Results under results/error_budget/:
#   reference/                 the converged run
#   <label>/                   each run (frames, metrics.csv, summary.json with time_error)
#   error_budget.csv, .md      per run: CPU time, true and estimated time error (mean over
#                              frames of the RMS over nodes) over 0-T/2, T/2-T and 0-T
#   error_budget.png/.svg      estimated against true error, and true error against CPU time
# WL_SCENE (default the frozen-sliding scene) and WL_OUT change the scene and folder;
# WL_RUNS="label:options;..." replaces the ladder. The reference takes about 13 min on
# the 2-core machine, the ladder about 15 min (its runs on every core: WL_JOBS, experiments/jobs.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source experiments/jobs.sh  # the ladder's runs on every core (WL_JOBS=1: one at a time)
tools/setup.sh
scene=${WL_SCENE:-experiments/scenes/hanging_wind_frozen.toml}
out=${WL_OUT:-results/error_budget}
runs=${WL_RUNS:-"be-linear-1ms:--integrator be-linear --dt 0.001;be-linear-0.5ms:--integrator be-linear --dt 0.0005;be-linear-0.25ms:--integrator be-linear --dt 0.00025;be-linear-0.125ms:--integrator be-linear --dt 0.000125;sdirk2-1ms:--integrator sdirk2 --dt 0.001;sdirk2-0.5ms:--integrator sdirk2 --dt 0.0005;sdirk2-0.25ms:--integrator sdirk2 --dt 0.00025;sdirk2-rtol1e-4:--integrator sdirk2 --rtol 1e-4"}
mkdir -p "$out"
start=$(date +%s)
if [ ! -f "$out/reference/summary.json" ]; then
  echo "error_budget: reference (ida, rtol 1e-8)" >&2
  build/weavelab run "$scene" --integrator ida --rtol 1e-8 --dt 1e-6 --quiet --out "$out/reference"
fi
ladder_run() {  # label options...: a numerical failure is a row of the table, not the end of the experiment
  local label=$1
  shift
  build/weavelab run "$scene" "$@" --error-estimate --quiet --out "$out/$label" || true
}
labels=()
IFS=';' read -r -a entries <<<"$runs"
for entry in "${entries[@]}"; do
  label=${entry%%:*}
  read -r -a options <<<"${entry#*:}"
  echo "error_budget: $label (${options[*]})" >&2
  job ladder_run "$label" "${options[@]}"
  labels+=("$label")
done
wait_jobs
/usr/bin/python3 experiments/error_budget.py "$out" "$out/reference" "${labels[@]}"
echo "error_budget: $(( $(date +%s) - start )) s wall (without the build); results in $out"
