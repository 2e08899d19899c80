#!/usr/bin/env bash
# The bending-length test (experiments/scenes/cantilever_ledge.toml, docs/models.md
# §3.11): the strip pushed over a ledge at both levels; the overhang l at which
# the edge-to-tip line first falls 41.5° below the horizontal gives the measured
# bending length c = 0.509 l (Peirce); the prediction is c = (G/W)^(1/3) with
# the continuum's warp bending stiffness G [N·m] and weight per area W, as the
# FEM model states them (`weavelab info --model fem`, with WL_FEM_PARAMS: the
# parameters of a calibration, else those derived from the yarns, docs/models.md §6.7).
# WL_FEM_LAW=grid_lines runs the continuum with grid-line bending and the yarn
# level's node masses ([fem] grid_line_bending, yarn_node_mass; docs/models.md
# §6.5.2, §6.6) on a copy of the scene. WL_OUT changes the folder.
# Results under results/cantilever/: the two runs and bending_length.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
source experiments/jobs.sh  # both models at once (WL_JOBS=1: one after the other)
scene=experiments/scenes/cantilever_ledge.toml
out=${WL_OUT:-results/cantilever}
python=/usr/bin/python3
params=()
if [ -n "${WL_FEM_PARAMS:-}" ]; then params=(--fem-params "$WL_FEM_PARAMS"); fi
tools/setup.sh
mkdir -p "$out"
case ${WL_FEM_LAW:-hinges} in
  hinges) ;;
  grid_lines)
    { cat "$scene"; printf '\n[fem]\ngrid_line_bending = true\nyarn_node_mass = true\n'; } >"$out/scene.toml"
    scene=$out/scene.toml ;;
  *) echo "cantilever.sh: WL_FEM_LAW: got '$WL_FEM_LAW', expected hinges or grid_lines" >&2; exit 2 ;;
esac
for model in yarn fem; do
  echo "== $model model" >&2
  extra=()
  if [ "$model" = fem ]; then extra=("${params[@]}"); fi
  job build/weavelab run "$scene" --model "$model" "${extra[@]}" --quiet --out "$out/$model"
done
wait_jobs
build/weavelab info "$scene" --model fem "${params[@]}" >"$out/fem_info.txt"
"$python" - "$scene" "$out" <<'PY' | tee "$out/bending_length.txt"
import math, re, sys, tomllib
import numpy as np
sys.path.insert(0, "experiments")
import weavelab_io as io
scene_path, out = sys.argv[1], sys.argv[2]
with open(scene_path, "rb") as f:
    scene = tomllib.load(f)
ledge = scene["obstacles"][0]
edge0 = ledge["center_m"][0] + ledge["half_extents_m"][0]
speed = -ledge["velocity_m_per_s"][0]
top = ledge["center_m"][2] + ledge["half_extents_m"][2]
nu, nv = scene["cloth"]["wefts"], scene["cloth"]["warps"]
length = (nu - 1) * scene["cloth"]["spacing_m"]
theta = math.radians(41.5)
peirce = (math.cos(theta / 2) / (8 * math.tan(theta))) ** (1 / 3)
facts = dict(re.findall(r"(\w+)=([0-9.eE+-]+)", open(f"{out}/fem_info.txt").read()))
g = -scene["gravity"]["acceleration_m_per_s2"][2]
G, rho = float(facts["warp_bending_N_m"]), float(facts["areal_density_kg_per_m2"])
predicted = (G / (rho * g)) ** (1 / 3)
print(f"predicted c = (G/W)^(1/3) = {predicted * 1e3:.2f} mm (G = {G:.4g} N m, W = {rho * g:.4g} N/m2)")
for model in ("yarn", "fem"):
    prev, found = None, None
    for t, mesh in io.read_frames(f"{out}/{model}"):
        strip = mesh.points.reshape(nv, nu, 3)[nv // 2]
        edge = edge0 - speed * t
        tip = strip[-1]
        if tip[0] > edge:
            angle = math.atan2(top - tip[2], tip[0] - edge)
            overhang = length - edge
            if prev and prev[0] < theta <= angle:
                f = (theta - prev[0]) / (angle - prev[0])
                found = ((1 - f) * prev[1] + f * overhang, t)
                break
            prev = (angle, overhang)
    if not found:
        print(f"{model}: the tip never fell to 41.5 degrees")
        continue
    c = peirce * found[0]
    print(f"{model}: overhang at 41.5 deg {found[0] * 1e3:.2f} mm (t = {found[1]:.2f} s), "
          f"c = {c * 1e3:.2f} mm, {100 * (c / predicted - 1):+.1f} % from the prediction")
PY
