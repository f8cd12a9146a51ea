"""The add-on's schema-driven parameters, species library and scene inputs, in headless
Blender: install the zip, add trees through the operator, and print one line per case for
tests/run-blender to compare with the command's figures.
    blender -b --factory-startup --python addon_more.py -- ZIP BUSH.syl"""
import os
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

# 3. the scene drives the model: a Bézier curve (moved and turned: world coordinates count) is
# the trunk of the curve-driven oak, a scaled ico sphere its envelope. Every trunk point of the
# curve output lies on the curve (within 1 % of its length), every branch point in the sphere.
from mathutils import Matrix, Vector  # noqa: E402
from mathutils.geometry import intersect_point_line  # noqa: E402

from sylva_blender import scene  # noqa: E402

bpy.ops.object.select_all(action="DESELECT")
cu = bpy.data.curves.new("Trunk", "CURVE")
cu.dimensions = "3D"
sp = cu.splines.new("BEZIER")
sp.bezier_points.add(3)
for bp, co in zip(sp.bezier_points, [(0, 0, 0), (0.6, 0, 3), (0, 0.5, 6), (0.4, 0.3, 9)]):
    bp.co = co
    bp.handle_left_type = bp.handle_right_type = "AUTO"
trunk = bpy.data.objects.new("Trunk", cu)
trunk.matrix_world = Matrix.Translation((2, 1, 0)) @ Matrix.Rotation(0.5, 4, "Z")
bpy.context.collection.objects.link(trunk)
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=1, location=(2.2, 1.2, 6.5))
sphere = bpy.context.active_object
sphere.scale = (3.5, 3.5, 3.5)  # the object's transform, not its mesh
sphere.select_set(True)
trunk.select_set(True)
bpy.context.view_layer.objects.active = trunk
bpy.context.view_layer.update()
r, obj = added(species="curvetree/bezier_oak", output="CURVES", use_scene=True)
if obj is None:
    print(f"curvetree result={r} nothing")
else:
    poly = scene.curve_points(trunk)
    length = sum((b - a).length for a, b in zip(poly, poly[1:]))

    def off_curve(p):
        best = 1e30
        for a, b in zip(poly, poly[1:]):
            q, t = intersect_point_line(p, a, b)
            q = a if t < 0 else b if t > 1 else q
            best = min(best, (p - q).length)
        return best

    mw = obj.matrix_world
    splines = [[mw @ bp.co for bp in s.bezier_points] for s in obj.data.splines]
    worst_trunk = max(off_curve(p) for p in splines[0]) / length
    centre, radius = sphere.matrix_world.translation, 3.5
    outside = sum((p - centre).length > radius * (1 + 1e-4) for s in splines[1:] for p in s)
    print(f"curvetree result={r} splines={len(splines)} trunk_points={len(splines[0])} "
          f"trunk_on_curve={'yes' if worst_trunk <= 0.01 else 'no:%.4f' % worst_trunk} "
          f"branch_points={sum(len(s) for s in splines[1:])} outside={outside}")
print(f"inputs_left={'yes' if os.path.exists(os.path.join(os.path.dirname(library.path('curvetree/bezier_oak')), '.sylva-blender')) else 'no'}")

# A grow block with a selected cube (moved: world coordinates count) as an obstacle: no node of
# the grown shrub lies in the cube, where without the cube some do; the cube's triangles are
# not in the tree's mesh.
bpy.ops.object.select_all(action="DESELECT")
bpy.ops.mesh.primitive_cube_add(size=1, location=(0.9, 0.0, 1.0))
cube = bpy.context.active_object
cube.scale = (0.6, 1.2, 1.2)
bpy.context.view_layer.update()  # matrix_world from location and scale
inv = cube.matrix_world.inverted()


def in_cube(p):
    q = inv @ p
    return max(abs(q.x), abs(q.y), abs(q.z)) < 0.5


found = {}
for use in (False, True):
    cube.select_set(True)
    r, obj = added(species="sot/shrub", output="CURVES", use_scene=use)
    if obj is None:
        found[use] = f"result={r}"
        continue
    mw = obj.matrix_world
    found[use] = sum(in_cube(mw @ bp.co) for s in obj.data.splines for bp in s.bezier_points)
r, obj = added(species="sot/shrub", use_scene=True)
cube_in_mesh = obj is not None and any(m.name.endswith(f" {sylva_blender.OBSTACLE_MATERIAL}") for m in obj.data.materials)
print(f"obstacle result={r} nodes_in_cube_without={found[False]} with={found[True]} "
      f"cube_in_mesh={'yes' if cube_in_mesh else 'no'}")

