#!/bin/bash
# A panel slider edits the setting (clicking the transmission slider near its left end); a typed value
# outside the allowed range is refused with a message and not applied. Clicks on the panel are not
# seen by the app (no grab starts under them).
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 480x360 --set sim.paused=true
sleep 2
xdotool mousemove --window "$WINDOW" 40 42 click 1     # open the Slime section
sleep 1
screenshot 1
xdotool mousemove --window "$WINDOW" 30 88 click 1     # transmission slider, near 0.1
sleep 1
screenshot 2
# Ctrl+click the mass slider to type a value: 0 kg is outside 0.001..100 kg. (Dear ImGui 1.86 misses a
# key pressed and released within one frame, hence keydown, a pause, keyup.)
xdotool mousemove --window "$WINDOW" 60 158 keydown ctrl click 1 keyup ctrl
sleep 0.5
xdotool type --window "$WINDOW" "0"
sleep 0.3
xdotool keydown --window "$WINDOW" Return
sleep 0.3
xdotool keyup --window "$WINDOW" Return
sleep 1
screenshot 3
quit_viewer

transmission=$(report '.settings.slime.transmission')
awk -v t="$transmission" 'BEGIN { exit !(t < 0.3) }' || fail "transmission $transmission: the slider click was not applied"
mass=$(report '.settings.slime.mass')
awk -v m="$mass" 'BEGIN { exit !(m > 0.001) }' || fail "mass $mass: an out-of-range value was applied"
error=$(report '.edit_error')
echo "$error" | grep -q "slime.mass" || fail "no error naming slime.mass for mass 0: '$error'"
[ "$(report '.grabs')" -eq 0 ] || fail "a click on a panel reached the app as a grab"
echo "PASS: transmission $transmission, mass 0 refused (mass stays $mass): $error"
