#!/usr/bin/env bash
# Free knit patches (docs/models.md §11): the stockinette, garter and 2×2 rib
# scenes (experiments/scenes/knit_*.toml, 16 courses × 16 wales, no gravity)
# released at their tiled rest shapes and run for 150 ms (the scenes' 50 ms
# do not reach the settled curl); plot_knits.py measures the curl at the
# edges and the width along the course over time. Then the scale probe: a
# 72 × 72 stockinette (10 224 stitch contacts) and the 129 × 129 woven cloth,
# a few be-newton steps each in this one script, step time and peak memory per
# DoF side by side. WL_OUT changes the folder (default results/knits);
# WL_DURATION the simulated time of the patches (default 0.15 s);
# WL_SKIP_SCALE=1 skips the scale probe, WL_ONLY_SCALE=1 runs it alone.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${WL_OUT:-results/knits}
python=/usr/bin/python3
tools/setup.sh
mkdir -p "$out"
args=()
kinds="stockinette garter rib"
if [ "${WL_ONLY_SCALE:-0}" = 1 ]; then kinds=""; fi
for kind in $kinds; do
  scene=experiments/scenes/knit_$kind.toml
  echo "== $kind" >&2
  build/weavelab run "$scene" --duration "${WL_DURATION:-0.15}" --output-interval 0.01 --quiet --out "$out/$kind"
  args+=("$scene:$out/$kind")
done
if [ -n "$kinds" ]; then "$python" experiments/plot_knits.py "$out" "${args[@]}" | tee "$out/knits.txt"; fi

if [ "${WL_SKIP_SCALE:-0}" = 1 ]; then exit 0; fi
# Scale: the same three steps of 0.5 ms on a knit and on a woven cloth.
{ sed -e 's/^courses = 16/courses = 72/' -e 's/^wales = 16/wales = 72/' experiments/scenes/knit_stockinette.toml
} >"$out/knit_72.toml"
for name in knit_72 woven_129; do
  scene=$out/knit_72.toml
  if [ "$name" = woven_129 ]; then scene=experiments/scenes/hanging_wind_129.toml; fi
  build/weavelab info "$scene" >"$out/$name.info"
  /usr/bin/time -v build/weavelab run "$scene" --integrator be-newton --dt 0.0005 --duration 0.0015 --output-interval 0.0015 \
    --quiet --out "$out/$name" 2>"$out/$name.time"
done
"$python" - "$out" <<'PY' | tee "$out/scale.txt"
import os, re, sys
sys.path.insert(0, "experiments")
import numpy as np
import weavelab_io as io
out = sys.argv[1]
rows = {}
for name in ("knit_72", "woven_129"):
    info = dict(re.findall(r"^(\w+): (.*)$", open(f"{out}/{name}.info").read(), re.M))
    rss_kb = float(re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(f"{out}/{name}.time").read()).group(1))
    wall = io.step_wall_times(io.read_metrics(f"{out}/{name}"))
    dofs = int(info["dofs"])
    rows[name] = (dofs, float(np.median(wall)), rss_kb * 1024.0)
    extra = f", {info['stitch_contacts']} stitch contacts" if "stitch_contacts" in info else ""
    print(f"{name}: {dofs} DoFs{extra}; median step {np.median(wall):.3f} s over {len(wall)} steps "
          f"({1e6 * np.median(wall) / dofs:.2f} us per DoF); peak RSS {rss_kb / 1024:.0f} MB "
          f"({rss_kb * 1024 / dofs / 1024:.2f} kB per DoF)")
k, w = rows["knit_72"], rows["woven_129"]
print(f"knit / woven per DoF: step time {(k[1] / k[0]) / (w[1] / w[0]):.2f}, peak memory {(k[2] / k[0]) / (w[2] / w[0]):.2f}")
PY
