#!/usr/bin/env bash
# Checks the include rules of docs/design.md §5 on src/ with grep; prints every breach and
# exits 1 if there is one. Run by CTest (IncludeRules) and by hand:
#   scripts/check_includes.sh
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here/src" || exit 2

# Module → the modules its files may include (besides itself). The pipeline runs one way:
# io → pm → lod → shape → lines → frame, then present (the one place that draws a frame),
# then app, which only parses.
declare -A allowed=(
  [core]=""
  [io]="core"
  [pm]="core io"
  [lod]="core pm"
  [shape]="core"
  [lines]="core shape"
  [frame]="core io pm lod shape lines"
  [export]="core io lines"
  [raster]="core"
  [gl]="core shape"
  [cgal]="core pm io"
  [present]="core io pm lod shape lines frame export raster gl cgal"
  [app]="core io pm lod shape lines frame export gl cgal present"
  [python]="core io pm lod shape lines frame export gl cgal present app"
)
breaches=0
for module in "${!allowed[@]}"; do
  [ -d "$module" ] || continue
  while IFS= read -r line; do
    file=${line%%:*}
    target=$(sed -E 's/.*#include "([a-z_]+)\/.*/\1/' <<<"$line")
    [ "$target" = "$module" ] && continue
    case " ${allowed[$module]} " in
      *" $target "*) ;;
      *) echo "$line: $module/ may not include $target/"; breaches=$((breaches + 1)) ;;
    esac
  done < <(grep -rnE '^#include "[a-z_]+/' "$module" --include='*.h' --include='*.cpp' | grep -v '/glad/')
done
# The commands never reach a drawing backend: no gl/renderer.h, no chamfer layer, no raster/.
while IFS= read -r line; do
  echo "$line: app/ may not include a drawing backend (present/ draws)"
  breaches=$((breaches + 1))
done < <(grep -rnE '^#include "(gl/renderer|gl/chamfer_[a-z_]+|raster/[a-z_]+)\.h"' app python)
# Only present/ includes both frame/ and a drawing backend (gl/renderer.h or raster/).
while IFS= read -r file; do
  case "$file" in present/*) continue ;; esac
  if grep -qE '^#include "frame/' "$file"; then
    echo "$file: includes frame/ and a drawing backend; only present/ may"
    breaches=$((breaches + 1))
  fi
done < <(grep -rlE '^#include "(gl/renderer|raster/[a-z_]+)\.h"' . | sed 's|^\./||')
if [ "$breaches" -gt 0 ]; then
  echo "check_includes.sh: $breaches breach(es) of the include rules (docs/design.md §5)"
  exit 1
fi
echo "check_includes.sh: the include rules of docs/design.md §5 hold"
