# Import a .glb and an .obj of the same plant into Blender (headless) and print what it sees:
# blender -b --factory-startup --python tests/blender/check.py -- PLANT.glb PLANT.obj
import sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24
import bpy

def seen(label):
    meshes = [o for o in bpy.context.scene.objects if o.type == 'MESH']
    tris = sum(sum(len(p.vertices) - 2 for p in o.data.polygons) for o in meshes)
    mats = sorted({m.name for o in meshes for m in o.data.materials if m})
    imgs = sum(1 for m in bpy.data.materials if m.use_nodes
               for n in m.node_tree.nodes if n.type == 'TEX_IMAGE' and n.image and n.image.size[0] > 0)
    print(f"{label} triangles={tris} materials={','.join(mats)} textures={imgs}")

glb, obj = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
seen("glb")
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.obj(filepath=obj)
seen("obj")
