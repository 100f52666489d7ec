#!/usr/bin/env bash
# Renders every shipped scene headless at a telling time into docs/gallery/ (640x360 PNGs), in
# the perspective view and, where a picture should be read (the Kelvin angle, the
# Cauchy-Poisson ring, the dam-break front, the vortex street), in the plan view too; the LBM
# flows also as speed and as the dye and foam they carried since t = 0, the SPH dam breaks as
# particles. Then a row of close-ups (closeup_*.png) from cameras set in a copy of the scene's JSON
# (render.camera): the solids in and through the water, grazing and from under the surface.
#   scripts/gallery.sh [BUILD_DIR]      (default: build; needs huygens-viz built there)
# EGL surfaceless (Mesa llvmpipe): no display needed. The images are what the README shows.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-build}
viz="$build/viz/app/huygens-viz"
[ -x "$viz" ] || viz="$root/$build/viz/app/huygens-viz"
[ -x "$viz" ] || { echo "gallery: $viz not found (build the huygens-viz target)" >&2; exit 1; }
out="$root/docs/gallery"
mkdir -p "$out"
# scene  time_s  views
shots=(
  "default 3 perspective"
  "ring 3 perspective,plan"
  "pond 1 perspective"
  "kelvin 15 perspective,plan"
  "ocean 10 perspective"
  "pool 0.3 perspective"
  "sph_dam_break 0.15 perspective,particles"
  "sph_wedge 0.25 perspective"
  "sph_wedge 0.4 particles"
  "dam_break 6 perspective"
  "dam_break 10 plan,dye"
  "channel 40 perspective,plan,speed,dye,foam"
  "flood 12 perspective,plan,foam"
)
for shot in "${shots[@]}"; do
  read -r scene t views <<<"$shot"
  for view in ${views//,/ }; do
    name=$scene; [ "$view" != perspective ] && name=${scene}_$view
    "$viz" "$root/scenes/$scene.json" --headless --time "$t" --frames 1 --size 640x360 --view "$view" \
      --screenshot "$out/$name.png" >/dev/null
    python3 "$root/scripts/png_shrink.py" "$out/$name.png"  # 6 bits per channel, zlib 9
    echo "gallery: $name.png ($scene at t = $t s, $view view)"
  done
done
# close-ups: name  scene  time_s  target x,y,z (m)  distance (m)  yaw  pitch (deg)
closeups=(
  "pool_cylinder pool 0.3 0.1,0.1,0.0 0.32 -70 10"
  "kelvin_grazing kelvin 15 26.8,25.6,0.0 3.5 -55 6"
  "flood_houses flood 12 62,37,0 45 -150 8"
  "pool_under pool 0.3 0.1,0.045,-0.03 0.04 -90 -25"
  "kelvin_under kelvin 15 27.2,25.6,-0.6 2.2 -150 -12"
)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for shot in "${closeups[@]}"; do
  read -r name scene t target dist yaw pitch <<<"$shot"
  python3 - "$root/scenes/$scene.json" "$tmp/$name.json" "$target" "$dist" "$yaw" "$pitch" <<'PY'
import json, sys
src, dst, target, dist, yaw, pitch = sys.argv[1:]
d = json.load(open(src))
d.setdefault("render", {})["camera"] = {"target_m": [float(v) for v in target.split(",")],
                                        "distance_m": float(dist), "yaw_deg": float(yaw), "pitch_deg": float(pitch)}
json.dump(d, open(dst, "w"))
PY
  "$viz" "$tmp/$name.json" --headless --time "$t" --frames 1 --size 640x360 --no-caption \
    --screenshot "$out/closeup_$name.png" >/dev/null
  python3 "$root/scripts/png_shrink.py" "$out/closeup_$name.png"
  echo "gallery: closeup_$name.png ($scene at t = $t s)"
done
