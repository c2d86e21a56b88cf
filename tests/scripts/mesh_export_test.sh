#!/bin/bash
# `slime sim --export-mesh` and `slime snapshot --export-mesh` write files that an independent reader,
# assimp (Debian's assimp-utils), opens with the slime's vertex and triangle counts, the .glb with its
# animation, the .obj y up with its .mtl; bad patterns, paths and up axes exit with 2 and leave no file. (The exact positions are checked
# in tests/core/export/mesh_export_test.cpp.)
set -u
SLIME="$1"
OUT="$2"
rm -rf "$OUT" && mkdir -p "$OUT"
fail() { echo "FAIL: $*" >&2; exit 1; }

# The default slime at level 4: 10·4^4 + 2 = 2562 vertices, 20·4^4 = 5120 triangles.
check_info() {  # check_info FILE [ANIMATIONS]
  local info
  info=$(assimp info "$1" 2>&1) || fail "assimp cannot read $1: $info"
  grep -Eq "^Vertices: +2562$" <<<"$info" || fail "$1: assimp does not find 2562 vertices"
  grep -Eq "^Faces: +5120$" <<<"$info" || fail "$1: assimp does not find 5120 faces"
  grep -Eq "^Animations: +${2:-0}$" <<<"$info" || fail "$1: assimp does not find ${2:-0} animations"
}

"$SLIME" sim --seconds 0.1 --export-mesh "$OUT/p_%02d.ply" --export-every 0.05 >"$OUT/ply.log" ||
  fail "sim --export-mesh .ply failed"
[ "$(ls "$OUT"/p_*.ply | wc -l)" -eq 3 ] || fail "expected p_00.ply, p_01.ply and p_02.ply (t = 0, 0.05, 0.1)"
for f in "$OUT"/p_0{0,1,2}.ply; do check_info "$f"; done
cmp -s "$OUT/p_00.ply" "$OUT/p_02.ply" && fail "the first and last .ply are the same: the slime did not move"
"$SLIME" sim --seconds 0.1 --export-mesh "$OUT/o_%d.obj" --export-every 0.1 >/dev/null || fail "sim .obj failed"
check_info "$OUT/o_1.obj"
grep -q "^mtllib o_1.mtl$" "$OUT/o_1.obj" || fail "o_1.obj does not name its material library o_1.mtl"
grep -q "^Ni 1.35$" "$OUT/o_1.mtl" || fail "o_1.mtl lacks the slime's index of refraction"
# y up by default: the settled slime's top is high along y; --obj-up z keeps the simulation's z.
max_along() { awk -v a="$2" '$1 == "v" { if (!seen || $a > m) m = $a; seen = 1 } END { print m }' "$1"; }
awk -v y="$(max_along "$OUT/o_0.obj" 3)" 'BEGIN { exit !(y > 0.1) }' || fail "o_0.obj is not y up (top at y = $(max_along "$OUT/o_0.obj" 3))"
"$SLIME" sim --seconds 0.1 --export-mesh "$OUT/z_%d.obj" --export-every 0.1 --obj-up z >/dev/null || fail "--obj-up z failed"
awk -v z="$(max_along "$OUT/z_0.obj" 4)" 'BEGIN { exit !(z > 0.1) }' || fail "z_0.obj is not z up"
"$SLIME" sim --seconds 0.1 --export-mesh "$OUT/run.glb" --export-every 0.02 >/dev/null || fail "sim .glb failed"
check_info "$OUT/run.glb" 1
"$SLIME" snapshot --size 64x48 --settle 0.1 -o "$OUT/snap.png" --export-mesh "$OUT/snap.glb" >/dev/null ||
  fail "snapshot --export-mesh failed"
check_info "$OUT/snap.glb"

refused() {  # refused WHAT ARGS...: exit 2, a message naming the option, and no new file
  local what="$1"; shift
  local before; before=$(ls "$OUT" | wc -l)
  "$SLIME" "$@" 2>"$OUT/err.txt" >/dev/null
  local code=$?
  [ $code -eq 2 ] || fail "$what: exit $code, expected 2"
  grep -Eq -- "--export|--obj-up" "$OUT/err.txt" || fail "$what: the error does not name the option: $(cat "$OUT/err.txt")"
  rm -f "$OUT/err.txt"
  [ "$(ls "$OUT" | wc -l)" -eq "$before" ] || fail "$what: left a file"
}
refused "no frame number" sim --seconds 0.1 --export-mesh "$OUT/one.ply" --export-every 0.05
refused "two frame numbers" sim --seconds 0.1 --export-mesh "$OUT/a%d_%d.obj" --export-every 0.05
refused "a string conversion" sim --seconds 0.1 --export-mesh "$OUT/a%s.ply" --export-every 0.05
refused "an unknown format" sim --seconds 0.1 --export-mesh "$OUT/a%d.stl" --export-every 0.05
refused "no directory" sim --seconds 0.1 --export-mesh "$OUT/missing/a%d.ply" --export-every 0.05
refused "no interval" sim --seconds 0.1 --export-mesh "$OUT/a%d.ply"
refused "a zero interval" sim --seconds 0.1 --export-mesh "$OUT/a%d.ply" --export-every 0
refused "snapshot, unknown format" snapshot --size 64x48 --settle 0.1 -o "$OUT/x.png" --export-mesh "$OUT/x.stl"
refused "an unknown up axis" sim --seconds 0.1 --export-mesh "$OUT/a%d.obj" --export-every 0.05 --obj-up x
refused "an up axis for a .glb" snapshot --size 64x48 --settle 0.1 -o "$OUT/x.png" --export-mesh "$OUT/x.glb" --obj-up z
refused "snapshot, no directory" snapshot --size 64x48 --settle 0.1 -o "$OUT/x.png" --export-mesh "$OUT/no/x.ply"
echo "PASS: .ply, .obj (y and z up, with its .mtl), .glb and the snapshot's surface read by assimp; 11 bad uses refused"
