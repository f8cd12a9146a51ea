# Import a quantized .glb with instanced leaves into Blender (headless) and print what it sees:
# blender -b --factory-startup --python tests/blender/quantized.py -- PLANT.glb NAME
#   quantized triangles=N protos=K    (the triangles of object NAME; mesh objects NAME_leaves*:
#   Blender 3.4 does not read EXT_mesh_gpu_instancing and shows each prototype once)
import sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24
import bpy

path, name = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
plant = [o for o in bpy.data.objects if o.type == 'MESH' and o.name == name]
tris = sum(len(p.vertices) - 2 for o in plant for p in o.data.polygons)
protos = sum(1 for o in bpy.data.objects if o.type == 'MESH' and o.name.startswith(name + "_leaves"))
print(f"quantized triangles={tris} protos={protos}")
