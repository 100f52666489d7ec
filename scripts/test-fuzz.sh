#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, ASan + UBSan, the core library only) into
# build-fuzz and runs each for a bounded time, failing on any crash, sanitizer report, leak,
# uncaught exception or time-out (docs/robustness.md, "Fuzzing").
#   HUYGENS_FUZZ_SECONDS   time per target (default 60)
#   HUYGENS_FUZZ_BUILD_DIR build folder (default build-fuzz)
# Seeds: tests/fuzz/corpus/<target>/ (and scenes/ for the scene target); the units the fuzzer adds
# go to BUILD/corpus/<target>/, a crashing input to BUILD/artifacts/ (reproduce: BUILD/fuzz_<target>
# FILE).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HUYGENS_FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${HUYGENS_FUZZ_SECONDS:-60}
cc=$(command -v clang || command -v clang-14 || true)
cxx=$(command -v clang++ || command -v clang++-14 || true)
if [ -z "$cxx" ] || [ -z "$cc" ]; then
  echo "test-fuzz: clang is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
cmake -S "$root/tests/fuzz" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" >/dev/null
cmake --build "$build" --target fuzz_scene fuzz_npy -j "$(nproc)"

# run TARGET FLAGS_ARRAY_NAME [SEED_DIR...]: the first corpus folder, the only one libFuzzer
# writes to, is in the build folder
run() {
  local target=$1
  local -n flags=$2
  shift 2
  mkdir -p "$build/corpus/$target" "$build/artifacts"
  echo "== fuzz_$target: $seconds s"
  # -timeout: one input taking over 10 s is a hang; -rss_limit_mb: a run over 2 GiB is a finding
  # (a lying size allocated); leaks are reported (detect_leaks=1)
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$target-" "${flags[@]}" "$build/corpus/$target" "$root/tests/fuzz/corpus/$target" "$@"
}
# scene inputs of up to 8 KB (the shipped scenes are 0.5-1.2 KB); .npy inputs of up to 1 KB
scene_flags=(-max_len=8192 "-dict=$root/tests/fuzz/scene.dict")
npy_flags=(-max_len=1024)
# the two targets side by side when there are two cores (the same fuzzing time each, half the wall
# time); a finding in either fails the script
if [ "$(nproc)" -ge 2 ]; then
  run scene scene_flags "$root/scenes" >"$build/scene.log" 2>&1 &
  scene_pid=$!
  npy_rc=0
  run npy npy_flags || npy_rc=$?
  scene_rc=0
  wait "$scene_pid" || scene_rc=$?
  tail -n 20 "$build/scene.log"
  [ "$scene_rc" = 0 ] && [ "$npy_rc" = 0 ] || { echo "test-fuzz: finding (scene $scene_rc, npy $npy_rc)" >&2; exit 1; }
else
  run scene scene_flags "$root/scenes"
  run npy npy_flags
fi
echo "test-fuzz: no findings"
