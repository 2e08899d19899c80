#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# (Debug: assertions on, at -O1 so the suite runs in reasonable time) in
# build-sanitize/ and runs it; any sanitizer report fails the test that
# triggered it. Arguments go to ctest, e.g. `tests/sanitize.sh -R IntegratorSuite`
# for a subset (default: the whole suite less the long simulations listed in
# tests/sanitize_skip.txt, which the Release suite runs). Slow (docs/design.md §10).
set -euo pipefail
cd "$(dirname "$0")/.."
# Under AddressSanitizer Eigen switches to its own aligned allocator, while the
# prebuilt Ceres library (not instrumented) keeps glibc's malloc, and the two
# would then free each other's blocks: glibc's malloc is 16-byte aligned, so
# both use it. hypre is left out (-DWEAVELAB_WITH_HYPRE=OFF): Open MPI, under it,
# keeps allocations to the end of the process that LeakSanitizer reports; this
# build thus also checks the build without hypre (its amg test skips, saying so).
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DWEAVELAB_TEST_TIMEOUT=3000 \
      -DWEAVELAB_WITH_HYPRE=OFF \
      ${WEAVELAB_CMAKE_ARGS:-} >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target weavelab_tests
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build-sanitize
if [ $# -eq 0 ]; then
  skip=$(grep -v '^#' ../tests/sanitize_skip.txt | grep -v '^$' | sed 's/\./\\./g' | paste -sd'|')
  set -- -E "^(${skip})\$"
fi
ctest --output-on-failure -j"$(nproc)" "$@"
