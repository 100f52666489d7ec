#!/usr/bin/env bash
# README command 1: install the Debian packages, build, and run the main job on the
# default scene. Extra arguments go to `huygens run`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
build=${HUYGENS_BUILD_DIR:-$root/build}
scene=${HUYGENS_SCENE:-$root/scenes/default.json}
echo "== huygens run $scene (headless: per-stage timings) =="
"$build/cli/huygens" run "$scene" --steps 300 "$@"
