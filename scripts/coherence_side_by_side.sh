#!/usr/bin/env bash
# Side-by-side captures for docs/temporal-coherence.md: one camera path drawn three ways,
# full detail | T = 16 without geomorphs and smoothing | T = 16 with them (the defaults),
# as one MP4 (the three videos stacked left to right) and one PNG strip of five frames
# (rows: 0, 1, 2, 3 and 3.9 s). Each panel's metrics CSV is kept beside the video so the
# churn figures of the page can be checked against what the video shows.
#
#   scripts/coherence_side_by_side.sh [--lodline build/lodline] [--out docs/images] \
#       MESH PATH [MESH PATH ...]      e.g. data/meshes/armadillo.off zoom-out
set -euo pipefail

lodline=build/lodline
out=docs/images
while [[ $# -gt 0 && $1 == --* ]]; do
    case $1 in
        --lodline) lodline=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        *) echo "coherence_side_by_side.sh: unknown option $1" >&2; exit 2 ;;
    esac
done
if [[ $# -lt 2 || $(($# % 2)) -ne 0 ]]; then
    echo "usage: coherence_side_by_side.sh [--lodline BIN] [--out DIR] MESH PATH [MESH PATH ...]" >&2
    exit 2
fi
command -v ffmpeg >/dev/null || { echo "coherence_side_by_side.sh: ffmpeg not found" >&2; exit 1; }
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Labels need a font; without DejaVu the panels go unlabelled (the page's caption names them).
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
label() {
    if [[ -f $font ]]; then
        printf "drawtext=fontfile=%s:text='%s':x=8:y=8:fontsize=18:fontcolor=black" "$font" "$1"
    else
        printf "null"
    fi
}

common=(--duration 4 --fps 30 --size 640x360 --style lines)
while [[ $# -gt 0 ]]; do
    mesh=$1 path=$2; shift 2
    name=$(basename "${mesh%.*}")-$path
    "$lodline" capture "$mesh" --path "$path" "${common[@]}" --full-detail \
        --metrics "$work/full.csv" -o "$work/full.mp4" >/dev/null
    "$lodline" capture "$mesh" --path "$path" "${common[@]}" --geomorphs off --smoothing off \
        --metrics "$work/bare.csv" -o "$work/bare.mp4" >/dev/null
    "$lodline" capture "$mesh" --path "$path" "${common[@]}" \
        --metrics "$work/t16.csv" -o "$work/t16.mp4" >/dev/null
    ffmpeg -hide_banner -loglevel error -y -i "$work/full.mp4" -i "$work/bare.mp4" -i "$work/t16.mp4" \
        -filter_complex "[0:v]$(label 'full detail')[a];[1:v]$(label 'T=16, no geomorphs or smoothing')[b];[2:v]$(label 'T=16 (defaults)')[c];[a][b][c]hstack=inputs=3[v]" \
        -map '[v]' -c:v libx264 -pix_fmt yuv420p -crf 28 -movflags +faststart "$work/side.mp4"
    mv "$work/side.mp4" "$out/coherence-side-$name.mp4"
    # Five frames (0, 1, 2, 3, 3.9 s), one per row, at half size to keep the page light.
    ffmpeg -hide_banner -loglevel error -y -i "$out/coherence-side-$name.mp4" \
        -vf "select='eq(n\,0)+eq(n\,30)+eq(n\,60)+eq(n\,90)+eq(n\,117)',scale=960:-2,tile=1x5" \
        -frames:v 1 -fps_mode passthrough "$work/strip.png"
    mv "$work/strip.png" "$out/coherence-side-$name.png"
    for panel in full bare t16; do
        mv "$work/$panel.csv" "$work/$name-$panel.csv"
    done
    python3 - "$work/$name" <<'EOF'
import csv, sys
base = sys.argv[1]
for panel, title in (("full", "full detail"), ("bare", "T=16 no geomorphs/smoothing"), ("t16", "T=16 defaults")):
    rows = list(csv.DictReader(open(f"{base}-{panel}.csv")))[1:]
    mean = lambda k: sum(float(r[k]) for r in rows) / len(rows)
    print(f"{base.rsplit('/', 1)[-1]:24s} {title:30s} churn {mean('churn'):.5f}  binary {mean('churn_binary'):.5f}  specks {mean('specks'):.0f}")
EOF
done
