#!/bin/bash
# The two headless GL back-ends draw the same viewer: `snapshot --ui --gl egl` and `--gl osmesa` agree
# within 1/255 on at least 99.9 % of the pixels; with EGL unusable (its vendor library pointing
# nowhere) `--gl auto` says so on stderr and still draws, through OSMesa; a bad --gl is refused.
set -u
SLIME="$1"
OUT="$2"
rm -rf "$OUT" && mkdir -p "$OUT"
fail() { echo "FAIL: $*" >&2; exit 1; }
unset DISPLAY  # prove that no X server is needed
SIZE=400x300
PIXELS=120000

snap() {  # snap NAME [--gl API]: the viewer at SIZE, settled 0.2 s, into NAME.png; stderr kept in NAME.err
  local name="$1"; shift
  "$SLIME" snapshot --ui --size $SIZE --settle 0.2 -o "$OUT/$name.png" "$@" 2>"$OUT/$name.err"
}

# Pixels of two PNGs of SIZE differing by more than 1/255 in a channel: cmp lists differing bytes
# (1-based offset, both values in octal) of the raw RGB.
differing_pixels() {
  convert "$OUT/$1.png" -depth 8 rgb:"$OUT/$1.rgb" && convert "$OUT/$2.png" -depth 8 rgb:"$OUT/$2.rgb" || return 1
  cmp -l "$OUT/$1.rgb" "$OUT/$2.rgb" | awk '
    function octal(s,   v, i) { v = 0; for (i = 1; i <= length(s); ++i) v = v * 8 + substr(s, i, 1); return v }
    { d = octal($2) - octal($3); if (d > 1 || d < -1) seen[int(($1 - 1) / 3)] = 1 }
    END { n = 0; for (p in seen) ++n; print n }'
}

snap egl --gl egl || fail "snapshot --ui --gl egl failed: $(cat "$OUT/egl.err")"
snap osmesa --gl osmesa || fail "snapshot --ui --gl osmesa failed: $(cat "$OUT/osmesa.err")"
[ "$(identify -format '%wx%h' "$OUT/osmesa.png")" = "$SIZE" ] || fail "osmesa.png is not $SIZE"
both=$(differing_pixels egl osmesa) || fail "cannot read the pictures"
[ $((both * 1000)) -le $PIXELS ] || fail "$both of $PIXELS pixels differ by more than 1/255 between EGL and OSMesa"

# EGL unusable: GLVND finds no vendor library, so eglGetPlatformDisplay fails.
export __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent
snap auto || fail "snapshot --ui (auto) without EGL failed: $(cat "$OUT/auto.err")"
grep -q "drawing with OSMesa" "$OUT/auto.err" || fail "auto did not say on stderr that it fell back to OSMesa"
fallback=$(differing_pixels egl auto) || fail "cannot read the fallback picture"
[ $((fallback * 1000)) -le $PIXELS ] || fail "$fallback pixels differ between EGL and the fallback"
snap forced --gl egl && fail "--gl egl drew without EGL"
[ -e "$OUT/forced.png" ] && fail "--gl egl without EGL left a file"
grep -q "EGL" "$OUT/forced.err" || fail "--gl egl without EGL did not say why"
unset __EGL_VENDOR_LIBRARY_FILENAMES

snap bad --gl vulkan; [ $? -eq 2 ] || fail "--gl vulkan did not exit with 2"
grep -q "egl, osmesa or auto" "$OUT/bad.err" || fail "--gl vulkan: the error does not list the choices"
[ -e "$OUT/bad.png" ] && fail "--gl vulkan left a file"

"$SLIME" record --ui --gl osmesa --seconds 0.2 --fps 10 --size 160x120 -o "$OUT/clip.gif" 2>"$OUT/record.err" ||
  fail "record --ui --gl osmesa failed: $(cat "$OUT/record.err")"
[ "$(identify "$OUT/clip.gif" | wc -l)" -eq 2 ] || fail "the OSMesa clip does not hold 2 frames"
echo "PASS: EGL and OSMesa differ on $both of $PIXELS pixels, the fallback on $fallback"
