#!/usr/bin/env bash
# README command 1: install the Debian packages, build, and run the main job on the default
# scene: the visualizer in a window when there is a display; otherwise a headless run that
# prints the per-stage timings, and a headless render of the scene to a PNG.
# HUYGENS_SCENE picks another scene; extra arguments go to the program that runs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
build=${HUYGENS_BUILD_DIR:-$root/build}
# the Python package where Debian's python3 finds it (/usr/local/lib/python3.*/dist-packages), so
# `python3 -c "import huygens"` works after this set-up; as root only (else: PYTHONPATH=build/python)
if [ "$(id -u)" -eq 0 ] && [ -d "$build/python/huygens" ]; then
  cmake --install "$build" --component python >/dev/null && echo "== python3: import huygens (installed under /usr/local) =="
fi
scene=${HUYGENS_SCENE:-$root/scenes/default.json}
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec "$build/viz/app/huygens-viz" "$scene" "$@"
fi
echo "== no display: huygens run $scene (headless, per-stage timings) =="
"$build/cli/huygens" run "$scene" --steps 300 "$@"
png=$root/out/$(basename "$scene" .json).png
mkdir -p "$root/out"
echo "== no display: huygens-viz --headless renders the scene at t = 2 s =="
"$build/viz/app/huygens-viz" "$scene" --headless --time 2 --frames 3 --size 1280x720 --screenshot "$png"
echo "image: $png"
