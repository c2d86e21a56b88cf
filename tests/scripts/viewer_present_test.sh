#!/bin/bash
# The window shows what the frames drew. The viewer draws again, and copies to the window, only what
# changed in a frame (app/viewer/frame_compositor.h, GLX_MESA_copy_sub_buffer under Xvfb): a region
# it forgot would stay on screen as it was, a ring or a slime left behind. A scripted drag moves the
# slime, its shadow and the grab ring about the image, lets go and pauses the physics while the slime
# still wobbles; once the image has stopped refining, the window as X shows it must equal the frame's
# own pixels (F12, read from the framebuffer), pixel for pixel; and again after the window grows and
# shrinks.
source "$(dirname "$0")/viewer_lib.sh"
cat > "$OUT/scenario.json" <<'JSON'
{"events": [
  {"t": 0.5, "grab": {"point": [0, 0, 0.055], "radius": 0.015}},
  {"t": 0.5, "drag": {"to": [0.02, 0, 0.075], "duration": 0.4}},
  {"t": 0.9, "drag": {"to": [0, 0.02, 0.085], "duration": 0.3}},
  {"t": 1.2, "drag": {"to": [-0.02, 0, 0.075], "duration": 0.3}},
  {"t": 1.5, "drag": {"to": [0, -0.02, 0.065], "duration": 0.3}},
  {"t": 1.8, "release": {}},
  {"t": 2.2, "set": {"sim.paused": true}}
]}
JSON
start_viewer --size 730x360 --set slime.position=0,0,0.04 --scenario "$OUT/scenario.json" ${VIEWER_EXTRA:-}
# The window as X shows it.
capture() { import -window "$WINDOW" "$1" 2>/dev/null || fail "cannot capture the window"; }
# expect_window_shows_frame N WHEN: waits until the window stops changing, then presses F12 (shot-N)
# and compares the window with it, pixel for pixel.
expect_window_shows_frame() {
  local still="" attempt
  for attempt in $(seq 1 30); do
    sleep 1
    capture "$OUT/window-$1-a.png"
    sleep 0.5
    capture "$OUT/window-$1-b.png"
    if [ "$(compare -metric AE "$OUT/window-$1-a.png" "$OUT/window-$1-b.png" null: 2>&1 | cut -d' ' -f1)" = "0" ]; then
      still=yes
      break
    fi
  done
  [ -n "$still" ] || fail "$2: the window never stopped changing (30 s)"
  screenshot "$1"
  capture "$OUT/window-$1.png"
  local differing
  differing=$(compare -metric AE "$OUT/window-$1.png" "$OUT/shot-$1.png" "$OUT/difference-$1.png" 2>&1 | cut -d' ' -f1)
  [ "$differing" = "0" ] ||
    fail "$2: the window shows $differing pixels other than the frame drew (see $OUT/difference-$1.png)"
  echo "$2: the window shows the frame (still after $attempt attempts)"
}
# resize W H: gives the window a new size; the viewer must live through it.
resize() {
  timeout 10 xdotool windowsize --sync "$WINDOW" "$1" "$2" || fail "the window did not take the size $1x$2"
  sleep 1
  kill -0 "$VIEWER_PID" 2>/dev/null || fail "the viewer died when the window became $1x$2: $(tail -5 "$OUT/stdout.txt")"
}
expect_window_shows_frame 1 "after the drag"
# A new size: the window is swapped once (the back buffer takes the new size), then copied again.
resize 780 450
expect_window_shows_frame 2 "grown to 780x450"
resize 600 300
expect_window_shows_frame 3 "shrunk to 600x300"
quit_viewer
[ "$(report '.grabs')" -ge 1 ] || fail "the scenario's grab did not take hold"
echo "PASS: after a drag and two resizes the window shows the frame's pixels, every one"
