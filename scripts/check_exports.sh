#!/bin/bash
# Checks Slime's exports with two programs that know nothing of Slime (docs/export.md, "Checked by other
# programs"): the Khronos glTF validator on a still and an animated .glb (0 errors, 0 warnings), and
# Blender 3.4's own importers, which must find the .glb's jelly (transmission > 0, the scene's IOR, a
# base colour of the scene's hue, an absorbing volume) and the .obj standing upright where the .glb
# stands; each import is rendered to a small Cycles image to look at.
#
#   scripts/check_exports.sh [OUT_DIR] [-- SLIME_SCENE_OPTIONS...]
#     OUT_DIR   default build/check_exports; gets the exports, validator.txt, blender.txt, glb.png, obj.png
#     after --  passed to `slime snapshot` and `slime sim`, e.g. -- --set slime.color=0.9,0.9,1
#   SLIME=path/to/slime (default build/release/app/slime)
#   SLIME_NPM_DIR=where gltf-validator is installed with npm if missing (default /tmp/slime-gltf-validator)
#
# Needs node and npm (the validator comes from the npm registry), and Blender with numpy (Debian:
# apt-get install blender python3-numpy). Takes about a minute; not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/check_exports}"
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
scene=("$@")
slime="$(realpath "${SLIME:-build/release/app/slime}")"
npm_dir="${SLIME_NPM_DIR:-/tmp/slime-gltf-validator}"
[ -x "$slime" ] || { echo "check_exports.sh: no slime binary at $slime (build first: scripts/test.sh)" >&2; exit 2; }
for tool in node npm blender; do
  command -v "$tool" >/dev/null || { echo "check_exports.sh: $tool is needed (see the header)" >&2; exit 2; }
done
mkdir -p "$out"
out="$(realpath "$out")"
fail() { echo "FAIL: $*" >&2; exit 1; }

# The exports: the settled default slime as a still .glb and a y-up .obj (the same frame: the snapshot is
# deterministic), and 32 frames of a pulled slime as one animated .glb.
"$slime" snapshot --size 160x120 -o "$out/snapshot.png" --export-mesh "$out/still.glb" "${scene[@]}" >/dev/null
"$slime" snapshot --size 160x120 -o "$out/snapshot.png" --export-mesh "$out/still.obj" "${scene[@]}" >/dev/null
"$slime" sim --seconds 0.62 --scenario assets/scenarios/pull_release_press.json --export-mesh "$out/animated.glb" \
  --export-every 0.02 "${scene[@]}" >/dev/null

# The Khronos validator, through its npm package's validateBytes.
if [ ! -d "$npm_dir/node_modules/gltf-validator" ]; then
  mkdir -p "$npm_dir"
  npm install --prefix "$npm_dir" --no-save --silent gltf-validator >/dev/null
