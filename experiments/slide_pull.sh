#!/usr/bin/env bash
# The slide-pull scene (experiments/scenes/slide_pull_7.toml, docs/calibration.md §7.5): the run at its
# μ and at 2μ, both at the scene's step with their time errors, compared frame by frame with each run's
# slide indicator; then the same pair with hanging_wind.toml's friction damping d_f = 1000 N·s/m.
# Writes results/slide_pull/<run>/ and results/slide_pull/table.md. About 1 min of CPU.
set -euo pipefail
scene=experiments/scenes/slide_pull_7.toml out=${OUT:-results/slide_pull}
cd "$(dirname "$0")/.." && tools/setup.sh >/dev/null && mkdir -p "$out"
mu=$(/usr/bin/python3 -c "import sys, tomllib; print(tomllib.load(open(sys.argv[1], 'rb'))['contact']['friction_coefficient'])" "$scene")
mu2=$(/usr/bin/python3 -c "import sys; print(2 * float(sys.argv[1]))" "$mu")

pair() {  # name sed-expression: the scene at μ and at 2μ, each with its time error
  for m in "$mu" "$mu2"; do
    sed -e "s/^friction_coefficient = [^ ]*/friction_coefficient = $m/" -e "$2" "$scene" > "$out/$1_mu_$m.toml"
    build/weavelab run "$out/$1_mu_$m.toml" --error-estimate --quiet --out "$out/$1_mu_$m"
  done
  echo "### $1: μ = $mu (A) against 2μ = $mu2 (B)"
  echo
  /usr/bin/python3 experiments/slide_pull_table.py "$out/$1_mu_$mu" "$out/$1_mu_$mu2"
  echo
}
{
  pair scene ""
  pair shipped_damping "s/^friction_damping_Ns_per_m = [^ ]*/friction_damping_Ns_per_m = 1000.0/"
} > "$out/table.md"
cat "$out/table.md"