# An ecosystem block with a selected mesh as its terrain (a tilted, moved plane): its last
# snapshot becomes one collection instance per plant, of a collection per species and age
# class. The script also writes the same terrain and block beside each other in OUT, for
# `sylva ecosystem` to count the snapshot's plants.
out_dir = args[2]
bpy.ops.object.select_all(action="DESELECT")
bpy.ops.mesh.primitive_grid_add(x_subdivisions=12, y_subdivisions=12, size=1, location=(3, -2, 1))
plane = bpy.context.active_object
plane.scale = (9, 7, 1)
plane.rotation_euler = (0.15, 0.05, 0.3)
bpy.context.view_layer.update()
r, _ = added(species="ecosystem/meadow", steps=3, use_scene=True)
root = next((o for o in bpy.data.objects if o.type == "EMPTY" and o.get("sylva_plants") is not None), None)
if root is None:
    print(f"ecosystem result={r} nothing")
else:
    inst = [o for o in root.children if o.instance_type == "COLLECTION" and o.instance_collection]
    colls = {o.instance_collection.name for o in inst}
    print(f"ecosystem result={r} instances={len(inst)} collections={len(colls)}")
    scene.write_obj(plane, os.path.join(out_dir, "terrain.obj"))
    src = open(library.path("ecosystem/meadow"), encoding="utf-8").read()
    with open(os.path.join(out_dir, "meadow.syl"), "w", encoding="utf-8") as f:
        f.write(src.replace('terrain "meadow.asc"', 'terrain "terrain.obj"'))

# 4. Leaves as instances: the oak's leaves are one leaf object instanced on an emitter's faces;
# Blender's evaluated instances are as many as `sylva mesh --leaves instanced` counts, each at
# its leaf's position with its +x along the leaf's heading; the branches are the mesh the .glb has.
bpy.ops.object.select_all(action="DESELECT")
r, _ = added(species="curvetree/bezier_oak", leaves="instanced")
root = next((o for o in bpy.data.objects if o.type == "EMPTY" and o.get("sylva_leaf_instances") is not None), None)
obj = next((o for o in root.children if o.type == "MESH" and o.instance_type != "FACES"), None) if root else None
dg = bpy.context.evaluated_depsgraph_get()
inst = [i.matrix_world.copy() for i in dg.object_instances
        if i.is_instance and i.parent and i.parent.original.parent == root]
plant = sylva_blender.load_model(library.path("curvetree/bezier_oak")).build(leaves="instanced", until="skeleton")
org = plant.skeleton.organs
from mathutils.kdtree import KDTree  # noqa: E402

tree = KDTree(len(org))
heads = []
for i, (p, h) in enumerate(zip(org["pos"], org["h"])):
    tree.insert((float(p[0]), float(-p[2]), float(p[1])), i)
    heads.append(Vector((float(h[0]), float(-h[2]), float(h[1]))).normalized())
tree.balance()
at = along = 0
for mw in inst:  # the nearest leaf within a micrometre, and the instance's +x along its heading
    _, i, d = tree.find(mw.translation)
    at += d < 1e-6
    along += d < 1e-6 and mw.col[0].xyz.normalized().dot(heads[i]) > 0.999
print(f"leaves result={r} instances={len(inst)} at_leaf={at} along_heading={along} "
      f"stored={root.get('sylva_leaf_instances') if root else None} {counts(obj)}")
# the leaf object is the leaf the mesher makes (the model's outline), not a stand-in: its
# triangles on every face are the leaf triangles of the copied mesh (`--leaves mesh` less
# `--leaves instanced`), and it is flat, from its base along +x
emitters = [o for o in root.children if o.instance_type == "FACES"] if root else []
protos = [c for e in emitters for c in e.children if c.type == "MESH"]
leaf_tris = sum(len(e.data.polygons) * sum(len(p.vertices) - 2 for p in c.data.polygons)
                for e in emitters for c in e.children if c.type == "MESH")
flat = all(max(abs(v.co.z) for v in c.data.vertices) == 0 and min(v.co.x for v in c.data.vertices) >= 0
           for c in protos)
print(f"leafshape protos={len(protos)} leaf_triangles={leaf_tris} flat={'yes' if protos and flat else 'no'}")

# 5. Sapling's presets from the running Blender's own add-on are species too: the aspen by name
# gives the mesh `sylva mesh PRESET.py` gives.
r, obj = added(species="sapling/quaking_aspen")
print(f"sapling result={r} {counts(obj)} presets={sum(n.startswith('sapling/') for n in items)}")

