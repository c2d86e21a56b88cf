# Renders Slime's scene with Blender's Cycles, a physically based path tracer (run by render.sh):
#   blender -b --factory-startup -P cycles_scene.py -- --scene DIR/scene.json --mesh DIR/slime.glb
#       --out DIR/reference [--samples N] [--seed S] [--no-slime] [--masks DIR/masks.pfm] [--threads T]
# writes OUT.exr (32-bit float, linear) and OUT.pfm (the same floats, for `slime bench reference`).
#
# The scene is `slime snapshot --reference-scene DIR`'s (app/bench/render/reference_scene.h) with the
# drawn surface of the same frame (--export-mesh DIR/slime.glb). Every setting Cycles would otherwise
# default is pinned: the Standard view transform, no clamping, no glossy filter, a one-pixel box filter,
# a point light of radius 0, 64 bounces of every kind, no denoiser, no adaptive sampling.
#
# How the project's model maps onto a physical one:
# - The floor is a Lambertian plane of the project's albedo (the tiles: each texel the pattern's box
#   average) and the slime a smooth dielectric (Glass BSDF, the scene's index) filled with an absorbing
#   homogeneous volume of the project's σ per channel (physical shading's: k (−ln(color · k_t))).
# - The light has no fall-off in the project: the floor's lit term is k_d · albedo · I_l · cos θ at any
#   distance. A Cycles point light of power P gives a Lambertian floor radiance albedo · P cos θ /
#   (4π² r²); its emission goes through a Light Falloff node's Constant output, which multiplies by r²,
#   so P = 4π² k_d I_l reproduces the project's light exactly (k_d folded into the light, so that the
#   ambient below sees the albedo itself).
# - The ambient: the project adds albedo · I_a to the floor, as a uniform sky of radiance I_a would
#   to a Lambertian floor that sees all of it. Here the world returns I_a to every path that has made a
#   diffuse bounce (so the floor's ambient is occluded and tinted by the jelly, physically), and the
#   sky's gradient, mix(horizon, zenith, √z), to the camera's own rays through the jelly or past it.
# - The haze: the floor's radiance is mixed towards the horizon colour by 1 − exp(−d / haze distance),
#   d the ray's length to it, as the project does.
# - The light through the jelly onto the floor (a point light seen through a refracting surface) cannot
#   be found by tracing paths from the eye. Cycles' shadow caustics (manifold next-event estimation) are
#   switched on for it (the slime casts, the floor receives, the light is a caustics light; --no-mnee
#   turns them off), but on this scene they return almost nothing: the direct light's gain in the
#   shadow read 0.001–0.005 for the green slime and about 0.02 for a clear one, where the straight
#   rays alone give 0.03–0.09 and 0.9. So the reference's shadow holds the ambient (sky) light that
#   reaches it through and around the jelly, and not the caustic: compare the shadow's colour with the
#   light off (--set light.color=0,0,0 on both sides), as docs/rendering.md does.
import math
import sys
import time

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer uses numpy.bool, which Debian 12's numpy no longer has

import bpy
import mathutils
from mathutils.bvhtree import BVHTree


def arguments():
    import argparse
    parser = argparse.ArgumentParser(prog="cycles_scene.py")
    parser.add_argument("--scene", required=True)
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--samples", type=int, default=256)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--no-slime", action="store_true")
    parser.add_argument("--no-mnee", action="store_true")
    parser.add_argument("--masks")
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return parser.parse_args(argv)


def read_pfm(path):
    with open(path, "rb") as f:
        magic = f.readline().strip()
        if magic != b"PF":
            raise SystemExit(f"{path}: not a colour PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = numpy.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4", count=width * height * 3)
    return width, height, data.reshape(height, width, 3).astype(numpy.float32)  # bottom row first


def write_pfm(path, rgb):  # rgb: rows bottom to top, (h, w, 3)
    height, width, _ = rgb.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{width} {height}\n-1.0\n".encode())
        f.write(numpy.ascontiguousarray(rgb, dtype="<f4").tobytes())


def float_image(name, path):
    width, height, rgb = read_pfm(path)
    image = bpy.data.images.new(name, width, height, float_buffer=True, alpha=False)
    image.colorspace_settings.name = "Non-Color"
    rgba = numpy.ones((height, width, 4), dtype=numpy.float32)
    rgba[:, :, :3] = rgb
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    return image


def vec(v):
    return mathutils.Vector(v)


