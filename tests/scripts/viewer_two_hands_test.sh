#!/bin/bash
# Two hands stretch the slime: Ctrl+left-drag grabs its left side with the second hand and pulls it
# left, and that hand keeps holding after the button is released; a left-drag then grabs the right
# side with the first hand and pulls it right. With both holding, the slime is wider than when the
# first grab began, and the two hands pull in opposite directions (the report's per-hand forces).
# The window is 730 wide: the panel column takes 250 at the left, the image the 480 right of it.
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 730x360 --set slime.position=0,0,0.04
sleep 3
screenshot 1
# The second hand holds the left side where it is: Ctrl held through the press (the viewer reads the
# modifier at the press), moved a little (a long pull would slide the whole slime off the first
# hand's spot: the floor is not sticky by default) and let go of: it keeps holding.
xdotool mousemove --window "$WINDOW" 420 165 keydown ctrl mousedown 1
for x in 418 416 414; do
  xdotool mousemove --window "$WINDOW" "$x" 165
  sleep 0.12
done
xdotool mouseup 1 keyup ctrl
sleep 0.5
# The first hand, on the right side, pulled right and held.
xdotool mousemove --window "$WINDOW" 552 165 mousedown 1
for x in 562 572 582 592 602 612 622 632 642; do
  xdotool mousemove --window "$WINDOW" "$x" 165
  sleep 0.12
done
sleep 2.5
screenshot 2
quit_viewer  # while still holding the button: the report shows both hands holding
xdotool mouseup 1

[ "$(report '.grabs')" -ge 2 ] || fail "$(report '.grabs') grabs: the two presses did not both take hold"
[ "$(report '.hands[1].holding')" = "true" ] || fail "the second hand let go when its button was released"
[ "$(report '.hands[0].holding')" = "true" ] || fail "the first hand let go while its button was held"
before=$(report '.width_before_grabs')
peak=$(report '.peak_width_while_two_hands')
awk -v p="$peak" -v b="$before" 'BEGIN { exit !(b > 0 && p > 1.15 * b) }' ||
  fail "widest $peak m while both hands held: not 15 % wider than the $before m before the grabs"
# Opposite pulls: the two hands' forces on the body point away from each other.
opposite=$(jq '[.hands[0].force, .hands[1].force] | (.[0][0]*.[1][0] + .[0][1]*.[1][1] + .[0][2]*.[1][2]) < 0' "$OUT/report.json")
[ "$opposite" = "true" ] || fail "the hands' forces $(jq -c '[.hands[].force]' "$OUT/report.json") do not oppose"
echo "PASS: width $before m before the grabs, $peak m with both hands; forces $(jq -c '[.hands[].force]' "$OUT/report.json")"
