#!/usr/bin/env bash
# The default experiment: the published hanging cloth in the wind (docs/models.md
# §8), simulated at yarn level and as a continuum (triangle FEM, docs/models.md
# §6) with sdirk2 under error control (rtol 1e-4), each with its estimated time
# error (--error-estimate, docs/models.md §7.8), then compared frame by frame;
# the comparison ends with the error budget: the distance beside each run's
# time error. About 5 minutes on 2 cores. WL_RUN_OPTIONS replaces the
# integrator options (e.g. "--integrator be-linear" for the published step).
# Results under results/hanging_wind/:
#   yarn/, fem/            the two runs (frames, metrics.csv, summary.json)
#   compare.csv            per frame: RMS and max distance between the yarn
#                          crossings and the FEM surface at the same material
#                          (u, v), and the step-time ratio FEM/yarn
#   compare.png/.svg       that distance over time
#   fem_tension.png        the FEM tension map of the last frame
#   yarn_energy.png/.svg, fem_energy.png/.svg   energy and speed over time
# Each step stops the script with a message naming it when it fails.
set -euo pipefail
cd "$(dirname "$0")/.."

scene=experiments/scenes/hanging_wind.toml
out=results/hanging_wind
python=/usr/bin/python3

step() {  # step "description" command...: runs the command; on failure, says which step failed
  local what=$1
  shift
  echo "== $what" >&2
  local status=0
  "$@" || status=$?
  if [ "$status" -ne 0 ]; then
    echo "run_default: step '$what' failed with exit status $status: $*" >&2
    exit "$status"
  fi
}

step "setup and build" tools/setup.sh
mkdir -p "$out"
read -r -a run_options <<<"${WL_RUN_OPTIONS:---integrator sdirk2 --rtol 1e-4}"
for model in yarn fem; do
  step "$model run of $scene (${run_options[*]}, with its time error)" \
    build/weavelab run "$scene" --model "$model" "${run_options[@]}" --error-estimate --quiet --out "$out/$model"
done
step "compare yarn and fem" \
  "$python" experiments/compare.py "$out/yarn" "$out/fem" --out "$out/compare.csv" --plot "$out/compare.png" \
  --table >"$out/compare.txt"
step "plot fem tension map" "$python" experiments/plot_tension.py "$out/fem" --out "$out/fem_tension.png"
for model in yarn fem; do
  step "plot $model energy" "$python" experiments/plot_run.py "$out/$model" --out "$out/${model}_energy.png"
done

echo
echo "Yarn crossings vs FEM surface at the same material (u, v), per output frame, and the error budget:"
cat "$out/compare.txt"
echo
echo "results in $out: compare.csv, compare.png, fem_tension.png, yarn_energy.png, fem_energy.png"
echo "(open $out/yarn/run.pvd and $out/fem/run.pvd in ParaView)"