def setup_render(scene, spec, a):
    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x = spec["image"]["width"]
    render.resolution_y = spec["image"]["height"]
    render.resolution_percentage = 100
    render.pixel_aspect_x = render.pixel_aspect_y = 1.0
    render.use_border = False
    render.film_transparent = False
    render.use_motion_blur = False
    if a.threads > 0:
        render.threads_mode = "FIXED"
        render.threads = a.threads
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    render.image_settings.color_mode = "RGB"
    render.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.view_settings.use_curve_mapping = False
    scene.display_settings.display_device = "sRGB"
    scene.sequencer_colorspace_settings.name = "sRGB"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.samples
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_preview_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    for bounces in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                    "volume_bounces", "transparent_max_bounces"):
        setattr(c, bounces, 64)
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.light_sampling_threshold = 0.0
    c.film_exposure = 1.0
    c.use_layer_samples = "IGNORE"
    c.sample_offset = 0
    c.volume_step_rate = 1.0
    scene.cycles_curves.shape = "RIBBONS"


def setup_camera(scene, spec):
    cam = spec["camera"]
    data = bpy.data.cameras.new("camera")
    data.type = "PERSP"
    data.sensor_fit = "VERTICAL"
    data.angle_y = 2.0 * math.atan(cam["tan_half_fov"])
    data.shift_x = data.shift_y = 0.0
    data.clip_start = 1e-4
    data.clip_end = 1e5
    obj = bpy.data.objects.new("camera", data)
    # A Blender camera looks down its local −Z with +Y up: columns right, up, −forward.
    right, up, forward = vec(cam["right"]), vec(cam["up"]), vec(cam["forward"])
    basis = mathutils.Matrix((right, up, -forward)).transposed()
    obj.matrix_world = mathutils.Matrix.Translation(vec(cam["eye"])) @ basis.to_4x4()
    scene.collection.objects.link(obj)
    scene.camera = obj


def setup_world(scene, spec):
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    world.cycles.sampling_method = "NONE"  # the ambient is reached by the floor's own cosine-weighted rays
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputWorld")
    coords = nodes.new("ShaderNodeTexCoord")
    xyz = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coords.outputs["Generated"], xyz.inputs[0])  # the world's Generated is the ray's direction
    clamp = nodes.new("ShaderNodeClamp")
    links.new(xyz.outputs["Z"], clamp.inputs["Value"])
    root = nodes.new("ShaderNodeMath")
    root.operation = "SQRT"
    links.new(clamp.outputs[0], root.inputs[0])
    gradient = nodes.new("ShaderNodeMixRGB")
    gradient.blend_type = "MIX"
    links.new(root.outputs[0], gradient.inputs["Fac"])
    gradient.inputs["Color1"].default_value = (*spec["sky"]["horizon"], 1.0)
    gradient.inputs["Color2"].default_value = (*spec["sky"]["zenith"], 1.0)
    sky = nodes.new("ShaderNodeBackground")
    links.new(gradient.outputs[0], sky.inputs["Color"])
    ambient = nodes.new("ShaderNodeBackground")
    ambient.inputs["Color"].default_value = (*spec["light"]["ambient"], 1.0)
    path = nodes.new("ShaderNodeLightPath")
    diffused = nodes.new("ShaderNodeMath")
    diffused.operation = "GREATER_THAN"
    links.new(path.outputs["Diffuse Depth"], diffused.inputs[0])
    diffused.inputs[1].default_value = 0.5
    mix = nodes.new("ShaderNodeMixShader")
    links.new(diffused.outputs[0], mix.inputs["Fac"])
    links.new(sky.outputs[0], mix.inputs[1])
    links.new(ambient.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])


def setup_light(scene, spec, a):
    light = spec["light"]
    data = bpy.data.lights.new("light", "POINT")
    data.shadow_soft_size = 0.0
    data.color = light["color"]
    data.energy = 4.0 * math.pi ** 2 * light["floor_diffuse"]
    data.use_nodes = True
    data.cycles.cast_shadow = True
    data.cycles.use_multiple_importance_sampling = True
    data.cycles.is_caustics_light = not a.no_mnee
    nodes, links = data.node_tree.nodes, data.node_tree.links
    emission = next(n for n in nodes if n.type == "EMISSION")
    emission.inputs["Strength"].default_value = 1.0
    emission.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    falloff = nodes.new("ShaderNodeLightFalloff")
    falloff.inputs["Strength"].default_value = 1.0
    falloff.inputs["Smooth"].default_value = 0.0
    links.new(falloff.outputs["Constant"], emission.inputs["Strength"])
    obj = bpy.data.objects.new("light", data)
    obj.location = vec(light["position"])
    scene.collection.objects.link(obj)


