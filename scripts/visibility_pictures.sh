#!/usr/bin/env bash
# The pictures of docs/visibility.md, rendered again: the cow close up with the
# interpolated contour alone and with the completed outline (full detail and T = 16),
# hidden lines on models/machine.json, intersection lines on models/crossing.json.
#   scripts/visibility_pictures.sh [OUT_DIR]   (default docs/images)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$here/docs/images}
L=$here/build/lodline
cow=$here/data/meshes/cow.off
mkdir -p "$out"
for view in 1.6 2.2; do
  tag=${view/./}
  "$L" render "$cow" --style lines --view 60,20,$view --size 1920x1080 --full-detail --outline contour \
    -o "$out/visibility-cow$tag-contour.png"
  "$L" render "$cow" --style lines --view 60,20,$view --size 1920x1080 --full-detail -o "$out/visibility-cow$tag-complete.png"
  "$L" render "$cow" --style lines --view 60,20,$view --size 1920x1080 --target-area 16 \
    -o "$out/visibility-cow$tag-complete-t16.png"
done
"$L" render "$here/models/machine.json" --hidden-lines '#8a8a8a:1:dash=4,3' -o "$out/visibility-machine-hidden.png" \
  --svg "$out/visibility-machine-hidden.svg"
"$L" render "$here/models/crossing.json" -o "$out/visibility-crossing.png"
"$L" render "$here/models/crossing.json" --style lines --hidden-lines '#9a9a9a:1:dash=3,3' \
  -o "$out/visibility-crossing-lines.png"
echo "wrote the pictures of docs/visibility.md into $out"
