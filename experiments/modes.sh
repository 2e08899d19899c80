#!/usr/bin/env bash
# The lowest vibration modes of the yarn level and the continuum on one scene
# (default hanging_wind.toml): with the first-guess continuum and, when the
# parameter file PARAMS exists (default: that of experiments/calibrate.sh), the
# calibrated one; then the charts. Extra arguments go to `weavelab modes`.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
scene=${SCENE:-experiments/scenes/hanging_wind.toml}
params=${PARAMS:-results/calibration/hanging_wind/params.toml}
out=${OUT:-results/modes/$(basename "$scene" .toml)}
build/weavelab modes "$scene" --count 20 --out "$out/first_guess" "$@"
folders=("$out/first_guess")
labels=(--label "first guess")
if [ -f "$params" ]; then
  build/weavelab modes "$scene" --count 20 --fem-params "$params" --out "$out/calibrated" "$@"
  folders+=("$out/calibrated")
  labels+=(--label calibrated)
else
  echo "modes.sh: no calibrated parameters at $params (run experiments/calibrate.sh); first guess only" >&2
fi
/usr/bin/python3 experiments/plot_modes.py "${folders[@]}" "${labels[@]}" --shapes 10 --out "$out/modes"
echo "modes.sh: results and charts in $out" >&2
