#!/usr/bin/env bash
# The pictures of docs/strokes.md, rendered again: the armadillo (CGAL demo mesh) in each
# stroke-style preset at full detail and under detail control (T = 16 px²), and the trio
# scene under detail control, each as PNG and SVG.
#   scripts/stroke_style_pictures.sh [OUT_DIR]   (default docs/images)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$here/docs/images}
L=$here/build/lodline
arm=$here/data/meshes/armadillo.off
mkdir -p "$out"
for preset in plain ink pencil marker; do
  common=(--style lines --stroke-style "$preset" --size 480x360)
  "$L" render "$arm" "${common[@]}" --full-detail -o "$out/strokes-$preset-full.png" --svg "$out/strokes-$preset-full.svg"
  "$L" render "$arm" "${common[@]}" --target-area 16 -o "$out/strokes-$preset-t16.png" --svg "$out/strokes-$preset-t16.svg"
  "$L" render "$here/models/trio.json" --stroke-style "$preset" --size 480x360 \
    -o "$out/strokes-$preset-trio.png" --svg "$out/strokes-$preset-trio.svg"
done
"$L" render "$here/data/meshes/cow.off" --style lines --view 60,20,1.6 --size 1920x1080 --msaa 1 \
  --hidden-lines '#999:1:dash=4,3' -o /tmp/strokes-cow-gl.png
"$L" render "$here/data/meshes/cow.off" --style lines --view 60,20,1.6 --size 1920x1080 --msaa 1 --backend soft \
  --hidden-lines '#999:1:dash=4,3' -o /tmp/strokes-cow-soft.png
for b in gl soft; do
  ffmpeg -loglevel error -y -i /tmp/strokes-cow-$b.png -vf "crop=200:150:1120:80,scale=800:600:flags=neighbor" \
    "$out/strokes-cow-closeup-$b.png"
done
echo "wrote the pictures of docs/strokes.md into $out"
