#!/usr/bin/env bash
# Knit against woven under the same uniaxial load per width (docs/models.md
# §11.8): `weavelab pull` on an 8 × 8 stockinette patch of
# experiments/scenes/knit_stockinette.toml's yarn (rest tile of §11.3),
# pulled wale-wise (y) and course-wise (x), and on a flat plain weave of the
# same yarn type and radius whose spacing gives it the knit's yarn length per
# area; plot_knit_uniaxial.py interpolates the strain each reaches at the same
# F/W and writes the ratios (OUT/knit_uniaxial.txt) and the curves
# (OUT/knit_uniaxial.png). WL_OUT changes the folder (default results/knit_uniaxial).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${WL_OUT:-results/knit_uniaxial}
python=/usr/bin/python3
mkdir -p "$out"
sed -e 's/^courses = 16/courses = 8/' -e 's/^wales = 16/wales = 8/' experiments/scenes/knit_stockinette.toml >"$out/knit.toml"
knit_strains=0.01,0.02,0.04,0.07,0.1,0.15,0.2,0.3,0.4
for dir in y x; do
  build/weavelab pull "$out/knit.toml" --hold-z --direction "$dir" --strains "$knit_strains" --out "$out/knit_$dir" || true
done
# The woven: n × n crossings at spacing L with the knit's yarn length per area
# ρ = 2n / ((n − 1) L), about the knit patch's size.
read -r n spacing < <("$python" - "$out/knit_y/pull.json" <<'PY'
import json, sys
k = json.load(open(sys.argv[1]))
rho, size = k["yarn_length_per_area_per_m"], k["grip_distance_m"]
n = max(5, round(size * rho / 2.0) + 1)
print(n, 2.0 * n / ((n - 1) * rho))
PY
)
radius=$(sed -n 's/^radius_m = \([^ ]*\).*/\1/p' experiments/scenes/knit_stockinette.toml)
cat >"$out/woven.toml" <<TOML
# A flat plain weave with the knit's yarn (experiments/knit_uniaxial.sh).
[cloth]
warps = $n
wefts = $n
spacing_m = $spacing
radius_m = $radius
sliding = true
[yarn_types.default]
$(sed -n '/^\[yarn_types.default\]/,/^$/p' experiments/scenes/knit_stockinette.toml | sed -n '2,4p')
[pose]
kind = "flat"
[gravity]
acceleration_m_per_s2 = [0.0, 0.0, 0.0]
TOML
build/weavelab pull "$out/woven.toml" --hold-z --direction y --strains 0.0001,0.0002,0.0005,0.001,0.002,0.005,0.01,0.02,0.05 \
  --out "$out/woven_y" || true
"$python" experiments/plot_knit_uniaxial.py "$out" | tee "$out/knit_uniaxial.txt"
