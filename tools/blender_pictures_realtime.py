"""docs/blender/levels.png and docs/blender/wind.png: a tree added by the add-on with LOD levels,
the impostor and wind, rendered by Blender's own Cycles (CPU): the levels NAME_LOD0 .. NAME_LODn
side by side (the last the impostor's card), and the swaying tree at three frames of its loop.
Run by tools/blender-pictures:
    blender -b --factory-startup --python tools/blender_pictures_realtime.py -- ZIP MODEL OUTDIR"""
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

zip_path, model, out = sys.argv[sys.argv.index("--") + 1:][:3]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="sylva_blender")
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
sc = bpy.context.scene


def bounds(objs):
    bpy.context.view_layer.update()
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    return (Vector([min(p[i] for p in pts) for i in range(3)]), Vector([max(p[i] for p in pts) for i in range(3)]))


def stage(lo, hi, width, height):
    """Camera framing lo..hi from the front, a sun, a sky and a ground."""
    sc.render.engine = "CYCLES"
    sc.cycles.samples, sc.cycles.device, sc.cycles.use_denoising = 16, "CPU", False
    sc.render.resolution_x, sc.render.resolution_y = width, height
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 1.08 * max(hi.x - lo.x, (hi.z - lo.z) * width / height)
    cam.location = ((lo.x + hi.x) / 2, lo.y - 10 * (hi.z - lo.z), (lo.z + hi.z) / 2)
    cam.rotation_euler = (math.radians(90), 0, 0)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sc.collection.objects.link(sun)
    sun.rotation_euler = (math.radians(40), math.radians(20), math.radians(30))
    sun.data.energy = 3
    sc.world = bpy.data.worlds.new("w")
    sc.world.use_nodes = True
    sc.world.node_tree.nodes["Background"].inputs[0].default_value = (0.75, 0.85, 1.0, 1)
    bpy.ops.mesh.primitive_plane_add(size=40 * (hi.z - lo.z), location=(0, 0, lo.z))


def render(path):
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)


# 1. the levels side by side: LOD0 .. LODn shown and moved apart, the card last
bpy.ops.mesh.sylva_tree_add(filepath=model, lod=3, impostor=True, impostor_view=128)
root = next(o for o in bpy.data.objects if o.type == "EMPTY")
levels = sorted((o for o in root.children if "sylva_lod" in o), key=lambda o: o["sylva_lod"])
for o in root.children:
    if o.type == "ARMATURE":
        o.hide_render = True
lo, hi = bounds(levels[:1])
gap = 1.1 * max(hi.x - lo.x, hi.y - lo.y)
for k, o in enumerate(levels):
    o.hide_set(False)
    o.hide_render = False
    o.location.x += k * gap
lo, hi = bounds(levels)
stage(lo, hi, 960, 320)
render(os.path.join(out, "levels.png"))

# 2. the wind: the tree (wind alone) at three frames of its loop, the renders side by side
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
bpy.ops.mesh.sylva_tree_add(filepath=model, wind=12.0, wind_seconds=2.0)
tree = [o for o in bpy.data.objects if o.type == "MESH" and o.parent]
lo, hi = bounds(tree)
pad = 0.25 * (hi.z - lo.z)
stage(lo - Vector((pad, 0, 0)), hi + Vector((pad, 0, 0)), 320, 320)
pictures = []
for f in (0, 12, 30):
    sc.frame_set(f)
    render(os.path.join(out, f"_wind{f}.png"))
    img = bpy.data.images.load(os.path.join(out, f"_wind{f}.png"))
    px = np.empty(img.size[0] * img.size[1] * 4, np.float32)
    img.pixels.foreach_get(px)
    pictures.append(px.reshape(img.size[1], img.size[0], 4))
    os.remove(os.path.join(out, f"_wind{f}.png"))
row = np.concatenate(pictures, axis=1)
img = bpy.data.images.new("wind", row.shape[1], row.shape[0], alpha=True)
img.pixels.foreach_set(row.ravel())
img.filepath_raw = os.path.join(out, "wind.png")
img.file_format = "PNG"
img.save()
