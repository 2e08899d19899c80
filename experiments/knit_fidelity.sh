#!/usr/bin/env bash
# The knit's yarn level against its calibrated continuum (docs/models.md §11.9):
# `weavelab calibrate` fits the continuum to an N × N patch (default 8) of the
# scene's pattern, sliding frozen, one start, then `weavelab fidelity` runs the
# scene's ladder with that params.toml (fem_s1 and fem_s3 on the 12 × 14
# knit_hanging_14 scene) and reports each rung's distance to the yarn level at
# the stitch contacts beside each run's own time error, and its CPU time.
# WL_OUT changes the folder (default results/knit_fidelity), WL_SCENE the scene,
# WL_PATCH the patch, WL_TESTS the calibration's tests, WL_LAW the calibration's
# law options (e.g. "--stretch-coupling --stretch-stiffening", docs/models.md
# §6.3.1; default the linear law); extra arguments go to
# `weavelab fidelity` (e.g. --variants fem_s1).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${WL_OUT:-results/knit_fidelity}
scene=${WL_SCENE:-experiments/scenes/knit_hanging_14.toml}
patch=${WL_PATCH:-8}
tests=${WL_TESTS:-uniaxial-warp,uniaxial-weft,biaxial,shear,bending-warp,bending-weft}
read -r -a law <<<"${WL_LAW:-}"
mkdir -p "$out"
nice build/weavelab calibrate "$scene" --patch "$patch" --tests "$tests" --starts 1 "${law[@]}" --quiet --out "$out/calibration"
nice build/weavelab fidelity "$scene" --fem-params "$out/calibration/params.toml" --out "$out/fidelity" "$@"
