#!/usr/bin/env bash
# Renders every shipped scene headless at a telling time into docs/gallery/ (640x360 PNGs), in
# the perspective view and, where a picture should be read (the Kelvin angle, the
# Cauchy-Poisson ring, the dam-break front, the vortex street), in the plan view too; the LBM
# flows also as speed and as the dye and foam they carried since t = 0, the SPH dam breaks as
# particles.
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
