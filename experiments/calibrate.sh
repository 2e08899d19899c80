#!/usr/bin/env bash
# Calibrates the continuum to the yarn level of the hanging-cloth fabric and
# validates it on two dynamic scenes; results and charts in results/calibration/.
# Extra arguments go to `weavelab calibrate` (e.g. --starts 8, --tests shear).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
out=${OUT:-results/calibration/hanging_wind}
build/weavelab calibrate experiments/scenes/hanging_wind.toml --out "$out" \
  --validate experiments/scenes/hanging_wind.toml --validate experiments/scenes/swing_17.toml "$@"
/usr/bin/python3 experiments/plot_calibration.py "$out"
echo "calibrate.sh: results and charts in $out" >&2
