#!/bin/bash
# Left-drag on the slime grabs it and pulls it up: it stretches (10 % taller than when it was grabbed,
# the picture changes above it) while the button is held. The slime starts at rest height so it is where we click.
# The window is 730 wide: the panel column takes 250 at the left, the image the 480 right of it.
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 730x360 --set slime.position=0,0,0.04
sleep 3
screenshot 1
press_and_move 512 120 0.15 512,110 512,100 512,90 512,80 512,70 512,60 512,50 512,40
sleep 3.5
screenshot 2
quit_viewer  # while still holding the button: the report shows the slime stretched
xdotool mouseup 1

[ "$(report '.grabs')" -ge 1 ] || fail "the left press at (512, 120) did not grab the slime"
[ "$(report '.grabbing')" = "true" ] || fail "the grab ended before the button was released"
peak=$(report '.peak_height_while_grabbing')
start=$(report '.height_at_grab')
awk -v h="$peak" -v s="$start" 'BEGIN { exit !(h > 1.10 * s) }' ||
  fail "peak height $peak m while grabbing: not 10 % above the $start m it had when grabbed"
convert "$OUT/shot-1.png" -crop 140x70+440+30 +repage "$OUT/above-1.png"
convert "$OUT/shot-2.png" -crop 140x70+440+30 +repage "$OUT/above-2.png"
above=$(differing_pixels "$OUT/above-1.png" "$OUT/above-2.png")
[ "$above" -gt 1500 ] || fail "only $above pixels changed above the slime while dragging it up"
echo "PASS: grabbed at height $start m, stretched to $peak m, $above pixels changed above the slime"
