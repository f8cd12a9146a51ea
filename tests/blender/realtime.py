# Import real-time .glb files into Blender (headless) and print what it sees, one line each:
# blender -b --factory-startup --python tests/blender/realtime.py -- LOD.glb WIND.glb
#   lod objects=NAME_LOD0,.. clip=N          (mesh objects; leaf materials alpha-clipped)
#   wind bones=N quaternion_curves=N frames=F0..F1
import sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24
import bpy

lod, wind = sys.argv[sys.argv.index("--") + 1:][:2]

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
