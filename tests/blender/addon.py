"""The add-on as an artist uses it, in headless Blender: install the zip, enable it, add trees
through the operator (Add → Mesh → Sylva Tree), and print what the scene holds, one line per
case, for tests/run-blender to compare with the command's figures.
    blender -b --factory-startup --python addon.py -- ZIP MODEL..."""
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
zip_path, models = args[0], args[1:]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="sylva_blender")
print("addon", "enabled" if "sylva_blender" in bpy.context.preferences.addons else "missing",
      "menu" if hasattr(bpy.types, "SYLVA_PT_panel") else "nopanel")

for path in models:
    for output in ("MESH", "CURVES"):
        before = set(bpy.data.objects)
        r = bpy.ops.mesh.sylva_tree_add(filepath=path, output=output)
        new = [o for o in bpy.data.objects if o not in before]
        root = next((o for o in new if o.type == "EMPTY"), None)
        kids = [o for o in new if o.parent is root] if root else []
        obj = kids[0] if kids else None
        if output == "MESH" and obj is not None:
            me = obj.data
            tris = sum(len(p.vertices) - 2 for p in me.polygons)
            print(f"mesh {path} result={r.pop()} root={root.name} vertices={len(me.vertices)} triangles={tris} "
                  f"materials={len(me.materials)}")
        elif obj is not None:
            radii = [p.radius for s in obj.data.splines for p in s.bezier_points]
            print(f"curves {path} result={r.pop()} splines={len(obj.data.splines)} "
                  f"min_radius={min(radii):.6f}")
        else:
            print(f"{output.lower()} {path} result={r} nothing added")

# a wrong parameter is reported, nothing is added, and Blender goes on
before = len(bpy.data.objects)
try:
    r = bpy.ops.mesh.sylva_tree_add(filepath=models[0], overrides="anglee=3")
except RuntimeError as e:  # operators report errors as RuntimeError in background mode
    r = {"CANCELLED"} if "anglee" in str(e) else {str(e)}
print(f"refused result={r.pop()} added={len(bpy.data.objects) - before}")
