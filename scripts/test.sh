#!/usr/bin/env bash
# README command 2: install the Debian packages, build, and pass the tests: the Release
# suite (unit, physics, render, stress), then the sanitizer builds (ThreadSanitizer on the
# threaded tests, AddressSanitizer + UBSan on the unit tests; scripts/test-sanitizers.sh).
# Between the two, `huygens-bench --quick` (every section at CI size, about 2-3 minutes): it
# asserts no timing, but it must finish and its accuracy checks must pass (exit 0).
# HUYGENS_SKIP_SANITIZERS=1 runs the Release suite only; HUYGENS_SKIP_BENCH=1 skips the bench;
# HUYGENS_SKIP_FUZZ=1 skips scripts/test-fuzz.sh (the libFuzzer targets, after the bench);
# HUYGENS_SKIP_INSTALL_TEST=1 skips scripts/test-install.sh (the installed CMake package used by
# an outside project, right after ctest).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
# habits checked before the build: every C++ file clang-formatted, no function over 80 lines in
# core/, validation/, viz/, cli/, benchmarks/ and python/ (tests are lists of cases and may run longer)
bash "$root/scripts/check-format.sh"
(cd "$root" && python3 scripts/function_lengths.py core validation viz cli benchmarks python)
# The Release suite and the bench are built for the AVX2 + FMA baseline most users' CPUs have
# (x86-64-v3; HUYGENS_ISA=native measures this machine's own ISA), so CI measures what they get.
export HUYGENS_ISA=${HUYGENS_ISA:-x86-64-v3}
bash "$root/scripts/build.sh"
# OpenMP threads that sleep at barriers in the programs the suite runs (the tests themselves get
# one thread each from CTest's environment).
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
(cd "${HUYGENS_BUILD_DIR:-$root/build}" && ctest --output-on-failure -j "$(nproc)" --timeout 900)
[ "${HUYGENS_SKIP_INSTALL_TEST:-0}" = 1 ] || bash "$root/scripts/test-install.sh"  # find_package(huygens) from outside
if [ "${HUYGENS_SKIP_BENCH:-0}" != 1 ]; then
  echo "== huygens-bench --quick"
  "${HUYGENS_BUILD_DIR:-$root/build}/benchmarks/huygens-bench" --quick --csv "${HUYGENS_BUILD_DIR:-$root/build}/bench-quick.csv"
fi
# the libFuzzer targets (scene parser, .npy reader), HUYGENS_FUZZ_SECONDS each (default 60)
[ "${HUYGENS_SKIP_FUZZ:-0}" = 1 ] || bash "$root/scripts/test-fuzz.sh"
if [ "${HUYGENS_SKIP_SANITIZERS:-0}" != 1 ]; then
  bash "$root/scripts/test-sanitizers.sh"
fi
