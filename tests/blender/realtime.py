# Import real-time .glb files into Blender (headless) and print what it sees, one line each:
# blender -b --factory-startup --python tests/blender/realtime.py -- LOD.glb WIND.glb [WINDLOD.glb]
#   lod objects=NAME_LOD0,.. clip=N          (mesh objects; leaf materials alpha-clipped)
#   wind bones=N quaternion_curves=N frames=F0..F1
#   windlod armatures=A bones=N skinned=NAME_LOD0,.. still=NAME_LODk,.. anchors=E anchor_curves=C
#     (LOD meshes with and without an armature modifier; animated empties that carry
#     instanced leaves, and their rotation curves)
import sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24
import bpy

lod, wind = sys.argv[sys.argv.index("--") + 1:][:2]
windlod = sys.argv[sys.argv.index("--") + 1:][2:3]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=lod)
names = sorted(o.name for o in bpy.data.objects if "_LOD" in o.name)
clip = sum(1 for m in bpy.data.materials if m.name.startswith("leaf") and m.blend_method == 'CLIP')
print(f"lod objects={','.join(names)} clip={clip}")

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=wind)
bones = sum(len(o.data.bones) for o in bpy.data.objects if o.type == 'ARMATURE')
curves = sum(1 for a in bpy.data.actions for c in a.fcurves if c.data_path.endswith("rotation_quaternion"))
ranges = [a.frame_range for a in bpy.data.actions]
f0 = min((r[0] for r in ranges), default=0)
f1 = max((r[1] for r in ranges), default=0)
print(f"wind bones={bones} quaternion_curves={curves} frames={f0:g}..{f1:g}")

if windlod:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=windlod[0])
    arms = [o for o in bpy.data.objects if o.type == 'ARMATURE']
    meshes = [o for o in bpy.data.objects if o.type == 'MESH' and "_LOD" in o.name and "_stem" not in o.name]
    level = lambda o: o.name.split(".")[0]  # Blender renames a skinned node's mesh NAME.001
    skinned = sorted(level(o) for o in meshes if any(m.type == 'ARMATURE' and m.object in arms for m in o.modifiers))
    still = sorted(level(o) for o in meshes if not any(m.type == 'ARMATURE' for m in o.modifiers))
    anchors = [o for o in bpy.data.objects if o.type == 'EMPTY' and "_stem" in o.name and o.animation_data
               and o.animation_data.action]
    curves = sum(1 for o in anchors for c in o.animation_data.action.fcurves if c.data_path.startswith("rotation"))
    print(f"windlod armatures={len(arms)} bones={sum(len(a.data.bones) for a in arms)} skinned={','.join(skinned)} "
          f"still={','.join(still)} anchors={len(anchors)} anchor_curves={curves}")
