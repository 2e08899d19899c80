#!/usr/bin/env bash
# The pattern study (docs/calibration.md): nine fabrics calibrated by Snakemake,
# locally on every core; results/pattern_study/parameters.{csv,md,png}.
# Extra arguments go to snakemake (e.g. --profile experiments/pattern_study/profiles/cluster).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
command -v snakemake >/dev/null || { echo "pattern_study.sh: needs Debian's snakemake (apt-get install snakemake)" >&2; exit 1; }
snakemake -s experiments/pattern_study/Snakefile --cores "$(nproc)" "$@"
