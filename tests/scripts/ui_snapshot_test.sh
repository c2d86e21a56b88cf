#!/bin/bash
# `slime snapshot --ui` draws the whole viewer headless (EGL, no display): the same scene as the plain
# snapshot, with the panels over it. Where the panels are the pictures differ; away from them they agree.
set -u
SLIME="$1"
OUT="$2"
rm -rf "$OUT" && mkdir -p "$OUT"
fail() { echo "FAIL: $*" >&2; exit 1; }
unset DISPLAY  # prove that no X server is needed

"$SLIME" snapshot --size 480x360 --settle 0.5 -o "$OUT/plain.png" || fail "plain snapshot failed"
"$SLIME" snapshot --ui --size 480x360 --settle 0.5 -o "$OUT/ui.png" || fail "snapshot --ui failed"
[ "$(identify -format '%wx%h' "$OUT/ui.png")" = "480x360" ] || fail "ui.png is not 480x360"

region_difference() {  # pixels differing by more than 3 % inside WxH+X+Y
  convert "$OUT/plain.png" -crop "$1" +repage "$OUT/plain-crop.png"
  convert "$OUT/ui.png" -crop "$1" +repage "$OUT/ui-crop.png"
  compare -metric AE -fuzz 3% "$OUT/plain-crop.png" "$OUT/ui-crop.png" null: 2>&1 | cut -d' ' -f1
}
panels=$(region_difference 240x90+6+6)      # the Controls window's three section headers
scene=$(region_difference 200x100+140+250)  # the floor in front of the slime, below the panels
slime=$(region_difference 150x150+250+110)  # the right half of the slime: the settled shape, not the start
[ "$panels" -gt 10000 ] || fail "only $panels of 21600 pixels differ where the panels are"
[ "$scene" -lt 200 ] || fail "$scene of 20000 pixels differ away from the panels: not the same picture"
[ "$slime" -lt 200 ] || fail "$slime of 22500 pixels differ on the slime: the --ui frame is not the settled slime"
echo "PASS: $panels pixels differ under the panels, $scene on the floor, $slime on the slime"
