#!/usr/bin/env bash
# The Cusick-style drape at 65×65 (experiments/scenes/cusick_drape_65.toml,
# docs/models.md §3.11): the cloth dropped on a disk pedestal at both levels,
# its drape coefficient and fold count per frame (drape_measure.py), and the
# cost of contact at this size: the same scene without the pedestal run back
# to back in this invocation, median step wall time of each and their ratio.
# WL_DURATION (default 0.05 s) is the simulated time: the drape is still
# falling then; it settles only after seconds of simulated time.
# WL_LINEAR_SOLVER (e.g. umfpack) sets the step matrix solver of every run.
# WL_SCENE (default cusick_drape_65) names another scene of experiments/scenes,
# e.g. cusick_drape_33 (run until it settles: WL_DURATION=1 WL_FREE=0);
# WL_OUTPUT_INTERVAL replaces the scene's frame interval (s); WL_FREE=0 skips
# the runs without the pedestal (and cost.txt).
# Results under results/cusick/ (results/<scene>/ for another scene): the runs,
# drape_<model>.csv and cost.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
name=${WL_SCENE:-cusick_drape_65}
scene=experiments/scenes/$name.toml
out=results/cusick
if [ "$name" != cusick_drape_65 ]; then out=results/$name; fi
python=/usr/bin/python3
duration=${WL_DURATION:-0.05}
free=${WL_FREE:-1}
extra=()
if [ -n "${WL_LINEAR_SOLVER:-}" ]; then extra=(--linear-solver "$WL_LINEAR_SOLVER"); fi
if [ -n "${WL_OUTPUT_INTERVAL:-}" ]; then extra+=(--output-interval "$WL_OUTPUT_INTERVAL"); fi
tools/setup.sh
mkdir -p "$out"
"$python" - "$scene" <<'PY' >"$out/free.toml"
import re, sys
text = open(sys.argv[1]).read()
print(re.sub(r"\[\[obstacles\]\].*?(?=\n\[)", "", text, flags=re.S))
PY
runs=(drape free)
if [ "$free" = 0 ]; then runs=(drape); fi
for model in yarn fem; do
  for run in "${runs[@]}"; do
    s=$scene
    if [ "$run" = free ]; then s=$out/free.toml; fi
    echo "== $run, $model model, $duration s" >&2
    build/weavelab run "$s" --model "$model" --duration "$duration" "${extra[@]}" --quiet --out "$out/${run}_$model"
  done
  "$python" experiments/drape_measure.py "$out/drape_$model" "$scene" --out "$out/drape_$model.csv" | tail -1
done
if [ "$free" = 0 ]; then exit 0; fi
"$python" - "$out" <<'PY' | tee "$out/cost.txt"
import statistics, sys
sys.path.insert(0, "experiments")
import weavelab_io as io
out = sys.argv[1]
print("model  median step with pedestal [ms]  without [ms]  ratio  steps with/without")
for model in ("yarn", "fem"):
    w = {r: io.step_wall_times(io.read_metrics(f"{out}/{r}_{model}")) for r in ("drape", "free")}
    a, b = statistics.median(w["drape"]), statistics.median(w["free"])
    print(f"{model:5s}  {1e3 * a:.1f}  {1e3 * b:.1f}  {a / b:.2f}  {len(w['drape'])}/{len(w['free'])}")
PY
