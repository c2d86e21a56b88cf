#!/bin/bash
# Tearing with two hands and pressing back with one, in the window (slime.tearing): Ctrl+left-press holds
# the slime's left side with the second hand; a left-drag pulls its right side fast to the right until a
# piece tears off. The first hand keeps the piece it holds: dragged back, it brings that piece back and
# presses it against the rest until the two merge (slime.mergeTime, 0.3 s).
source "$(dirname "$0")/viewer_lib.sh"
tear_with_two_hands  # viewer_lib.sh: screenshot 1, the second hand holds, the first pulls
sleep 1.5
screenshot 2
# ... and back, button still down: the piece it holds is pressed against the rest.
for x in $(seq 700 -20 520); do
  said "merge 1 " && break
  xdotool mousemove --window "$WINDOW" "$x" 180
  sleep 0.1
done
wait_until_said "merge 1 " 8
sleep 1
screenshot 3
quit_viewer  # while still holding the button
xdotool mouseup 1

[ "$(report '.grabs')" -ge 2 ] || fail "$(report '.grabs') grabs: the two presses did not both take hold"
[ "$(report '.peak_pieces')" -ge 2 ] || fail "the 20 cm pull between the two hands tore nothing off"
[ "$(report '.merges')" -ge 1 ] ||
  fail "$(report '.pieces') pieces at exit: the piece the first hand brought back did not merge"
[ "$(report '.pieces')" -eq 1 ] || fail "$(report '.pieces') pieces at exit, expected 1 after the merge"
[ "$(report '.hands[0].holding')" = "true" ] && [ "$(report '.hands[1].holding')" = "true" ] ||
  fail "a hand let go across the tear and the merge: $(jq -c '[.hands[].holding]' "$OUT/report.json")"
# The three pictures differ where the torn piece was (right of the slime): there, then gone again.
convert "$OUT/shot-1.png" -crop 150x80+570+140 +repage "$OUT/right-1.png"
convert "$OUT/shot-2.png" -crop 150x80+570+140 +repage "$OUT/right-2.png"
convert "$OUT/shot-3.png" -crop 150x80+570+140 +repage "$OUT/right-3.png"
torn=$(differing_pixels "$OUT/right-1.png" "$OUT/right-2.png")
back=$(differing_pixels "$OUT/right-1.png" "$OUT/right-3.png")
[ "$torn" -gt 300 ] || fail "only $torn pixels changed right of the slime while the torn piece was held there"
[ "$back" -lt "$torn" ] || fail "$back pixels still differ right of the slime after the merge ($torn while torn)"
echo "PASS: $(report '.tears') tear, $(report '.merges') merge with the hands; $torn pixels changed right of the slime, $back after"
