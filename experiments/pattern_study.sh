#!/usr/bin/env bash
# The pattern study (docs/calibration.md): nine fabrics calibrated by Snakemake,
# locally on every core; results/pattern_study/parameters.{csv,md,png}.
# tools/setup.sh installs Debian's snakemake with the other packages when run as root.
# Extra arguments go to snakemake (e.g. --profile experiments/common/profiles/cluster).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
snakemake -s experiments/pattern_study/Snakefile --cores "$(nproc)" "$@"