def setup_floor(scene, spec, directory, a):
    size = 2.0e4
    mesh = bpy.data.meshes.new("floor")
    h = 0.5 * size
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new("floor", mesh)
    scene.collection.objects.link(obj)
    obj.cycles.is_caustics_receiver = not a.no_mnee
    material = bpy.data.materials.new("floor")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    geometry = nodes.new("ShaderNodeNewGeometry")
    position = nodes.new("ShaderNodeSeparateXYZ")
    links.new(geometry.outputs["Position"], position.inputs[0])
    color = None
    tiles = spec["floor"]["tiles"]
    # The finest tile last, so that it wins where the tiles overlap.
    albedo = nodes.new("ShaderNodeRGB")
    albedo.outputs[0].default_value = (*spec["floor"]["mean_albedo"], 1.0)
    color = albedo.outputs[0]
    for tile in reversed(tiles):
        image = float_image(tile["file"], f"{directory}/{tile['file']}")
        x0 = tile["center"][0] - 0.5 * tile["size"]
        y0 = tile["center"][1] - 0.5 * tile["size"]
        coords = []
        inside = None
        for axis, origin in (("X", x0), ("Y", y0)):
            u = nodes.new("ShaderNodeMath")
            u.operation = "MULTIPLY_ADD"
            links.new(position.outputs[axis], u.inputs[0])
            u.inputs[1].default_value = 1.0 / tile["size"]
            u.inputs[2].default_value = -origin / tile["size"]
            coords.append(u)
            low = nodes.new("ShaderNodeMath")
            low.operation = "GREATER_THAN"
            links.new(u.outputs[0], low.inputs[0])
            low.inputs[1].default_value = 0.0
            high = nodes.new("ShaderNodeMath")
            high.operation = "LESS_THAN"
            links.new(u.outputs[0], high.inputs[0])
            high.inputs[1].default_value = 1.0
            both = nodes.new("ShaderNodeMath")
            both.operation = "MULTIPLY"
            links.new(low.outputs[0], both.inputs[0])
            links.new(high.outputs[0], both.inputs[1])
            if inside is None:
                inside = both
            else:
                joined = nodes.new("ShaderNodeMath")
                joined.operation = "MULTIPLY"
                links.new(inside.outputs[0], joined.inputs[0])
                links.new(both.outputs[0], joined.inputs[1])
                inside = joined
        uv = nodes.new("ShaderNodeCombineXYZ")
        links.new(coords[0].outputs[0], uv.inputs["X"])
        links.new(coords[1].outputs[0], uv.inputs["Y"])
        texture = nodes.new("ShaderNodeTexImage")
        texture.image = image
        texture.interpolation = "Closest"
        texture.extension = "EXTEND"
        links.new(uv.outputs[0], texture.inputs["Vector"])
        mix = nodes.new("ShaderNodeMixRGB")
        mix.blend_type = "MIX"
        links.new(inside.outputs[0], mix.inputs["Fac"])
        links.new(color, mix.inputs["Color1"])
        links.new(texture.outputs["Color"], mix.inputs["Color2"])
        color = mix.outputs[0]
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0
    links.new(color, diffuse.inputs["Color"])
    horizon = nodes.new("ShaderNodeEmission")
    horizon.inputs["Color"].default_value = (*spec["sky"]["horizon"], 1.0)
    horizon.inputs["Strength"].default_value = 1.0
    path = nodes.new("ShaderNodeLightPath")
    scaled = nodes.new("ShaderNodeMath")
    scaled.operation = "MULTIPLY"
    links.new(path.outputs["Ray Length"], scaled.inputs[0])
    scaled.inputs[1].default_value = -1.0 / spec["sky"]["haze_distance"]
    kept = nodes.new("ShaderNodeMath")
    kept.operation = "EXPONENT"
    links.new(scaled.outputs[0], kept.inputs[0])
    haze = nodes.new("ShaderNodeMath")
    haze.operation = "SUBTRACT"
    haze.inputs[0].default_value = 1.0
    links.new(kept.outputs[0], haze.inputs[1])
    mix = nodes.new("ShaderNodeMixShader")
    links.new(haze.outputs[0], mix.inputs["Fac"])
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(horizon.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    mesh.materials.append(material)
    return obj


def setup_slime(scene, spec, mesh_path, a):
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=mesh_path)
    imported = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    if not imported:
        raise SystemExit(f"{mesh_path}: no mesh imported")
    material = bpy.data.materials.new("jelly")
    material.use_nodes = True
    material.cycles.homogeneous_volume = True
    material.cycles.volume_interpolation = "LINEAR"
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    glass = nodes.new("ShaderNodeBsdfGlass")
    glass.distribution = "SHARP"
    glass.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    glass.inputs["IOR"].default_value = spec["slime"]["ior"]
    links.new(glass.outputs[0], out.inputs["Surface"])
    sigma = spec["slime"]["absorption_per_metre"]
    density = max(sigma)
    if density > 0.0:
        # Cycles' Volume Absorption absorbs density · (1 − colour) per unit length, each channel.
        absorption = nodes.new("ShaderNodeVolumeAbsorption")
        absorption.inputs["Density"].default_value = density
        absorption.inputs["Color"].default_value = (*(1.0 - s / density for s in sigma), 1.0)
        links.new(absorption.outputs[0], out.inputs["Volume"])
    for obj in imported:
        obj.data.materials.clear()
        obj.data.materials.append(material)
        for polygon in obj.data.polygons:
            polygon.use_smooth = True
        obj.cycles.is_caustics_caster = not a.no_mnee
        if a.no_slime:
            obj.hide_render = True
    return imported


