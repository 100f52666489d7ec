#!/usr/bin/env bash
# CI sanitizer jobs:
#   1. ThreadSanitizer build of the tests that exercise threads (the executables whose
#      huygens_add_test line has the label "tsan": the SPSC queue, the frame ring and the
#      runner), run with a smaller stress count.
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build of the whole test suite
#      (ctest label ${HUYGENS_ASAN_LABEL:-unit}; set HUYGENS_ASAN_LABEL= for every test).
# Build dirs: ${HUYGENS_TSAN_DIR:-build-tsan} and ${HUYGENS_ASAN_DIR:-build-asan}. The viewer
# is not built here (Mesa's llvmpipe is not instrumented; the render tests run in test.sh).
# HUYGENS_STRESS_ITEMS sets the stress item count under TSan: the SPSC queue runs 4 million
# items per capacity (10 million in the Release suite), the frame ring and the runner (whole
# frames checked value by value) 200000 unless it is set.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc)
tsan=${HUYGENS_TSAN_DIR:-$root/build-tsan}
asan=${HUYGENS_ASAN_DIR:-$root/build-asan}
asan_label=${HUYGENS_ASAN_LABEL-unit}
# -O1 -g1 (line tables: the sanitizers' stack traces keep file:line): about half the compile time
# of RelWithDebInfo's -O2 -g under the sanitizers (the JSON-heavy sources most), and the
# instrumented tests run in well under a minute either way
opt="-O1 -g1 -DNDEBUG"
common=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$opt" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$opt"
  -DHUYGENS_BUILD_VIZ=OFF -DHUYGENS_BUILD_BENCHMARKS=OFF)
t0=$SECONDS
# OpenMP threads that sleep instead of spinning at barriers: on a 2-core runner shared by two
# ctest jobs, spinning threads slow the threaded tests down by 10-20x
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}

# ---- ThreadSanitizer: only the executables whose huygens_add_test line carries the tsan label
mapfile -t tsan_targets < <(grep -E '^\s*huygens_add_test\(\w+ .*LABELS[^)]*\btsan\b' "$root/tests/CMakeLists.txt" |
  sed -E 's/^\s*huygens_add_test\((\w+).*/\1/')
if [ "${#tsan_targets[@]}" -eq 0 ]; then
  echo "test-sanitizers: no test carries the tsan label" >&2
  exit 1
fi
echo "== ThreadSanitizer: ${tsan_targets[*]}"
cmake -S "$root" -B "$tsan" "${common[@]}" -DHUYGENS_SANITIZE=thread >/dev/null
cmake --build "$tsan" -j "$jobs" --target "${tsan_targets[@]}"
# the executables are run directly (so the environment CTest would set is set here): with CMake < 3.27, gtest_discover_tests keeps only the
# first label of a test, so `ctest -L tsan` cannot be relied on
for t in "${tsan_targets[@]}"; do
  echo "-- $t (TSan)"
  items=200000
  [ "$t" = spsc_queue_test ] && items=4000000
  # one OpenMP thread: libgomp is not instrumented, so TSan cannot see its barriers and would
  # report every parallel loop (a solver built in a test) as a race; the threads under test
  # here are the project's own (queue, ring, runner)
  HUYGENS_STRESS_ITEMS=${HUYGENS_STRESS_ITEMS:-$items} OMP_NUM_THREADS=1 HUYGENS_SCENES_DIR="$root/scenes" \
    TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ${TSAN_OPTIONS:-}" \
    "$tsan/tests/$t" --gtest_brief=1
done
echo "== ThreadSanitizer done after $((SECONDS - t0)) s"

# ---- AddressSanitizer + UndefinedBehaviorSanitizer: the whole suite (label filter above)
echo "== AddressSanitizer + UBSan: ctest ${asan_label:+-L $asan_label}"
cmake -S "$root" -B "$asan" "${common[@]}" -DHUYGENS_SANITIZE=address >/dev/null
cmake --build "$asan" -j "$jobs"
# ctest starts the longest tests first when it knows their cost; a fresh build dir knows none,
# and a long test then starts late and runs alone at the end: seed the costs from the Release
# run of test.sh (same test names)
release_costs=${HUYGENS_BUILD_DIR:-$root/build}/Testing/Temporary/CTestCostData.txt
if [ -f "$release_costs" ] && [ ! -f "$asan/Testing/Temporary/CTestCostData.txt" ]; then
  mkdir -p "$asan/Testing/Temporary" && cp "$release_costs" "$asan/Testing/Temporary/"
fi
(cd "$asan" && HUYGENS_STRESS_ITEMS=${HUYGENS_STRESS_ITEMS:-200000} \
  ASAN_OPTIONS="detect_leaks=1 abort_on_error=1 ${ASAN_OPTIONS:-}" \
  UBSAN_OPTIONS="print_stacktrace=1 halt_on_error=1 ${UBSAN_OPTIONS:-}" \
  ctest ${asan_label:+-L "$asan_label"} --output-on-failure -j "$jobs" --timeout 900)
echo "== sanitizers done after $((SECONDS - t0)) s"