fi
cat > "$out/validate.js" <<'JS'
const validator = require('gltf-validator');
const fs = require('fs');
(async () => {
  let bad = 0;
  for (const path of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(path)), {maxIssues: 100});
    const i = report.issues;
    console.log(`${path.split('/').pop()}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ` +
                `${i.numHints} hints; extensions ${report.info.extensionsUsed}; gltf-validator ${report.validatorVersion}`);
    for (const m of i.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`);
    if (i.numErrors + i.numWarnings > 0) bad = 1;
  }
  process.exit(bad);
})();
JS
NODE_PATH="$npm_dir/node_modules" node "$out/validate.js" "$out/still.glb" "$out/animated.glb" | tee "$out/validator.txt" ||
  fail "the glTF validator found errors or warnings (above)"

# Blender: import, check, render.
cat > "$out/blender_check.py" <<'PY'
import sys
import numpy
numpy.bool = bool  # Blender 3.4's glTF importer uses numpy.bool, which Debian 12's numpy no longer has
import math

import bpy

out = sys.argv[sys.argv.index("--") + 1]
problems = []

def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        problems.append(what)

def imported(action):
    before = set(bpy.data.objects)
    action()
    return [o for o in bpy.data.objects if o not in before and o.type == 'MESH']

def world_bounds(obj):
    points = [obj.matrix_world @ v.co for v in obj.data.vertices]
    return [min(p[a] for p in points) for a in range(3)], [max(p[a] for p in points) for a in range(3)]

def principled(obj):
    """The object's material and its Principled BSDF node, or None for either."""
    material = obj.active_material
    if material is None or material.node_tree is None:
        return material, None
    return material, next((n for n in material.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'), None)

def numbers(name, count):
    at = sys.argv.index(name) + 1
    return [float(x) for x in sys.argv[at:at + count]]

def render(objects, path):
    """A small Cycles image of `objects` on a checker floor under a sun and a sky."""
    scene = bpy.context.scene
    for obj in bpy.data.objects:
        obj.hide_render = obj not in objects and obj.type == 'MESH' and obj.name != "floor"
    scene.render.engine = 'CYCLES'
    scene.cycles.samples = 32
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    scene.cycles.max_bounces = 16
    scene.cycles.transmission_bounces = 16
    scene.render.resolution_x, scene.render.resolution_y = 320, 240
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)

bpy.ops.wm.read_factory_settings(use_empty=True)

# The still .glb: a material with transmission, the scene's IOR and a base colour of the slime's hue.
glb = imported(lambda: bpy.ops.import_scene.gltf(filepath=out + "/still.glb"))
check(len(glb) == 1, "still.glb: one mesh")
material, bsdf = principled(glb[0])
check(bsdf is not None, "still.glb: a material with a Principled BSDF")
if bsdf is not None:
    base = bsdf.inputs["Base Color"].default_value
    transmission = bsdf.inputs["Transmission"].default_value
    ior = bsdf.inputs["IOR"].default_value
    print(f"     material {material.name}: base colour ({base[0]:.3f}, {base[1]:.3f}, {base[2]:.3f}), "
          f"metallic {bsdf.inputs['Metallic'].default_value:.2f}, roughness {bsdf.inputs['Roughness'].default_value:.3f}, "
          f"transmission {transmission:.3f}, IOR {ior:.3f}")
    check(transmission > 0.0, "still.glb: transmission > 0")
    check(abs(ior - numbers("--ior", 1)[0]) < 1e-5, "still.glb: the scene's IOR (the .mtl's Ni)")
    kd = numbers("--color", 3)
    check(max(abs(base[i] - kd[i]) for i in range(3)) < 1e-5, "still.glb: the scene's colour as base colour (the .mtl's Kd)")
    if kd[1] > kd[0] and kd[1] > kd[2]:
        check(base[1] > base[0] and base[1] > base[2], "still.glb: a green base colour (the slime's)")
    volume = [n for n in material.node_tree.nodes if n.type == 'VOLUME_ABSORPTION']
    check(len(volume) == 1, "still.glb: a volume absorption node (KHR_materials_volume)")
    if volume:
        c = volume[0].inputs["Color"].default_value
        print(f"     volume absorption: colour ({c[0]:.3f}, {c[1]:.3f}, {c[2]:.3f}), "
              f"density {volume[0].inputs['Density'].default_value:.3f} /m")

# The .obj, Blender's default import (forward −Z, up Y): upright, exactly where the .glb stands.
obj = imported(lambda: bpy.ops.wm.obj_import(filepath=out + "/still.obj"))
check(len(obj) == 1, "still.obj: one mesh")
(glb_low, glb_high), (obj_low, obj_high) = world_bounds(glb[0]), world_bounds(obj[0])
print("     .glb bounds " + ", ".join(f"{a} {glb_low[i]:+.5f}..{glb_high[i]:+.5f} m" for i, a in enumerate("xyz")))
print("     .obj bounds " + ", ".join(f"{a} {obj_low[i]:+.5f}..{obj_high[i]:+.5f} m" for i, a in enumerate("xyz")))
check(max(abs(obj_low[i] - glb_low[i]) + abs(obj_high[i] - glb_high[i]) for i in range(3)) < 1e-6,
      "still.obj: the same place as the .glb, within 1 µm")
check(abs(obj_low[2]) < 1e-3 and obj_high[2] > 0.02, "still.obj: on the floor (z = 0) and rising along Blender's Z")
_, obj_bsdf = principled(obj[0])
check(obj_bsdf is not None, "still.obj: its .mtl gives a material")
if obj_bsdf is not None:
    b = obj_bsdf.inputs["Base Color"].default_value
    print(f"     .mtl material: base colour ({b[0]:.3f}, {b[1]:.3f}, {b[2]:.3f}), "
          f"metallic {obj_bsdf.inputs['Metallic'].default_value:.2f}, "
          f"roughness {obj_bsdf.inputs['Roughness'].default_value:.3f}, "
          f"transmission {obj_bsdf.inputs['Transmission'].default_value:.3f}, "
          f"IOR {obj_bsdf.inputs['IOR'].default_value:.3f}")
    check(obj_bsdf.inputs["Transmission"].default_value > 0.0 and obj_bsdf.inputs["Metallic"].default_value == 0.0,
          "still.obj: its .mtl gives a transmissive, non-metallic material")

# The animated .glb: a shape key per frame.
animated = imported(lambda: bpy.ops.import_scene.gltf(filepath=out + "/animated.glb"))
keys = animated[0].data.shape_keys.key_blocks if animated and animated[0].data.shape_keys else []
print(f"     animated.glb: {max(len(keys) - 1, 0)} shape keys")
check(len(keys) - 1 == 32, "animated.glb: 32 frames as shape keys")
for o in animated:
    o.hide_render = True

# A floor, a sun and a sky, then one image of each import.
bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.0))
floor = bpy.context.object
floor.name = "floor"
checker = bpy.data.materials.new("checker")
checker.use_nodes = True
texture = checker.node_tree.nodes.new("ShaderNodeTexChecker")
texture.inputs["Scale"].default_value = 25.0  # 4 cm squares on the 1 m plane
checker.node_tree.links.new(texture.outputs["Color"], checker.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
floor.data.materials.append(checker)
bpy.ops.object.light_add(type='SUN', rotation=(0.6, 0.3, 0.5))
bpy.context.object.data.energy = 3.0
world = bpy.data.worlds.new("sky")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.9, 1.0)
bpy.context.scene.world = world
camera_data = bpy.data.cameras.new("camera")
camera = bpy.data.objects.new("camera", camera_data)
bpy.context.scene.collection.objects.link(camera)
camera.location = (0.0, -0.22, 0.10)  # the default scene's eye, looking 20° down as its camera does
camera.rotation_euler = (math.radians(70.0), 0.0, 0.0)
camera_data.angle_y = 0.785  # 45° vertical field of view
camera_data.sensor_fit = 'VERTICAL'
bpy.context.scene.camera = camera
render(glb, out + "/glb.png")
render(obj, out + "/obj.png")

print("PASS" if not problems else f"FAIL: {len(problems)} checks")
sys.exit(1 if problems else 0)
PY
# The scene's colour and IOR as the .mtl states them, for Blender's import of the .glb to be compared with.
grep -q "^Kd " "$out/still.mtl" 2>/dev/null && grep -q "^Ni " "$out/still.mtl" ||
  fail "no .mtl with Kd and Ni beside still.obj ($out/still.mtl)"
read -r _ kd_r kd_g kd_b < <(grep "^Kd " "$out/still.mtl")
read -r _ ni < <(grep "^Ni " "$out/still.mtl")
blender -b --python "$out/blender_check.py" -- "$out" --color "$kd_r" "$kd_g" "$kd_b" --ior "$ni" \
  >"$out/blender.log" 2>&1 || true
grep -E "^(ok|FAIL|PASS|     )" "$out/blender.log" | tee "$out/blender.txt"
grep -q "^PASS$" "$out/blender.txt" || fail "Blender's imports (above; the whole log: $out/blender.log)"
echo "PASS: validator and Blender; images $out/glb.png and $out/obj.png"
