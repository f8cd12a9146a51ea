# Import a .glb and an .obj of a plant with images of its own (docs/language.md §21) into
# Blender (headless) and print, per format, each image its materials load and its size:
# blender -b --factory-startup --python tests/blender/textures.py -- PLANT.glb PLANT.obj
# An OBJ's copies are NAME_tex_FILE.png: printed as FILE.png.
import os
import sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian 12's Blender 3.4 glTF importer predates numpy 1.24
import bpy


def seen(label):
    imgs = set()
    for m in bpy.data.materials:
        for n in (m.node_tree.nodes if m.use_nodes else []):
            if n.type == 'TEX_IMAGE' and n.image and n.image.size[0] > 0:
                name = os.path.basename(n.image.filepath) or n.image.name
                imgs.add("%s=%dx%d" % (name.split("_tex_", 1)[-1], n.image.size[0], n.image.size[1]))
    print(label, " ".join(sorted(imgs)))


for label, path in zip(("glb", "obj"), sys.argv[sys.argv.index("--") + 1:]):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    (bpy.ops.import_scene.gltf if label == "glb" else bpy.ops.import_scene.obj)(filepath=path)
    seen(label)
