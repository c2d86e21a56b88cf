#!/bin/bash
# `slime snapshot --ui` draws the whole viewer headless (EGL, no display): the same scene as the plain
# snapshot, with the panel column beside it. Where the panels are the pictures differ; right of them they agree.
set -u
SLIME="$1"
OUT="$2"
rm -rf "$OUT" && mkdir -p "$OUT"
fail() { echo "FAIL: $*" >&2; exit 1; }
unset DISPLAY  # prove that no X server is needed

# The panel column covers the left 250 pixels of an 800x600 viewer; the image fills the 550x600 right of it.
"$SLIME" snapshot --size 550x600 --settle 0.5 -o "$OUT/plain.png" || fail "plain snapshot failed"
"$SLIME" snapshot --ui --size 800x600 --settle 0.5 -o "$OUT/ui.png" || fail "snapshot --ui failed"
[ "$(identify -format '%wx%h' "$OUT/ui.png")" = "800x600" ] || fail "ui.png is not 800x600"
convert "$OUT/ui.png" -crop 550x600+250+0 +repage "$OUT/ui-image.png"

region_difference() {  # pixels differing by more than 3 % inside WxH+X+Y of the plain image and the viewer's
  convert "$OUT/plain.png" -crop "$1" +repage "$OUT/plain-crop.png"
  convert "$OUT/$2" -crop "$1" +repage "$OUT/ui-crop.png"
  compare -metric AE -fuzz 3% "$OUT/plain-crop.png" "$OUT/ui-crop.png" null: 2>&1 | cut -d' ' -f1
}
panels=$(region_difference 240x90+0+6 ui.png)          # the column's first section headers
scene=$(region_difference 550x300+0+300 ui-image.png)  # the floor in front of the slime, below the Stats title
slime=$(region_difference 200x200+175+150 ui-image.png)  # the slime: the settled shape, not the start
[ "$panels" -gt 10000 ] || fail "only $panels of 21600 pixels differ where the panels are"
[ "$scene" -lt 300 ] || fail "$scene of 165000 pixels differ beside the panels: not the same picture"
[ "$slime" -lt 300 ] || fail "$slime of 40000 pixels differ on the slime: the --ui frame is not the settled slime"
echo "PASS: $panels pixels differ under the panels, $scene on the floor, $slime on the slime"
