#!/bin/bash
# A press read late still lands where it was made: with frames far longer than the gesture (64 samples a
# pixel, a second or more a frame), the button goes down over the slime and the pointer moves off it,
# just above it, before the viewer reads either event. (Moved on to the window's top edge, the grab
# pulled the slime towards the horizon and each frame of it took minutes: the test hung.) The grab must take hold where the press was (X11's glfwGetCursorPos would say
# where the pointer is now, above the slime, and the press would miss).
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 730x360 --set slime.position=0,0,0.04 --set render.spp=64
sleep 3
xdotool mousemove --window "$WINDOW" 512 120 mousedown 1
for y in 100 80 60; do
  xdotool mousemove --window "$WINDOW" 512 "$y"
  sleep 0.02
done
sleep 2
quit_viewer
xdotool mouseup 1
frames=$(report '.frames')
[ "$(report '.grabs')" -ge 1 ] || fail "the press at (512, 120), read late (${frames} frames in all), did not grab the slime"
echo "PASS: the press read late grabbed the slime (${frames} frames in all)"
