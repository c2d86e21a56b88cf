#!/bin/bash
# `slime view --check-every K` (issue 28) in a real window under Xvfb, on a short scripted drag: every
# K-th frame the shown image is measured against the full trace of the same physics state and camera,
# and the exit report carries the figures, while the slime is held too. The aims: mean ≥ 38 dB and no
# checked frame below 32 dB while handled.
source "$(dirname "$0")/viewer_lib.sh"
cat > "$OUT/drag.json" <<'JSON'
{"events": [
  {"t": 0.2, "grab": {"point": [0, 0, 0.06], "radius": 0.015}},
  {"t": 0.2, "drag": {"to": [0.02, 0, 0.09], "duration": 0.3}},
  {"t": 0.5, "drag": {"to": [0, 0.02, 0.08], "duration": 0.3}},
  {"t": 0.8, "drag": {"to": [-0.02, 0, 0.09], "duration": 0.3}},
  {"t": 1.1, "drag": {"to": [0, -0.02, 0.08], "duration": 0.3}}
]}
JSON
"$SLIME" view --size 480x270 --scenario "$OUT/drag.json" --frames 36 --check-every 3 \
  --report "$OUT/report.json" --frame-log "$OUT/frames.csv" > "$OUT/stdout.txt" 2>&1 ||
  fail "the viewer exited with an error: $(cat "$OUT/stdout.txt")"

[ "$(report '.check.every')" = 3 ] || fail "check.every is $(report '.check.every'), not 3"
due=$(report '.check.frames + .check.skipped_refining_frames')
[ "$due" -eq 12 ] || fail "$due of 36 frames checked or skipped as refining, not every 3rd (12)"
held=$(report '.check.while_handled.frames')
[ "$held" -ge 1 ] || fail "no checked frame while the slime was held"
mean=$(report '.check.psnr_db.mean')
least=$(report '.check.while_handled.psnr_db.min')
handled_mean=$(report '.check.while_handled.psnr_db.mean')
awk -v m="$mean" -v h="$handled_mean" -v l="$least" 'BEGIN { exit !(m >= 38 && h >= 38 && l >= 32) }' ||
  fail "shown images too far from the full trace: mean $mean dB, while handled mean $handled_mean dB, min $least dB"
# The frame log marks the checked frames with their PSNR (its last column).
checked=$(awk -F, 'NR > 1 && $16 != ""' "$OUT/frames.csv" | wc -l)
[ "$checked" -eq "$(report '.check.frames')" ] || fail "$checked frames carry a PSNR in the frame log"
echo "PASS: $(report '.check.frames') frames checked ($held held): mean $mean dB, min while held $least dB"
