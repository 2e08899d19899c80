#!/usr/bin/env bash
# What time.exact_contact_jacobian costs (docs/models.md §3.6.1): the shipped
# 17×17 scene run for 0.05 s (50 be-newton steps) with F_n and F_u frozen and
# differentiated, alternating, RUNS times each; medians of the wall and CPU
# time per run and their ratio (reference: frozen), measured in this one run.
#   experiments/contact_jacobian_cost.sh [RUNS]      (default 5; about 2 min on 2 idle cores)
# WEAVELAB_BIN: the binary to time (default build/weavelab, built by tools/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -n "${WEAVELAB_BIN:-}" ] || tools/setup.sh >/dev/null
runs=${1:-5}
out=${OUT:-results/contact_jacobian_cost}
mkdir -p "$out"
scene=experiments/scenes/hanging_wind.toml
sed 's/^\[time\]$/[time]\nexact_contact_jacobian = true/' "$scene" >"$out/exact.toml"
cp "$scene" "$out/frozen.toml"
: >"$out/times.csv"
for r in $(seq "$runs"); do
  for kind in frozen exact; do
    /usr/bin/time -f "$kind,%e,%U,%S" -a -o "$out/times.csv" \
      ${WEAVELAB_BIN:-build/weavelab} run "$out/$kind.toml" --integrator be-newton --duration 0.05 --out "$out/run_$kind" --quiet
  done
done
/usr/bin/python3 - "$out/times.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.reader(open(sys.argv[1])))
med = {}
for kind in ("frozen", "exact"):
    wall = [float(r[1]) for r in rows if r[0] == kind]
    cpu = [float(r[2]) + float(r[3]) for r in rows if r[0] == kind]
    med[kind] = (statistics.median(wall), statistics.median(cpu))
    print(f"{kind:7s} median wall {med[kind][0]:.2f} s, CPU {med[kind][1]:.2f} s over {len(wall)} runs")
print(f"ratio exact/frozen: wall {med['exact'][0] / med['frozen'][0]:.2f}, CPU {med['exact'][1] / med['frozen'][1]:.2f}")
PY
