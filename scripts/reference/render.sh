#!/bin/bash
# Renders Slime's scene with Blender's Cycles (a physically based path tracer) and compares our frames
# with it: docs/rendering.md, "Against a path-traced reference".
#
#   scripts/reference/render.sh OUT_DIR [--size WxH] [--samples N] [--bare-samples N] [-- SCENE_OPTIONS...]
#     OUT_DIR         gets scene.json, slime.glb, the floor's tiles, masks.pfm (+ masks_haze.pfm), the
#                     reference (reference.exr/.pfm, seed 1), its second seed (reference_seed2), the
#                     reference without the slime (reference_bare), our frames (ours_<shading>_d<depth>.pfm
#                     and .png, ours_bare.pfm), side_<shading>_d<depth>.png and table.txt
#     --size          image size (default 320x240)
#     --samples       Cycles' samples a pixel of the reference and of its second seed (default 1024)
#     after --        passed to `slime snapshot`, e.g. -- --set slime.color=1,1,1 --set slime.absorption=0
#   SLIME=path/to/slime (default build/release/app/slime), THREADS (default 2)
#
# Needs Debian's blender (3.4) with python3-numpy. Not part of CI: a reference takes minutes.
set -euo pipefail
cd "$(dirname "$0")/../.."
root="$(pwd)"
[ $# -ge 1 ] || { sed -n 2,16p "$0" >&2; exit 2; }
out="$1"
shift
size=320x240
samples=1024
bare_samples=16
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size="$2"; shift 2 ;;
    --samples) samples="$2"; shift 2 ;;
    --bare-samples) bare_samples="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "render.sh: unknown option '$1' (allowed: --size WxH, --samples N, --bare-samples N, -- scene options)" >&2
       exit 2 ;;
  esac
done
scene=("$@")
slime="$(realpath "${SLIME:-build/release/app/slime}")"
threads="${THREADS:-2}"
[ -x "$slime" ] || { echo "render.sh: no slime binary at $slime (build first: scripts/test.sh)" >&2; exit 2; }
command -v blender >/dev/null || {
  echo "render.sh: blender is needed for the reference and was not found on PATH (Debian: apt-get install blender python3-numpy)" >&2
  exit 2
}
blender -b --factory-startup --python-expr "import numpy" >/dev/null 2>&1 || {
  echo "render.sh: Blender's Python cannot import numpy (Debian: apt-get install python3-numpy)" >&2
  exit 2
}
mkdir -p "$out"
out="$(realpath "$out")"
py="$root/scripts/reference/cycles_scene.py"
cycles() { blender -b --factory-startup -P "$py" -- --scene "$out/scene.json" --mesh "$out/slime.glb" --threads "$threads" "$@" 2>&1 |
  grep '^reference\|Error\|rror:' ; }

# Ours: the scene, the drawn surface of the frame and the frames to compare (the settled slime is the
# same in each: the snapshot is deterministic and the physics does not read render.*).
"$slime" snapshot --size "$size" -o "$out/ours.png" --reference-scene "$out" --export-mesh "$out/slime.glb" "${scene[@]}" >/dev/null
"$slime" snapshot --size "$size" -o "$out/ours_bare.png" --linear "$out/ours_bare.pfm" "${scene[@]}" \
  --set render.shadows=false --set render.caustics=false --set render.shading=physical >/dev/null
for shading in classic physical; do
  for depth in 3 16; do
    "$slime" snapshot --size "$size" -o "$out/ours_${shading}_d$depth.png" --linear "$out/ours_${shading}_d$depth.pfm" \
      "${scene[@]}" --set render.shading=$shading --set render.depth=$depth >/dev/null
  done
done

# The reference: two seeds, and the floor without the slime (for the shadow's gain), and the masks.
[ -f "$out/reference.pfm" ] || cycles --out "$out/reference" --samples "$samples" --seed 1 --masks "$out/masks.pfm"
[ -f "$out/reference_seed2.pfm" ] || cycles --out "$out/reference_seed2" --samples "$samples" --seed 2
[ -f "$out/reference_bare.pfm" ] || cycles --out "$out/reference_bare" --samples "$bare_samples" --seed 1 --no-slime

compare() { "$slime" bench reference --masks "$out/masks.pfm" --haze "$out/masks_haze.pfm" "$@"; }
{
  echo "# $(blender --version 2>/dev/null | head -1), $samples samples, $size; scene: ${scene[*]:-default}"
  compare --ours "$out/reference_seed2.pfm" --reference "$out/reference.pfm" --label "reference seed 2 vs seed 1"
  for shading in classic physical; do
    for depth in 3 16; do
      compare --ours "$out/ours_${shading}_d$depth.pfm" --reference "$out/reference.pfm" \
        --ours-bare "$out/ours_bare.pfm" --reference-bare "$out/reference_bare.pfm" \
        --picture "$out/side_${shading}_d$depth.png" --label "$shading depth $depth"
    done
  done
} | tee "$out/table.txt"
