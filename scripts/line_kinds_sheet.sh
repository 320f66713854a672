#!/usr/bin/env bash
# Every line kind on one model, at full detail and at T = 16 and 64, as a `lodline sweep`
# contact sheet (docs/lines.md), then the specks per kind of each run from its stats.
#
#   scripts/line_kinds_sheet.sh MODEL OUT_DIR [SIZE [CELL_WIDTH]]
#
# Needs build/lodline. Rows: kinds (each with the contour), columns: full detail, T = 16, 64.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
model=$1
out=$2
size=${3:-320x320}
cell=${4:-0}
kinds=(
  "contour,suggestive"
  "contour,suggestive-highlight,principal-highlight"
  "contour,ridge,valley"
  "contour,apparent-ridge"
  "contour,isophote"
  "contour,topo"
  "contour,parabolic"
  "contour,material"
)
lines="" lod="" ta=""
for k in "${kinds[@]}"; do
  for d in full 16 64; do
    lines+="${lines:+;}$k"
    if [ "$d" = full ]; then lod+="${lod:+;}none"; ta+=";"; else lod+="${lod:+;}pm"; ta+="$d;"; fi
  done
done
ta=${ta%;}
# Toon style: the highlight kinds are white, as DeCarlo & Rusinkiewicz draw them, over the fills.
"$here/build/lodline" sweep "$model" --size "$size" --style toon --zip -j 2 \
  --vary "lines=$lines" --vary "lod=$lod" --vary "target-area=$ta" --caption specks --columns 3 --cell-width "$cell" \
  --title "$(basename "$model"): line kinds (rows) at full detail, T = 16, T = 64" -o "$out" >&2
# Specks per kind (strokes shorter than 3 px), per run.
python3 - "$out" <<'PY'
import csv, json, pathlib, sys
out = pathlib.Path(sys.argv[1])
print("| kinds | detail | active faces | specks / visible segments, per kind |")
print("|---|---|---|---|")
for row in csv.DictReader(open(out / "results.csv")):
    s = json.load(open(out / "runs" / (row["run"] + ".json")))
    detail = "T = " + row["target-area"] if row["target-area"] else "full"
    kinds = row["lines"].split(",")
    cells = ", ".join("%s %d/%d" % (k, s["specks_by_kind"][k], s["lines"][k]) for k in kinds)
    print("| %s | %s | %d | %s |" % (row["lines"], detail, s["active_faces"], cells))
PY
