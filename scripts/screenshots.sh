#!/bin/bash
# Redraws the README's viewer screenshots (docs/viewer.png, docs/viewer-drag.png): the real window at
# the default 1280x720 under Xvfb, driven by xdotool like the window tests. Needs a built slime:
#   scripts/screenshots.sh [path/to/slime]   (default build/release/app/slime)
set -euo pipefail
cd "$(dirname "$0")/.."
slime="$(realpath "${1:-build/release/app/slime}")"
[ -x "$slime" ] || { echo "screenshots.sh: no slime binary at $slime (build first: scripts/test.sh)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cat > "$work/drive.sh" <<'DRIVE'
#!/bin/bash
set -euo pipefail
source tests/scripts/viewer_lib.sh "$1" "$2"
start_viewer   # 1280x720: the panel column takes the left 333 pixels, the slime is centred right of it
sleep 12                                  # the slime falls, settles and creeps; the image refines between its steps
screenshot 1
xdotool mousemove --window "$WINDOW" 845 250 mousedown 1   # on the settled slime's upper right
sleep 0.5                                 # held until a frame has seen the press where it was made
for y in 235 215 195 175 155 135 115 95; do
  xdotool mousemove --window "$WINDOW" 870 "$y"
  sleep 0.15
done
sleep 2
screenshot 2
xdotool mouseup 1
quit_viewer
[ "$(report '.grabs')" -ge 1 ] || fail "the press at (845, 250) did not grab the slime"
DRIVE
xvfb-run -a -s "-screen 0 1400x900x24" bash "$work/drive.sh" "$slime" "$work/out"
cp "$work/out/shot-1.png" docs/viewer.png
cp "$work/out/shot-2.png" docs/viewer-drag.png
echo "wrote docs/viewer.png and docs/viewer-drag.png"
