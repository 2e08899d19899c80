#!/bin/sh
# Wall time and steps of every integrator on a scene, for the yarn and the FEM
# model, from the run summaries of `weavelab run` (one line per pair).
# Usage: bench/integrator_timing.sh [WEAVELAB] [SCENE] [DURATION_S]
set -eu
bin=${1:-build/weavelab}
scene=${2:-experiments/scenes/hanging_wind.toml}
duration=${3:-0.01}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-6s %-12s %-15s %8s %7s %8s %8s %8s\n' model integrator outcome wall_s steps nl_iters setups solves
for model in yarn fem; do
  for integ in be-linear be-newton ida arkode-erk arkode-dirk arkode-imex symplectic; do
    dir="$out/$model-$integ"
    "$bin" run "$scene" --model "$model" --integrator "$integ" --duration "$duration" --out "$dir" --quiet \
      >/dev/null 2>&1 || true
    /usr/bin/python3 - "$dir" "$model" "$integ" <<'PY'
import json, sys, pathlib
d, model, integ = sys.argv[1:]
files = list(pathlib.Path(d).glob("**/*summary*.json"))
if not files:
    print(f"{model:6s} {integ:12s} (no summary)"); sys.exit()
j = json.load(open(files[0]))
s, r = j["statistics"], j["result"]
print(f"{model:6s} {integ:12s} {r['outcome']:15s} {s['wall_s']:8.3f} {s['steps']:7d} {s['nonlinear_iters']:8d} "
      f"{s['linear_setups']:8d} {s['linear_solves']:8d}")
PY
  done
done
