# Helpers for the viewer's window tests: run under `xvfb-run -a`, driven by xdotool. Source this file.
# Every test gets SLIME (the binary) and OUT (a fresh directory for its files) from its arguments.
set -u
SLIME="$1"
OUT="$2"
rm -rf "$OUT" && mkdir -p "$OUT"
VIEWER_PID=""
WINDOW=""

fail() {
  echo "FAIL: $*" >&2
  [ -n "$VIEWER_PID" ] && kill "$VIEWER_PID" 2>/dev/null
  exit 1
}

# start_viewer ARGS...: opens the viewer (1280x720 unless --size is given) and waits for its window.
start_viewer() {
  "$SLIME" view --report "$OUT/report.json" --screenshot-prefix "$OUT/shot" "$@" > "$OUT/stdout.txt" 2>&1 &
  VIEWER_PID=$!
  WINDOW=$(timeout 30 xdotool search --sync --name '^Slime$' | head -1)
  [ -n "$WINDOW" ] || fail "no viewer window appeared"
}

# screenshot N: presses F12 and waits until shot-N.png is written (the viewer numbers them 1, 2, ...).
screenshot() {
  xdotool key --window "$WINDOW" F12
  for _ in $(seq 1 100); do
    [ -s "$OUT/shot-$1.png" ] && return 0
    sleep 0.1
  done
  fail "F12 did not write $OUT/shot-$1.png"
}

# said LINE: whether the viewer has printed a line containing LINE (it says "tear N" and "merge N" as
# they happen).
said() {
  grep -q -- "$1" "$OUT/stdout.txt"
}

# wait_until_said LINE SECONDS: waits until the viewer has said LINE, or fails after SECONDS.
wait_until_said() {
  for _ in $(seq 1 $(($2 * 10))); do
    said "$1" && return 0
    sleep 0.1
  done
  fail "the viewer did not say '$1' within $2 s; it said: $(grep 'slime view:' "$OUT/stdout.txt" | tr '\n' ' ')"
}

# click_at X Y: a left click at window point (X, Y), the button held for a moment: Dear ImGui 1.86
# loses a press and release that arrive within one frame, and a loaded machine makes frames long.
click_at() {
  xdotool mousemove --window "$WINDOW" "$1" "$2" mousedown 1
  sleep 0.3
  xdotool mouseup 1
}

# press_and_move X Y PAUSE "x,y"...: presses the left button at window point (X, Y), then moves the
# pointer through the given points, PAUSE seconds at each (so a frame sees every step); the button
# stays down — the caller lets go with `xdotool mouseup 1`.
press_and_move() {
  local pause="$3"
  xdotool mousemove --window "$WINDOW" "$1" "$2" mousedown 1
  shift 3
  for point in "$@"; do
    xdotool mousemove --window "$WINDOW" "${point%,*}" "${point#*,}"
    sleep "$pause"
  done
}

# tear_with_two_hands: opens the tearing scene (slime.tearing; the camera further back than the default,
# so a 20 cm pull stays in the 480 pixels right of the panel column, about 1 mm a pixel at the slime),
# takes screenshot 1, holds the slime's left side with the second hand (Ctrl+left-press, kept when the
# button is let go) and pulls its right side fast to the right (about 0.3 m/s: a slow pull flows before
# it tears) until a piece tears off. The first hand's button stays down.
tear_with_two_hands() {
  start_viewer --size 730x360 --set slime.position=0,0,0.04 --set slime.tearing=true --eye 0 -0.45 0.16 \
    --look-at 0 0 0.02
  sleep 3
  screenshot 1
  xdotool mousemove --window "$WINDOW" 458 180 keydown ctrl mousedown 1
  sleep 0.3
  xdotool mouseup 1 keyup ctrl
  sleep 0.5
  press_and_move 518 180 0.03 $(seq -s ' ' -f '%g,180' 533 15 720)
  wait_until_said "tear 1 " 10
}

# differing_pixels A B: how many pixels differ by more than 3 % between two PNGs.
differing_pixels() {
  compare -metric AE -fuzz 3% "$1" "$2" null: 2>&1 | cut -d' ' -f1
}

# quit_viewer: Esc, then the exit code must be 0.
quit_viewer() {
  xdotool key --window "$WINDOW" Escape
  local code=0
  wait "$VIEWER_PID" || code=$?
  VIEWER_PID=""
  [ "$code" -eq 0 ] || fail "the viewer exited with code $code after Esc; output: $(cat "$OUT/stdout.txt")"
  [ -s "$OUT/report.json" ] || fail "no report written at exit"
}

# report EXPRESSION: a value from the viewer's exit report.
report() {
  jq -r "$1" "$OUT/report.json"
}
