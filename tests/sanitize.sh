#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# (Debug: assertions on, at -O1 so the suite runs in reasonable time) in
# build-sanitize/ and runs it; any sanitizer report fails the run, the test that
# triggered it being the last one its log names. Arguments go to ctest, e.g. `tests/sanitize.sh -R IntegratorSuite`
# for a subset through ctest (default: the whole gtest suite less the long
# simulations listed in tests/sanitize_skip.txt, which the Release suite runs).
# The libraries compile as unity builds (CMakeLists.txt). Slow (docs/design.md §10).
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
      -DWEAVELAB_WITH_HYPRE=OFF -DCMAKE_UNITY_BUILD=ON \
      ${WEAVELAB_CMAKE_ARGS:-} >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target weavelab_tests
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build-sanitize
if [ $# -gt 0 ]; then
  exec ctest --output-on-failure -j"$(nproc)" "$@"
fi
# The whole suite: the gtest program itself, split into four shards per core
# (GTEST_TOTAL_SHARDS), rather than ctest's one process per test, whose start-up
# under the sanitizers costs more than most tests; more shards than cores even
# out the shards' unequal lengths. A shard's log is printed in full when it
# fails. The ctest tests of tests/fuzz/ run beside the shards.
skip=$(grep -v '^#' ../tests/sanitize_skip.txt | grep -v '^$' | paste -sd':')
shards=$((4 * $(nproc)))
pids=()
for ((k = 0; k < shards; ++k)); do
  GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$k \
    timeout "${WEAVELAB_SHARD_TIMEOUT:-3000}" ./weavelab_tests --gtest_filter="-${skip}" \
    >"shard_$k.log" 2>&1 &
  pids+=($!)
done
# The command line's fuzz (tests/fuzz/) drives the sanitized executable.
ctest --output-on-failure -R '^fuzz\.' >fuzz.log 2>&1 &
fuzz_pid=$!
failed=0
for ((k = 0; k < shards; ++k)); do
  if wait "${pids[$k]}"; then
    grep -E '^\[  PASSED  \]|^\[  SKIPPED \]' "shard_$k.log" | sed "s/^/shard $k: /"
  else
    echo "shard $k failed (exit $?): its log follows" >&2
    cat "shard_$k.log" >&2
    failed=1
  fi
done
if ! wait "$fuzz_pid"; then failed=1; fi
cat fuzz.log
exit $failed
