#!/usr/bin/env bash
# Are runs bitwise identical across reruns and thread counts? Runs a scene
# under several (OMP_NUM_THREADS, OPENBLAS_NUM_THREADS) settings and compares
# every frame file and the metrics (without the wall-time column) byte for byte
# against the first run. Usage:
#   experiments/determinism.sh [SCENE] [MODEL] [DURATION]   (defaults: hanging_wind.toml, yarn, the scene's)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-experiments/scenes/hanging_wind.toml}
model=${2:-yarn}
duration=${3:-}
bin=${WEAVELAB:-build/weavelab}
out=results/determinism/$(basename "$scene" .toml)_$model
rm -rf "$out"
mkdir -p "$out"
settings=("default default" "default default" "1 1" "2 2" "1 2" "2 1")
reference=""
for k in "${!settings[@]}"; do
  read -r omp blas <<<"${settings[$k]}"
  dir=$out/run$k
  env_args=()
  [[ $omp != default ]] && env_args+=("OMP_NUM_THREADS=$omp")
  [[ $blas != default ]] && env_args+=("OPENBLAS_NUM_THREADS=$blas")
  env "${env_args[@]}" "$bin" run "$scene" --model "$model" ${duration:+--duration "$duration"} --quiet --out "$dir"
  cut -d, -f1-5 "$dir/metrics.csv" >"$dir/metrics_no_wall.csv"
  verdict="reference"
  if [[ -n $reference ]]; then
    differing=0
    for f in "$reference"/frames/*.vtu "$reference/metrics_no_wall.csv"; do
      cmp -s "$f" "$dir/${f#"$reference"/}" || differing=$((differing + 1))
    done
    verdict=$([[ $differing == 0 ]] && echo "bitwise identical" || echo "$differing files differ")
  fi
  echo "OMP_NUM_THREADS=$omp OPENBLAS_NUM_THREADS=$blas: $verdict"
  reference=${reference:-$dir}
done
