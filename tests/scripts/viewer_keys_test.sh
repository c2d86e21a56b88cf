#!/bin/bash
# W moves the camera forward (the picture changes, the camera position too); resizing the window works;
# Esc quits with exit code 0. Physics is paused so that only the camera changes the picture.
source "$(dirname "$0")/viewer_lib.sh"
start_viewer --size 730x360  # the image: 480x360 right of the panel column --set sim.paused=true
sleep 2
screenshot 1
xdotool keydown --window "$WINDOW" w
sleep 0.8
xdotool keyup --window "$WINDOW" w
sleep 1.5  # stillness: the full-resolution image comes back
screenshot 2
changed=$(differing_pixels "$OUT/shot-1.png" "$OUT/shot-2.png")
[ "$changed" -gt 20000 ] || fail "W changed only $changed pixels of 172800"

xdotool windowsize "$WINDOW" 400 300
sleep 1.5
screenshot 3
size=$(identify -format '%wx%h' "$OUT/shot-3.png")
[ "$size" = "400x300" ] || fail "after resizing to 400x300 the window shows $size"
quit_viewer

y=$(report '.settings.camera.position[1]')
awk -v y="$y" 'BEGIN { exit !(y > -0.22 + 0.03) }' || fail "camera y $y: W did not move the camera forward (+y) from -0.22"
[ "$(report '.framebuffer | join("x")')" = "400x300" ] || fail "framebuffer $(report '.framebuffer') after resize"
echo "PASS: W changed $changed pixels, camera y $y, resized to $size, Esc exit 0"
