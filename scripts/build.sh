#!/usr/bin/env bash
# Configures and builds Huygens (Release) into ${HUYGENS_BUILD_DIR:-build}.
# Extra arguments go to CMake's configure step (e.g. -DHUYGENS_SANITIZE=address).
# HUYGENS_ISA=x86-64-v3 (environment) builds for the AVX2 + FMA baseline instead of this CPU.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HUYGENS_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${HUYGENS_ISA:+-DHUYGENS_ISA="$HUYGENS_ISA"} "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
