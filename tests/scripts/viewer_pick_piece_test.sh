#!/bin/bash
# A grab takes the piece under the cursor (slime.tearing): two hands tear a piece off the slime as in
# viewer_tear_and_merge, the first hand lets it go, and a new left-press on the torn piece, found in a
# screenshot, grabs that piece and drags it back against the rest until the two merge. A press that took
# the nearest point of the big piece instead would drag the big piece, and the torn one would stay apart.
source "$(dirname "$0")/viewer_lib.sh"
tear_with_two_hands
sleep 1
xdotool mouseup 1  # the first hand lets the torn piece go
sleep 1.5
screenshot 2
# The torn piece: the box around the jelly's green pixels right of x = 600 (the rest of the slime ends
# near 530); its middle is where the press goes.
box=$(convert "$OUT/shot-2.png" -crop 130x120+600+120 +repage -fx "g >= r + 10/255 && g >= b + 10/255" \
  -threshold 50% -format "%@" info:)
[[ "$box" =~ ^([0-9]+)x([0-9]+)\+([0-9]+)\+([0-9]+)$ ]] || fail "no torn piece right of the slime in shot 2 (box '$box')"
x=$((600 + BASH_REMATCH[3] + BASH_REMATCH[1] / 2))
y=$((120 + BASH_REMATCH[4] + BASH_REMATCH[2] / 2))
# Dragged back a step at a time until the two merge, then held still: dragging on past the merge would
# press the merged slime against the second hand's hold.
xdotool mousemove --window "$WINDOW" "$x" "$y" mousedown 1
for step_x in $(seq $((x - 20)) -20 500); do
  said "merge 1 " && break
  xdotool mousemove --window "$WINDOW" "$step_x" "$y"
  sleep 0.1
done
wait_until_said "merge 1 " 8
sleep 1
screenshot 3
quit_viewer  # while still holding the button
xdotool mouseup 1

# green_around FILE X Y: the share of the 25x25 pixels around (X, Y) that are the jelly's green.
green_around() {
  convert "$1" -crop "25x25+$(($2 - 12))+$(($3 - 12))" +repage -fx "g >= r + 10/255 && g >= b + 10/255" \
    -format "%[fx:mean]" info:
}
before=$(green_around "$OUT/shot-2.png" "$x" "$y")
after=$(green_around "$OUT/shot-3.png" "$x" "$y")
[ "$(report '.grabs')" -ge 3 ] || fail "$(report '.grabs') grabs: the press at ($x, $y) on the torn piece took no hold"
[ "$(report '.peak_pieces')" -ge 2 ] || fail "the pull between the two hands tore nothing off"
[ "$(report '.merges')" -ge 1 ] ||
  fail "$(report '.pieces') pieces at exit: the press at ($x, $y) did not bring the torn piece back to the rest"
# The press moved the torn piece away from where it lay; a press that took the big piece left it there
# (and tore the big piece again).
awk -v b="$before" -v a="$after" 'BEGIN { exit !(b >= 0.25 && a <= 0.05) }' ||
  fail "the torn piece did not leave ($x, $y): green there $before before the press, $after after"
[ "$(report '.tears')" -eq 1 ] || fail "$(report '.tears') tears: the press tore the slime again instead of moving the torn piece"
echo "PASS: the torn piece at ($x, $y) grabbed (green there $before, then $after) and pressed back: $(report '.tears') tear, $(report '.merges') merge"
