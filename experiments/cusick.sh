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
# WL_SETTLE_DT (s) with WL_SETTLE_AFTER (s, default 0.2): from that time on, the
# drape runs take backward Euler steps of WL_SETTLE_DT (time.settle_dt_s,
# docs/models.md §3.11.6) so that it settles; summary.json's "settle" gives the
# end state's largest force and kinetic energy.
# WL_MODELS (default "yarn fem") chooses the models.
# WL_STEP_HESSIAN (projected | exact) sets the step matrices' Hessians of the
# contact barrier and the yarn stretch ([obstacle_contact] step_hessian and
# [terms] stretch_step_hessian, docs/models.md §3.11.2, §3.2); unset: the scene's.
# WL_SELF_CONTACT=1 runs the drape with cloth–cloth contact ([self_contact],
# docs/models.md §3.11.7), into the results folder with _self appended; WL_SELF_STIFFNESS (N/m)
# sets its κ (stiffness_N_per_m).
# Results under results/cusick/ (results/<scene>/ for another scene): the runs,
# drape_<model>.csv (with kinetic energy, intersecting triangle pairs and the
# closest node to the pedestal per frame) and cost.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
name=${WL_SCENE:-cusick_drape_65}
scene=experiments/scenes/$name.toml
out=results/cusick
if [ "$name" != cusick_drape_65 ]; then out=results/$name; fi
self=${WL_SELF_CONTACT:-0}
case $self in 0 | 1) ;; *) echo "cusick.sh: WL_SELF_CONTACT: got '$self', expected 0 or 1" >&2; exit 2 ;; esac
if [ "$self" = 0 ] && [ -n "${WL_SELF_STIFFNESS:-}" ]; then
  echo "cusick.sh: WL_SELF_STIFFNESS is set without WL_SELF_CONTACT=1" >&2; exit 2
fi
if [ "$self" = 1 ]; then out=${out}_self; fi
step_hessian=${WL_STEP_HESSIAN:-}
case $step_hessian in "" | projected | exact) ;; *) echo "cusick.sh: WL_STEP_HESSIAN: got '$step_hessian', expected projected or exact" >&2; exit 2 ;; esac
python=/usr/bin/python3
duration=${WL_DURATION:-0.05}
free=${WL_FREE:-1}
extra=()
if [ -n "${WL_LINEAR_SOLVER:-}" ]; then extra=(--linear-solver "$WL_LINEAR_SOLVER"); fi
if [ -n "${WL_OUTPUT_INTERVAL:-}" ]; then extra+=(--output-interval "$WL_OUTPUT_INTERVAL"); fi
tools/setup.sh
mkdir -p "$out"
# The scene with WL_STEP_HESSIAN's choice for the barrier and the yarn stretch.
"$python" - "$scene" "$step_hessian" <<'PY' >"$out/scene.toml"
import re, sys
text, choice = open(sys.argv[1]).read(), sys.argv[2]
if choice:
    if "[obstacle_contact]" in text or not re.search(r"^stretch_step_hessian = ", text, flags=re.M):
        print("cusick.sh: WL_STEP_HESSIAN needs a scene without [obstacle_contact] and with"
              " [terms] stretch_step_hessian", file=sys.stderr)
        sys.exit(2)
    text = re.sub(r"^stretch_step_hessian = .*$", f'stretch_step_hessian = "{choice}"', text, flags=re.M)
    text += f'\n[obstacle_contact]\nstep_hessian = "{choice}"\n'
print(text)
PY
"$python" - "$out/scene.toml" <<'PY' >"$out/free.toml"
import re, sys
text = open(sys.argv[1]).read()
print(re.sub(r"\[\[obstacles\]\].*?(?=\n\[)", "", text, flags=re.S))
PY
# The drape scene as run, with the settling phase if WL_SETTLE_DT is set.
"$python" - "$out/scene.toml" "${WL_SETTLE_AFTER:-0.2}" "${WL_SETTLE_DT:-}" "$duration" "$self" "${WL_SELF_STIFFNESS:-}" <<'PY' >"$out/drape.toml"
import re, sys
text, after, dt, duration = open(sys.argv[1]).read(), sys.argv[2], sys.argv[3], sys.argv[4]
if sys.argv[5] == "1":
    text += "\n[self_contact]\nenabled = true\n"
    if sys.argv[6]:
        text += f"stiffness_N_per_m = {sys.argv[6]}\n"
if dt:  # the scene's own duration must reach past settle_after_s
    text = re.sub(r"^duration_s = .*$", f"duration_s = {duration}", text, flags=re.M)
    text = re.sub(r"^\[time\]\n", f"[time]\nsettle_after_s = {after}\nsettle_dt_s = {dt}\n", text, flags=re.M)
print(text)
PY
runs=(drape free)
if [ "$free" = 0 ]; then runs=(drape); fi
for model in ${WL_MODELS:-yarn fem}; do
  for run in "${runs[@]}"; do
    echo "== $run, $model model, $duration s" >&2
    build/weavelab run "$out/$run.toml" --model "$model" --duration "$duration" "${extra[@]}" --quiet \
      --out "$out/${run}_$model"
  done
  "$python" experiments/drape_measure.py "$out/drape_$model" "$scene" --state --out "$out/drape_$model.csv" | tail -2
done
if [ "$free" = 0 ]; then exit 0; fi
"$python" - "$out" ${WL_MODELS:-yarn fem} <<'PY' | tee "$out/cost.txt"
import statistics, sys
sys.path.insert(0, "experiments")
import weavelab_io as io
out = sys.argv[1]
print("model  run    median step [ms]  ratio to free  steps  factorizations  GMRES iterations  solver")
for model in sys.argv[2:]:
    w = {r: io.step_wall_times(io.read_metrics(f"{out}/{r}_{model}"))
         for r in ("free", "drape")}
    free = statistics.median(w["free"])
    for r, times in w.items():
        st = io.read_summary(f"{out}/{r}_{model}")["statistics"]
        a = statistics.median(times)
        print(f"{model:5s}  {r:5s}  {1e3 * a:.1f}  {a / free:.2f}  {len(times)}  {st.get('factorizations')}"
              f"  {st.get('krylov_iters')}  {st.get('linear_solver')}")
PY