def write_masks(path, spec, slimes, scene):
    """R: the pixels that see the slime; G: floor pixels in its shadow (the straight ray from the floor point
    to the light crosses the slime, at the point and at 2 mm from it in 8 directions: eroded by 2 mm); B: lit
    floor (no such ray crosses it, at the point and 2 mm around it). Pixel centres, the project's camera rays.
    Beside it, NAME_haze.pfm: what the haze adds to each floor pixel, (1 − exp(−d / haze distance)) · horizon,
    which the shadow's gain takes away from both images before it divides."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    vertices, polygons = [], []
    for obj in slimes:
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        offset = len(vertices)
        vertices += [obj.matrix_world @ v.co for v in mesh.vertices]
        polygons += [[offset + i for i in p.vertices] for p in mesh.polygons]
        evaluated.to_mesh_clear()
    tree = BVHTree.FromPolygons(vertices, polygons)
    cam = spec["camera"]
    width, height = spec["image"]["width"], spec["image"]["height"]
    eye, forward, right, up = (vec(cam[k]) for k in ("eye", "forward", "right", "up"))
    light = vec(spec["light"]["position"])
    t, aspect = cam["tan_half_fov"], cam["aspect"]

    def shadowed(point):
        to_light = light - point
        return tree.ray_cast(point, to_light.normalized(), to_light.length)[0] is not None

    offsets = [mathutils.Vector((0.002 * math.cos(k * math.pi / 4), 0.002 * math.sin(k * math.pi / 4), 0.0))
               for k in range(8)]
    masks = numpy.zeros((height, width, 3), dtype=numpy.float32)  # top row first
    haze = numpy.zeros((height, width, 3), dtype=numpy.float32)  # what the haze adds to the floor: h · horizon
    horizon = numpy.array(spec["sky"]["horizon"], dtype=numpy.float32)
    for y in range(height):
        for x in range(width):
            u, v = (x + 0.5) / width, (y + 0.5) / height
            direction = (forward + ((2 * u - 1) * t * aspect) * right + ((1 - 2 * v) * t) * up).normalized()
            hit = tree.ray_cast(eye, direction)
            t_floor = -eye.z / direction.z if direction.z < 0 else math.inf
            if hit[0] is not None and hit[3] < t_floor:
                masks[y, x, 0] = 1.0
                continue
            if t_floor == math.inf:
                continue
            point = eye + t_floor * direction
            point.z = 0.0
            haze[y, x] = (1.0 - math.exp(-t_floor / spec["sky"]["haze_distance"])) * horizon
            centre = shadowed(point)
            around = [shadowed(point + o) for o in offsets]
            if centre and all(around):
                masks[y, x, 1] = 1.0
            elif not centre and not any(around):
                masks[y, x, 2] = 1.0
    write_pfm(path, masks[::-1])
    write_pfm(path[:-4] + "_haze.pfm" if path.endswith(".pfm") else path + "_haze", haze[::-1])


def main():
    a = arguments()
    import json
    import os
    with open(a.scene) as f:
        spec = json.load(f)
    directory = os.path.dirname(os.path.abspath(a.scene))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    setup_render(scene, spec, a)
    setup_camera(scene, spec)
    setup_world(scene, spec)
    setup_light(scene, spec, a)
    setup_floor(scene, spec, directory, a)
    slimes = setup_slime(scene, spec, a.mesh, a)
    if a.masks:
        start = time.time()
        write_masks(a.masks, spec, slimes, scene)
        print(f"reference: wrote {a.masks} in {time.time() - start:.1f} s")
    scene.render.filepath = a.out + ".exr"
    start = time.time()
    bpy.ops.render.render(write_still=True)
    seconds = time.time() - start
    image = bpy.data.images.load(a.out + ".exr")
    width, height = image.size
    rgba = numpy.empty(width * height * 4, dtype=numpy.float32)
    image.pixels.foreach_get(rgba)
    write_pfm(a.out + ".pfm", rgba.reshape(height, width, 4)[:, :, :3])
    print(f"reference: {a.out}.exr and .pfm, {width}x{height}, {a.samples} samples, seed {a.seed}, "
          f"{seconds:.1f} s, Blender {bpy.app.version_string}")


main()
