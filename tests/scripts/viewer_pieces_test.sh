#!/bin/bash
# Pieces in the window (slime.tearing): a scenario pins the slime with one hand and pinches its edge
# with the other, pulls a piece off, then presses it back. Screenshots at set simulated times
# (--screenshot-at): before the tear one piece, while torn two, after the press one again (merged).
# Each piece the report lists must be drawn: the pixels around its centroid are the jelly's green, not
# the wood or the sky (the renderer drawing only the first piece leaves the torn-off one's wood).
# The camera looks from further back than the default, so the torn piece stays in the picture.
source "$(dirname "$0")/viewer_lib.sh"
SCENARIO="$(dirname "$0")/../scenarios/tear_off_and_press_back.json"
start_viewer --size 730x360 --set slime.tearing=true --scenario "$SCENARIO" --eye 0.06 -0.36 0.15 \
  --look-at 0.06 0 0.02 --screenshot-at 0.9 2.45 6.0
for n in 1 2 3; do
  for _ in $(seq 1 1200); do
    [ -s "$OUT/shot-$n.png" ] && break
    sleep 0.1
  done
  [ -s "$OUT/shot-$n.png" ] || fail "no screenshot $n within 120 s (the simulation did not reach its time)"
done
quit_viewer

# slime_green FILE X Y: true when at least a quarter of the 25x25 pixels around (X, Y) are the jelly's
# green: green leads red and blue by 10 levels of 255 (the planks are red over green, the sky blue-grey,
# the grab ring of a hand holding the piece cyan).
slime_green() {
  local fraction
  fraction=$(convert "$1" -crop "25x25+$(($2 - 12))+$(($3 - 12))" +repage \
    -fx "g >= r + 10/255 && g >= b + 10/255" -format "%[fx:mean]" info:)
  echo "$1 ($2, $3): $fraction green" >> "$OUT/pixels.txt"
  awk -v f="$fraction" 'BEGIN { exit !(f >= 0.25) }'
}

expected=(1 2 1)
for n in 1 2 3; do
  shot=".timed_screenshots[$((n - 1))]"
  pieces=$(report "$shot.pieces | length")
  [ "$pieces" -eq "${expected[$((n - 1))]}" ] ||
    fail "screenshot $n at $(report "$shot.simulated_s") s: $pieces pieces, expected ${expected[$((n - 1))]}"
  for p in $(seq 0 $((pieces - 1))); do
    x=$(report "$shot.pieces[$p].window_pixel[0] | floor")
    y=$(report "$shot.pieces[$p].window_pixel[1] | floor")
    slime_green "$OUT/shot-$n.png" "$x" "$y" ||
      fail "screenshot $n: piece $((p + 1)) of $pieces is not drawn at its centroid ($x, $y): $(tail -1 "$OUT/pixels.txt")"
  done
done
[ "$(report '.peak_pieces')" -eq 2 ] || fail "$(report '.peak_pieces') pieces at most: the pinch did not tear a piece off"
[ "$(report '.merges')" -ge 1 ] || fail "the pressed pieces did not merge ($(report '.pieces') pieces at exit)"
echo "PASS: 1, 2, 1 pieces drawn at $(report '[.timed_screenshots[].simulated_s] | map(. * 100 | round / 100) | join(", ")') s; $(report '.tears') tear, $(report '.merges') merge"
