#!/usr/bin/env bash
# Builds weavelab (installing its Debian packages if needed) and runs the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
cd build
ctest --output-on-failure -j"$(nproc)"
