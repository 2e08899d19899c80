#!/usr/bin/env bash
# Installs weavelab's Debian packages when missing (as root; otherwise prints
# the command to run), then configures and builds Release into build/.
# WEAVELAB_CMAKE_ARGS (default empty) holds extra arguments for the configure
# step, split at whitespace, e.g. WEAVELAB_CMAKE_ARGS=-DWEAVELAB_STRICT_WARNINGS=ON;
# like every -D option they stay in build/CMakeCache.txt for later runs.
# Used by tests/run_tests.sh and the experiment scripts.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libeigen3-dev libsuitesparse-dev libopenblas-dev
          libtomlplusplus-dev libcli11-dev libspectra-dev libgtest-dev libsundials-dev libceres-dev libcgal-dev libhypre-dev libopenmpi-dev
          python3 python3-numpy python3-meshio python3-matplotlib
          python3-dev pybind11-dev snakemake)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing ${missing[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "setup: missing Debian packages; run as root:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

read -r -a extra_cmake_args <<<"${WEAVELAB_CMAKE_ARGS:-}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${extra_cmake_args[@]}" >/dev/null
cmake --build build -j"$(nproc)"
