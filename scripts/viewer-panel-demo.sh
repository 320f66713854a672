#!/usr/bin/env bash
# Drives `lodline view` under Xvfb like a user: opens a scene, drags the panel's T slider
# with the mouse (xdotool), and prints the window title (faces drawn, T) before and after;
# writes the last frame, panel included, to viewer-after.png. Used for docs/scenes.md.
#
#   scripts/viewer-panel-demo.sh [SCENE] [OUT_DIR]     (needs xvfb-run and xdotool)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scene=$(realpath "${1:-$here/models/trio.json}")
out=$(realpath -m "${2:-.}")
mkdir -p "$out"
for tool in xvfb-run xdotool; do
  command -v "$tool" >/dev/null || { echo "viewer-panel-demo.sh: $tool not found (apt-get install xvfb xdotool)" >&2; exit 1; }
done
inner=$(mktemp)
trap 'rm -f "$inner"' EXIT
cat >"$inner" <<INNER
#!/usr/bin/env bash
"$here/build/lodline" view "$scene" --exit-after 900 --snapshot "$out/viewer-after.png" &
pid=\$!
sleep 12
wid=\$(xdotool search --name "lodline - " | head -1)
echo "before: \$(xdotool getwindowname "\$wid")"
# The T slider sits at about (16..235, 256..273) in the panel's default layout.
xdotool mousemove --window "\$wid" 112 265 mousedown 1
sleep 0.5
for x in 130 150 170 190; do xdotool mousemove --window "\$wid" \$x 265; sleep 0.3; done
xdotool mouseup 1
sleep 8
echo "after:  \$(xdotool getwindowname "\$wid")"
wait \$pid
INNER
chmod +x "$inner"
xvfb-run -a -s "-screen 0 1400x900x24" "$inner" 2> >(grep -v -e "^X Error" -e "opcode" -e "Resource id" -e "serial number" >&2)
