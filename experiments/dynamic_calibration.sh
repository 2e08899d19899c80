#!/usr/bin/env bash
# Static against dynamic calibration of the continuum (docs/calibration.md §7.4).
# The continuum's stiffness is fitted to the first 20 frames (0.2 s) of the yarn
# level's hanging_wind trajectory, starting from the static calibration of
# experiments/calibrate.sh; then both parameter sets are run on the whole
# hanging_wind scene and on the held-out swing_17 scene and compared with the
# yarn level at the crossings (experiments/compare.py).
# Writes results/dynamic_calibration/ and its summary.md. About 10 min on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
out=${OUT:-results/dynamic_calibration}
static=${STATIC:-results/calibration/hanging_wind/params.toml}
[ -f "$static" ] || { echo "dynamic_calibration.sh: $static missing: run experiments/calibrate.sh first" >&2; exit 2; }
mkdir -p "$out"
py=/usr/bin/python3

for s in hanging_wind swing_17; do
  [ -f "$out/yarn_$s/summary.json" ] || build/weavelab run "experiments/scenes/$s.toml" --out "$out/yarn_$s" --quiet
done

free=fem.warp_stretch_N_per_m,fem.weft_stretch_N_per_m,fem.shear_N_per_m,fem.warp_bending_N_m,fem.weft_bending_N_m
build/weavelab fit experiments/scenes/hanging_wind.toml --target "$out/yarn_hanging_wind" --model fem \
  --integrator be-newton --frames 20 --free "$free" --fem-params "$static" --out "$out/fit" || true
$py experiments/plot_fit.py "$out/fit"

{
  echo "| scene | continuum | mean RMS distance to the yarn level [mm] | max [mm] |"
  echo "|---|---|---|---|"
  for s in hanging_wind swing_17; do
    for kind in static dynamic; do
      params=$static
      [ $kind = dynamic ] && params=$out/fit/params.toml
      build/weavelab run "experiments/scenes/$s.toml" --model fem --fem-params "$params" --out "$out/fem_${kind}_$s" --quiet
      $py experiments/compare.py "$out/yarn_$s" "$out/fem_${kind}_$s" --out "$out/distance_${kind}_$s.csv" >/dev/null
      $py - "$out/distance_${kind}_$s.csv" "$s" "$kind" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
col = next(c for c in rows[0] if c.startswith("rms"))
mcol = next(c for c in rows[0] if c.startswith("max"))
rms = [float(r[col]) for r in rows]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {1e3 * sum(rms) / len(rms):.3f} | {1e3 * max(float(r[mcol]) for r in rows):.3f} |")
PY
    done
  done
} > "$out/summary.md"
cat "$out/summary.md"