# 6. Levels of detail, the impostor card and the wind armature (addon_realtime.py), in this Blender
import runpy  # noqa: E402

rt_model = args[3] if len(args) > 3 else None
if rt_model:
    runpy.run_path(os.path.join(os.path.dirname(os.path.abspath(__file__)), "addon_realtime.py"),
                   init_globals={"added": added, "out_dir": out_dir, "rt_model": rt_model})

# 6b. Instanced leaves on every level, following the wind's bones (addon_leaves.py)
leaves_model = args[4] if len(args) > 4 else None
if leaves_model:
    runpy.run_path(os.path.join(os.path.dirname(os.path.abspath(__file__)), "addon_leaves.py"),
                   init_globals={"added": added, "leaves_model": leaves_model})

# 7. Sapling's own trees in this Blender: the splines of its curve object per level (the
# splines there when Sapling starts each level: its fabricate_stems, watched, not changed),
# averaged over seeds 0-3, for tests/run-blender to compare with `sylva compare`'s stems by
# order of the same files (within 15 %). The trunk's splines (level 0) are averaged over
# TRUNK_SEEDS trees of the trunk alone (levels=1, a few ms each): Sapling grows the trunk first,
# so its draws, and its splines, are those of the whole tree's trunk (checked: seeds 0-3 give the
# whole trees' level 0, printed as same=), and the splits' mean is known closely enough to test
# where four trees are too few (small_maple). japanese_maple (4.5 s a whole tree): two trees,
# seeds 0-1, give its levels above the trunk as stems per stem of the level below (those
# follow the trunk's splines closely: over seeds 0-11, 4.5-5.8, 5.5-6.3 and 6.4-6.7 a tree,
# where the trunk's splines are 31-65), times the 48 trunks' mean. Stems only (the leaves are a mesh of their own) and no
# bevel at resolution 1: those set only the curve's look (cu.bevel_depth, cu.resolution_u), not
# a draw, and evaluating the tubes was a tenth of the time.
import ast  # noqa: E402

import addon_utils  # noqa: E402

addon_utils.enable("add_curve_sapling", default_set=True)
sap = library.sapling_presets()
sap_utils = sys.modules["add_curve_sapling.utils"]
marks = []
fabricate = sap_utils.fabricate_stems
TRUNK_SEEDS = 48


def watched(*a, **k):
    marks.append(len(a[5].splines))  # a[5]: the tree's curve, before the level's stems
    return fabricate(*a, **k)


def sapling_tree(kw) -> list[int]:
    """Sapling's splines per level of one tree (kw: the operator's arguments)."""
    before = set(bpy.data.objects)
    marks.clear()
    bpy.ops.curve.tree_add(**kw)
    new = [o for o in bpy.data.objects if o not in before]
    bounds = marks + [sum(len(o.data.splines) for o in new if o.type == "CURVE")]
    for o in new:
        bpy.data.objects.remove(o)
    return [bounds[0]] + [bounds[i] - bounds[i - 1] for i in range(1, len(bounds))]


sap_utils.fabricate_stems = watched
props = {p.identifier: p for p in bpy.ops.curve.tree_add.get_rna_type().properties}
for name in ("callistemon", "douglas_fir", "quaking_aspen", "small_maple", "small_pine", "weeping_willow",
             "white_birch", "willow", "japanese_maple"):
    with open(os.path.join(sap, name + ".py")) as fh:
        preset = ast.literal_eval(fh.read().split("\n", 1)[1])  # after the licence line
    kw = {}
    for k, v in preset.items():  # older presets give one number for a per-level property
        if k in props:
            n = getattr(props[k], "array_length", 0)
            kw[k] = tuple([v] * n) if n and not isinstance(v, (tuple, list)) else v
    kw.update(showLeaves=False, do_update=True, bevel=False, resU=1)
    trunks = [sapling_tree({**kw, "seed": seed, "levels": 1})[0] for seed in range(TRUNK_SEEDS)]
    sums, same = [], True
    trees = 2 if name == "japanese_maple" else 4
    for seed in range(trees):
        levels = sapling_tree({**kw, "seed": seed})
        same = same and levels[0] == trunks[seed]
        sums = [a + b for a, b in zip(sums, levels)] if sums else levels
    means = [sum(trunks) / TRUNK_SEEDS]
    for k in range(1, len(sums)):  # four trees: their mean; two: per stem of the level below
        means.append(sums[k] / 4 if trees == 4 else means[-1] * sums[k] / sums[k - 1])
    print(f"sapling_levels {name} same={'yes' if same else 'no'} " + " ".join("%g" % x for x in means))
