#!/usr/bin/env bash
# Obstacle scenes (docs/models.md §3.11): the cloth dropped on a sphere
# (sphere_drape.toml), on the same sphere as a triangle mesh, the shipped
# icosphere (mesh_sphere_drape.toml, §3.11.9), and onto a table and the floor
# below it (floor_table.toml), each at yarn level and as a continuum; then the
# cost of contact: the sphere scene against the same scene with its obstacle
# removed, both models, run back to back in this one invocation, median step
# wall time of each and their ratio; and on the sphere, the closest any node
# came to it over the frames and the vertical contact force on the cloth at the
# end. Last the mesh against the analytic sphere (mesh.txt): the closest any
# node came to each over the frames by that obstacle's own distance (‖x − c‖ − r;
# the exact point–triangle distance to the mesh as written in obstacles.pvd),
# the frames with a node inside, the median step of each and their ratio
# (reference: the analytic sphere), and the final positions' largest and RMS
# distance between the two beside each run's estimated time error there.
# Results under results/obstacles/: one run folder per scene and model (frames
# with contact_force, obstacles.pvd, metrics.csv, summary.json), cost.txt and mesh.txt.
# WL_DURATION replaces the simulated time (s).
set -euo pipefail
cd "$(dirname "$0")/.."
out=results/obstacles
python=/usr/bin/python3
duration=${WL_DURATION:-0.3}

tools/setup.sh
mkdir -p "$out"
for scene in sphere_drape mesh_sphere_drape floor_table; do
  # the two spheres are compared: each with its time error (docs/models.md §7.8)
  estimate=()
  if [ "$scene" != floor_table ]; then estimate=(--error-estimate); fi
  for model in yarn fem; do
    echo "== $scene, $model model, $duration s" >&2
    build/weavelab run "experiments/scenes/$scene.toml" --model "$model" --duration "$duration" "${estimate[@]}" \
      --quiet --out "$out/${scene}_$model"
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
"$python" - "$out" <<'PY' | tee "$out/mesh.txt"
import statistics, sys, tomllib
import numpy as np
sys.path.insert(0, "experiments")
import weavelab_io as io


def segment_distance(p, a, b):
    """Distance of points p (n, 3) to segments a→b (m, 3): (n, m)."""
    ab = b - a
    t = np.clip(np.einsum("nmk,mk->nm", p[:, None, :] - a[None], ab) / np.einsum("mk,mk->m", ab, ab), 0, 1)
    return np.linalg.norm(p[:, None, :] - (a[None] + t[..., None] * ab[None]), axis=2)


def mesh_distance(p, v, tri):
    """Exact distance of points p to the triangles, and whether each point is
    inside the (convex, closed) mesh: below every face plane."""
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    h = np.einsum("nmk,mk->nm", p[:, None, :] - a[None], n)  # signed plane distances
    q = p[:, None, :] - h[..., None] * n[None]  # projections on the planes
    inside_tri = np.ones(h.shape, bool)
    for u, w in ((a, b), (b, c), (c, a)):
        inside_tri &= np.einsum("nmk,mk->nm", np.cross(w - u, q - u[None]), n) >= 0
    d = np.where(inside_tri, np.abs(h), np.inf)
    for u, w in ((a, b), (b, c), (c, a)):
        d = np.minimum(d, segment_distance(p, u, w))
    return d.min(axis=1), (h < 0).all(axis=1)  # the written faces point out (oriented at load)


out = sys.argv[1]
with open("experiments/scenes/sphere_drape.toml", "rb") as f:
    sphere = tomllib.load(f)["obstacles"][0]
center, radius = np.array(sphere["center_m"]), sphere["radius_m"]
print("model  obstacle  closest node over the frames [m]  frames with a node inside  median step [ms]  "
      "steps  rejected")
for model in ("yarn", "fem"):
    rows, final = {}, {}
    for name in ("sphere_drape", "mesh_sphere_drape"):
        run = f"{out}/{name}_{model}"
        frames = io.read_frames(run)
        obstacle = dict(io.read_frames(run, "obstacles"))
        closest, inside = np.inf, 0
        for t, m in frames:
            if name == "sphere_drape":
                d = np.linalg.norm(m.points - center, axis=1) - radius
                closest, inside = min(closest, d.min()), inside + int((d < 0).any())
            else:
                o = obstacle[t]
                tri = next(c.data for c in o.cells if c.type == "triangle")
                d, ins = mesh_distance(m.points, o.points, tri)
                closest, inside = min(closest, d.min()), inside + int(ins.any())
        final[name] = frames[-1][1].points
        times = io.step_wall_times(io.read_metrics(run), run)
        summary = io.read_summary(run, required=True)
        rows[name] = (closest, inside, len(frames), statistics.median(times), len(times),
                      summary["statistics"].get("rejected_steps", 0))
        r = rows[name]
        print(f"{model:5s}  {'sphere' if name == 'sphere_drape' else 'mesh':8s}  {r[0]:.4e}  {r[1]}/{r[2]}  "
              f"{1e3 * r[3]:.3f}  {r[4]}  {r[5]}")
    gap = np.linalg.norm(final["mesh_sphere_drape"] - final["sphere_drape"], axis=1)
    err = {k: io.read_summary(f"{out}/{k}_{model}", required=True)["time_error"]["max_per_frame_m"][-1]
           for k in final}
    print(f"{model:5s}  step time mesh/sphere {rows['mesh_sphere_drape'][3] / rows['sphere_drape'][3]:.2f}; "
          f"final positions mesh vs sphere: largest {gap.max():.3e} m, RMS {np.sqrt((gap ** 2).mean()):.3e} m; "
          f"time error at the last frame (largest over nodes): sphere {err['sphere_drape']:.3e} m, "
          f"mesh {err['mesh_sphere_drape']:.3e} m")
PY
