#!/usr/bin/env bash
# Obstacle scenes (docs/models.md §3.11): the cloth dropped on a sphere
# (sphere_drape.toml) and onto a table and the floor below it
# (floor_table.toml), each at yarn level and as a continuum; then the cost of
# contact: the sphere scene against the same scene with its obstacle removed,
# both models, run back to back in this one invocation, median step wall time
# of each and their ratio; and on the sphere, the closest any node came to it
# over the frames and the vertical contact force on the cloth at the end.
# Results under results/obstacles/: one run folder per scene and model (frames
# with contact_force, obstacles.pvd, metrics.csv, summary.json) and cost.txt.
# WL_DURATION replaces the simulated time (s).
set -euo pipefail
cd "$(dirname "$0")/.."
out=results/obstacles
python=/usr/bin/python3
duration=${WL_DURATION:-0.3}

tools/setup.sh
mkdir -p "$out"
for scene in sphere_drape floor_table; do
  for model in yarn fem; do
    echo "== $scene, $model model, $duration s" >&2
    build/weavelab run "experiments/scenes/$scene.toml" --model "$model" --duration "$duration" --quiet \
      --out "$out/${scene}_$model"
  done
done
# The sphere scene without its obstacle (the [[obstacles]] entry removed).
"$python" - <<'PY' >"$out/sphere_free.toml"
import re
text = open("experiments/scenes/sphere_drape.toml").read()
print(re.sub(r"\[\[obstacles\]\].*?(?=\n\[)", "", text, flags=re.S))
PY
for model in yarn fem; do
  echo "== sphere_drape without the sphere, $model model" >&2
  build/weavelab run "$out/sphere_free.toml" --model "$model" --duration "$duration" --quiet \
    --out "$out/sphere_free_$model"
done
"$python" - "$out" <<'PY' | tee "$out/cost.txt"
import statistics, sys, tomllib
import numpy as np
sys.path.insert(0, "experiments")
import weavelab_io as io
out = sys.argv[1]
with open("experiments/scenes/sphere_drape.toml", "rb") as f:
    sphere = tomllib.load(f)["obstacles"][0]
center, radius = np.array(sphere["center_m"]), sphere["radius_m"]
print("model  closest node to the sphere over the frames [m]  contact force z at the end [N]")
for model in ("yarn", "fem"):
    frames = io.read_frames(f"{out}/sphere_drape_{model}")
    closest = min((np.linalg.norm(m.points - center, axis=1) - radius).min() for _, m in frames)
    force = frames[-1][1].point_data["contact_force"][:, 2].sum()
    print(f"{model:5s}  {closest:.3e}  {force:.4e}")
print("model  median step with sphere [ms]  without [ms]  ratio  steps with/without  rejected with")
for model in ("yarn", "fem"):
    runs = {}
    for name in ("sphere_drape", "sphere_free"):
        run = f"{out}/{name}_{model}"
        runs[name] = (io.step_wall_times(io.read_metrics(run), run), io.read_summary(run, required=True))
    w, wo = (statistics.median(runs[k][0]) for k in ("sphere_drape", "sphere_free"))
    rej = runs["sphere_drape"][1]["statistics"].get("rejected_steps", 0)
    print(f"{model:5s}  {1e3 * w:.3f}  {1e3 * wo:.3f}  {w / wo:.2f}  "
          f"{len(runs['sphere_drape'][0])}/{len(runs['sphere_free'][0])}  {rej}")
PY
