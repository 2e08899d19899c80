#!/usr/bin/env bash
# The continuum calibrated to knit patches (docs/calibration.md §8): `weavelab
# calibrate` on an N × N patch (courses = wales = N, default 8) of each knit scene
# given (default stockinette and garter), once per continuum law — linear shear
# with the lock, the spline shear law, and each of them with the stretch's
# warp–weft coupling and quartic stiffening (`stretch`, `stretch-spline`,
# docs/models.md §6.3.1), each with residuals scaled by the
# curve's range and by the response at each load — then
# knit_calibration_table.py tabulates each curve's residual as % of its range per
# law and R(0) (OUT/table.md). WL_OUT changes the folder (default
# results/knit_calibration), WL_PATCH the patch, WL_SCENES the scenes, WL_TESTS the
# tests, WL_LAWS the laws; extra arguments go to every
# `weavelab calibrate` (e.g. --sliding).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${WL_OUT:-results/knit_calibration}
patch=${WL_PATCH:-8}
scenes=${WL_SCENES:-"stockinette garter"}
tests=${WL_TESTS:-uniaxial-warp,uniaxial-weft,biaxial,shear,bending-warp,bending-weft}
mkdir -p "$out"
for s in $scenes; do
  for law in ${WL_LAWS:-linear spline stretch stretch-spline}; do
    for residuals in range relative; do
      extra=()
      case $law in *spline) extra+=(--shear-spline 0.1,0.2,0.3,0.4) ;; esac
      case $law in stretch*) extra+=(--stretch-coupling --stretch-stiffening) ;; esac
      dir="$out/${s}_${law}_${residuals}"
      nice build/weavelab calibrate "experiments/scenes/knit_$s.toml" --patch "$patch" --tests "$tests" --starts 1 \
        --residuals "$residuals" "${extra[@]}" --quiet --out "$dir" "$@" || echo "knit_calibration.sh: $dir: exit $?" >&2
    done
  done
done
/usr/bin/python3 experiments/knit_calibration_table.py "$out" | tee "$out/table.md"
