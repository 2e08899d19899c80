#!/bin/sh
# The speed table (README, "Benchmarks"): medians of interleaved runs of this
# build, a reference build and this build on one thread (speed_table.py).
# Usage: [WL_REFERENCE_BIN=PATH] [WL_SPEED_REPEATS=3] bench/speed_table.sh [ROW ...]
set -eu
exec /usr/bin/python3 "$(dirname "$0")/speed_table.py" "$@"
