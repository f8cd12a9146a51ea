"""The add-on's levels of detail, impostor card and wind armature, in the Blender process of
addon_more.py (one Blender for the add-on's checks): runpy'd at its end with `added` and the
work folder, it prints one line per case for tests/run-blender to compare with `sylva mesh`.
WORK/rt_wind.glb is `sylva mesh MODEL --wind 6 --wind-seconds 2`, made by tests/run-blender:
Blender's own glTF importer reads it, and at one frame its skinned mesh must be where the
add-on's armature puts the add-on's mesh."""
import os

import bpy
import numpy

added, work, model = globals()["added"], globals()["out_dir"], globals()["rt_model"]
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24


def tris(obj):
    return sum(len(p.vertices) - 2 for p in obj.data.polygons)


def positions(obj, deformed=True):
    """obj's vertices (n, 3) as the depsgraph evaluates them at the scene's frame, or at rest."""
    me = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh() if deformed else obj.data
    co = numpy.empty(3 * len(me.vertices))
    me.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


# 1. Levels, impostor and wind together: NAME_LOD0..3 in NAME_LODs, the last the billboards'
# card with the baked atlas; an armature of a bone per wind joint, its action the loop's frames
bpy.ops.object.select_all(action="DESELECT")
r, lod0 = added(filepath=model, lod=3, impostor=True, impostor_view=64, wind=6.0, wind_seconds=2.0)
root = lod0.parent if lod0 else None
name = root.name if root else "?"
coll = bpy.data.collections.get(f"{name}_LODs")
levels = sorted(coll.objects, key=lambda o: o.name) if coll else []
arm = next((o for o in root.children if o.type == "ARMATURE"), None) if root else None
action = arm.animation_data.action if arm and arm.animation_data else None
f0, f1 = action.frame_range if action else (-1, -1)
print(f"rt_lod result={r} objects={','.join(o.name.replace(name, 'NAME') for o in levels)} "
      f"triangles={','.join(str(tris(o)) for o in levels)}")
skinned = [o.name.replace(name, "NAME") for o in levels
           if any(m.type == "ARMATURE" and m.object is arm for m in o.modifiers)]
print(f"rt_wind bones={len(arm.data.bones) if arm else 0} frames={f0:g}..{f1:g} "
      f"curves={len(action.fcurves) if action else 0} skinned={','.join(skinned)}")
card = levels[-1] if levels else None
img = None
if card and card.active_material and card.active_material.use_nodes:
    img = next((n.image for n in card.active_material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image), None)
alpha = numpy.empty(img.size[0] * img.size[1] * 4, numpy.float32) if img else numpy.zeros(4, numpy.float32)
if img:
    img.pixels.foreach_get(alpha)
print(f"rt_card texture={'x'.join(map(str, img.size)) if img else 'none'} packed={bool(img and img.packed_file)} "
      f"covered={'yes' if 0 < (alpha[3::4] > 0.5).mean() < 1 else 'no'} clip={card.active_material.blend_method if card else '-'}")

# 2. The sway itself: the add-on's mesh (wind alone) against Blender's import of the command's
# .glb (the same vertices in the same order): at frames 5 and 17 of the loop, between Sylva's
# keys, every vertex where the importer's skinning puts it, and the tips moved
bpy.ops.object.select_all(action="DESELECT")
r, mine = added(filepath=model, wind=6.0, wind_seconds=2.0)
before = set(bpy.data.objects)
bpy.ops.import_scene.gltf(filepath=os.path.join(work, "rt_wind.glb"))
theirs = next(o for o in bpy.data.objects if o not in before and o.type == "MESH")
rest, trest = positions(mine, False), positions(theirs, False)
same_rest = rest.shape == trest.shape and bool(numpy.all(rest == trest))
size = float(numpy.ptp(rest, axis=0).max())
dev = moved = 0.0
for f in (5, 17):
    bpy.context.scene.frame_set(f)
    a = positions(mine)
    dev = max(dev, float(numpy.linalg.norm(a - positions(theirs), axis=1).max()) / size if same_rest else 1.0)
    moved = max(moved, float(numpy.linalg.norm(a - rest, axis=1).max()) / size)
bpy.context.scene.frame_set(0)
print(f"rt_sway result={r} vertices={len(rest)} same_rest={'yes' if same_rest else 'no'} "
      f"as_imported={'yes' if dev < 1e-5 else 'no (%.3g)' % dev} moved={'yes' if moved > 1e-3 else 'no'}")
