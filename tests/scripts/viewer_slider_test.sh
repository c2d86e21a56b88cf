#!/bin/bash
# The panels come from the settings table: a slider click edits the setting (stiffness, near its left
# end); a typed value outside the table's range is refused with a message naming the key and range and
# not applied (stiffness 2000: the limit is 1000 N/m), typed a letter at a time as a person types: a
# typed number counts when the field is left, so its prefixes 2, 20 and 200 are never applied (and a
# typed 7 N/m before it is); a three-component field likewise (the light's z: 150 m refused, not
# clamped to 100, its prefix 15 never applied), the refused stiffness not blocking it; the level slider waits for Reload
# instead of rebuilding the slime. Clicks on the panel are not seen by the app (no grab starts under them).
# The column is 250 wide at the left; with the Scene file section closed its rows are 23 px apart.
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 730x360 --set sim.paused=true --set slime.model=membrane  # stiffness is the membrane's
sleep 2
click_at 60 36      # close the Scene file section
sleep 1
screenshot 1
click_at 12 289     # stiffness slider (logarithmic 1..1000), near 1 N/m
sleep 1
click_at 12 220     # level slider at its left end: 0, held for Reload
sleep 1
screenshot 2
# Ctrl+click a slider to type a value. (Dear ImGui 1.86 misses a key pressed and released within one
# frame, hence keydown, a pause, keyup.)
type_into() {  # X Y TEXT
  xdotool mousemove --window "$WINDOW" "$1" "$2" keydown ctrl mousedown 1
  sleep 0.3
  xdotool mouseup 1 keyup ctrl
  sleep 0.5
  xdotool type --delay 150 --window "$WINDOW" "$3"  # a letter a frame or so, as a person types
  sleep 0.3
  xdotool keydown --window "$WINDOW" Return
  sleep 0.3
  xdotool keyup --window "$WINDOW" Return
  sleep 1
}
type_into 60 289 "7"        # stiffness 7 N/m: inside the range, applied on Enter
type_into 60 289 "2000"     # stiffness 2000 N/m: outside 1..1000 N/m (its prefixes are inside)
screenshot 3
# A three-component field the same way (the refused stiffness does not block it): open the Light
# section, type into the position's z.
click_at 60 82              # the Light section's header
sleep 1
screenshot 4
type_into 100 105 "150"     # z 150 m: outside −100..100 m (its prefixes 1 and 15 are inside)
screenshot 5
quit_viewer

stiffness=$(report '.settings.slime.stiffness')
awk -v k="$stiffness" 'BEGIN { exit !(k < 50) }' ||
  fail "stiffness $stiffness: the slider click near 1 N/m (from 100) was not applied, or a prefix of the typed 2000 was (see $OUT/shot-2.png)"
awk -v k="$stiffness" 'BEGIN { exit !(k <= 1000) }' || fail "stiffness $stiffness: an out-of-range value was applied"
awk -v k="$stiffness" 'BEGIN { exit !(k == 7) }' || fail "stiffness $stiffness: the typed 7 N/m was not applied on Enter"
error=$(report '.edit_errors[0]')  # every refused edit, in order
echo "$error" | grep -q "slime.stiffness" || fail "no error naming slime.stiffness for 2000 N/m: '$error'"
echo "$error" | grep -q "1 to 1000" || fail "the error does not give the table's range 1 to 1000: '$error'"
[ "$(report '.settings.slime.level')" -eq 4 ] || fail "the level slider rebuilt the slime at once (level $(report '.settings.slime.level'))"
report '.reload_pending[]' | grep -qx "slime.level" || fail "slime.level is not waiting for Reload: $(report '.reload_pending')"
[ "$(report '.grabs')" -eq 0 ] || fail "a click on a panel reached the app as a grab"
light_z=$(report '.settings.light.position[2]')
awk -v z="$light_z" 'BEGIN { exit !(z == 0.35) }' ||
  fail "light z $light_z: the typed 150 m (or its prefix 15, or 100 clamped) was applied, or the field was not reached (see $OUT/shot-4.png, shot-5.png)"
light_error=$(report '.edit_errors[1]')
echo "$light_error" | grep -q "light.position" || fail "no error naming light.position for z = 150 m: '$light_error'"
[ "$(report '.edit_errors | length')" -eq 2 ] || fail "refused edits: $(report '.edit_errors') (expected the stiffness's and the light's)"
echo "PASS: stiffness $stiffness, 2000 N/m refused: $error; light z $light_z, 150 m refused: $light_error; level held for Reload"
