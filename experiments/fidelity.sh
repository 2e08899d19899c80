#!/usr/bin/env bash
# The fidelity ladder on the hanging cloth: 17×17 over the published 0.5 s at
# the controlled resolution with the time rungs and every run's own time error
# (docs/models.md §7.11; CPU times the medians of 3 runs), and 65×65 over 0.2 s
# at the scene's step without time errors (one run each: the full yarn model
# costs about 0.8 s per step there on one thread, so the controlled resolution
# and the estimates would take hours; its distances carry the time error the
# 17×17 ladder measures). The
# continuum is calibrated first on a 17×17 patch of each scene's fabric (one
# start; reused when results/calibration/<scene>_fidelity/params.toml exists).
# Results and Pareto charts in results/fidelity/<scene>/.
# CPU times are of one thread (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1): a
# busy machine inflates multi-threaded CPU time through spinning threads.
# Each ladder is a Snakemake workflow (experiments/fidelity/Snakefile): the
# reference once, then one job per rung on every core, cached by the scene's
# hash, the options and the program, so a rerun only runs what changed.
# WL_OPTIONS adds options of `weavelab fidelity` (e.g. WL_OPTIONS="--tolerance
# 0.0008"); extra arguments go to snakemake (e.g. --cores 1, or --profile
# experiments/common/profiles/cluster).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
start=$(date +%s)
model_rungs=no_friction,no_parallel_contact,linear_shear,frozen_sliding,fem_s1,fem_s2,fem_s4,fem_first_guess
for spec in hanging_wind:0.5:3:controlled hanging_wind_65:0.2:1:scene; do  # scene:duration:repeats:resolution
  IFS=: read -r name duration repeats resolution <<<"$spec"
  cal=results/calibration/${name}_fidelity
  [ -f "$cal/params.toml" ] ||
    build/weavelab calibrate "experiments/scenes/$name.toml" --patch 17 --starts 1 --quiet --out "$cal"
  options="--duration $duration --repeats $repeats --fem-params $cal/params.toml --resolution $resolution"
  config=(scene="experiments/scenes/$name.toml" out="results/fidelity/$name")
  if [ "$resolution" = scene ]; then options+=" --no-error-estimate"; config+=(variants="$model_rungs"); fi
  snakemake -s experiments/fidelity/Snakefile --cores "$(nproc)" \
    --config "${config[@]}" options="$options ${WL_OPTIONS:-}" "$@"
done
echo "fidelity.sh: $(( $(date +%s) - start )) s wall (without the build); results in results/fidelity/" >&2
