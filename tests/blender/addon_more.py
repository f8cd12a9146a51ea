"""The add-on's schema-driven parameters, species library and scene inputs, in headless
Blender: install the zip, add trees through the operator, and print one line per case for
tests/run-blender to compare with the command's figures.
    blender -b --factory-startup --python addon_more.py -- ZIP BUSH.syl"""
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
zip_path, bush = args[0], args[1]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="sylva_blender")
import sylva_blender  # noqa: E402
from sylva_blender import library  # noqa: E402


def added(**kw):
    """Run the operator; (result, the mesh or curve object under the new empty)."""
    before = set(bpy.data.objects)
    try:
        r = bpy.ops.mesh.sylva_tree_add(**kw).pop()
    except RuntimeError as e:
        return f"error:{e}".replace(" ", "_"), None
    new = [o for o in bpy.data.objects if o not in before]
    root = next((o for o in new if o.type == "EMPTY"), None)
    kids = [o for o in new if o.parent is root and o.type in ("MESH", "CURVE")]
    return r, (kids[0] if kids else None)


def row(name, value):
    """A parameter as bpy.ops takes a collection item: every field given; fill() keeps the value."""
    return {"name": name, "value": value, "ivalue": int(value), "integer": False, "min": 0.0, "max": 0.0,
            "model_value": 0.0, "default": "", "unit": "", "doc": ""}


def counts(obj) -> str:
    if obj is None:
        return "nothing"
    me = obj.data
    return f"vertices={len(me.vertices)} triangles={sum(len(p.vertices) - 2 for p in me.polygons)}"


# 1. the directive schema: a parameter set by name reaches the build as `--set` does, and a
# value beyond the schema's range is held at its end
r, obj = added(filepath=bush, params=[row("angle", 30.0)])
print(f"param angle=30 result={r} {counts(obj)}")
oak = library.path("curvetree/bezier_oak")
r, obj = added(filepath=oak, params=[row("branch2Density", -3.0)])
print(f"clamp branch2Density=-3 result={r} {counts(obj)}")
# the collection the redo panel draws, filled from the schema: a row per number parameter,
# each with the schema's range, the model's value and a tooltip
from sylva_blender import params as schema  # noqa: E402


class Rows(bpy.types.PropertyGroup):
    rows: bpy.props.CollectionProperty(type=schema.SylvaParam)


bpy.utils.register_class(Rows)
bpy.types.Scene.sylva_test = bpy.props.PointerProperty(type=Rows)
rows = bpy.context.scene.sylva_test.rows
schema.fill(rows, sylva_blender.load_model(oak), keep=False)
it = rows["branch2Density"]
print(f"rows {len(rows)} branch2Density={it.value:g} min={it.min:g} max={it.max:g} "
      f"tooltip={'yes' if schema.tooltip(it).startswith('branch2Density: second-level') else 'no'} "
      f"trunkRes={'integer' if rows['trunkRes'].integer else 'number'} overrides={schema.overrides(rows)}")

# 2. the library: a species by name, with its gallery picture as the enum's icon
r, obj = added(species="curvetree/bezier_oak")
items = {i[0]: i for i in library.enum_items(None, bpy.context)}
pic = library.picture("curvetree/bezier_oak")
pv = library._previews.get("curvetree/bezier_oak") if library._previews else None
print(f"species curvetree/bezier_oak result={r} {counts(obj)} picture={'yes' if pic and pv else 'no'} "
      f"species={len(items) - 1}")
