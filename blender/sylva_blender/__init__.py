"""Sylva in Blender: grow any Sylva model (.syl, Arbaro .xml, Pafčo .cfg, a library species) into the scene, as a mesh with
bark and leaf materials or as Bézier curves you can still reshape (docs/blender.md).

Add → Mesh → Sylva Tree adds one with a redo panel; the sidebar's Sylva tab picks the file,
the model and its parameters. The add-on ships the `sylva` Python package (built for
Blender's Python) beside this file."""
from __future__ import annotations

import os
import sys

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

bl_info = {
    "name": "Sylva",
    "author": "Sylva developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Add > Mesh > Sylva Tree; View3D > Sidebar > Sylva",
    "description": "Plants from grammar files: L-systems, grown trees, Weber-Penn and strand trees",
    "category": "Add Mesh",
}

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:  # the bundled `sylva` package
    sys.path.insert(0, _HERE)

import sylva  # noqa: E402

from . import forest, leaves as leaf_instances, library, params as schema, realtime, scene  # noqa: E402

LEAVES = [("copied", "Copied", "every leaf its own geometry"),
          ("cards", "Cards", "one alpha-tested card a leaf"),
          ("instanced", "Instanced", "one leaf object instanced on the faces of an emitter, a face per leaf")]
# the operator's and panel's options of `sylva mesh --lod --impostor --wind` (realtime.py)
REALTIME = ("lod", "impostor", "impostor_view", "wind", "wind_seconds")
OUTPUTS = [("MESH", "Mesh", "branches as tubes, leaves as faces"),
           ("CURVES", "Curves", "a Bézier curve a stem, with the radius per point (editable)")]


def _overrides(text: str) -> dict:
    """`angle=30 width=0.2` → {"angle": 30.0, "width": 0.2}: the --set values of the redo panel."""
    out = {}
    for item in text.replace(",", " ").split():
        name, _, value = item.partition("=")
        if not value:
            raise ValueError(f"{item!r}: a parameter is NAME=VALUE")
        out[name.strip()] = float(value)
    return out


def _material(name: str, rgb, leaf: bool) -> bpy.types.Material:
    mat = bpy.data.materials.get(name)
    if mat is not None and mat.use_nodes and all(abs(a - b) < 1e-6 for a, b in zip(mat.diffuse_color, (*rgb, 1.0))):
        return mat  # made by an earlier tree of this model: reused as it is (the user's edits too)
    mat = mat or bpy.data.materials.new(name)
    mat.diffuse_color = (*rgb, 1.0)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    if bsdf:
        bsdf.inputs["Base Color"].default_value = (*rgb, 1.0)
        bsdf.inputs["Roughness"].default_value = 0.6 if leaf else 0.85
    if leaf:
        mat.blend_method = "CLIP"
        mat.use_backface_culling = False
    return mat


# a scene's obstacles come appended to its plants' mesh in a group of this material (scene.c's
# OBSTACLE_MATERIAL): the add-on leaves them out, the scene has them already
OBSTACLE_MATERIAL = 250


def _edges(me, tris, nv: int) -> None:
    """The triangles' edges, each once, and every loop's edge, found by the package's C helper
    (one hash of the sides): Mesh.update() finds them itself when a mesh has none, which took
    half the add-on's time on a large tree, and a numpy sort a third (docs/blender.md, "Speed
    beside Sapling")."""
    import numpy as np
    from sylva import _core
    edges, loop_edge = (np.asarray(a).view(np.uint32) for a in _core.mesh_edges(tris, nv))
    me.edges.add(len(edges))
    me.edges.foreach_set("vertices", edges.ravel())
    me.loops.foreach_set("edge_index", loop_edge)


# Blender 3.4's foreach_set copies an array of uint32 ('I') straight into a mesh's int
# properties and goes item by item for int32 and others, 15-25 times slower (a 900,000-loop
# mesh: 2 ms against 30 ms a property): every index array is given as uint32.
U32 = "uint32"


def mesh_object(plant, name: str, drop_obstacles: bool = False, z_up: bool = True) -> bpy.types.Object:
    """The plant's mesh (or a sylva.Mesh: a level's, a leaf prototype's) as one object, filled
    from Sylva's arrays with foreach_set (no Python loop per vertex): Sylva's y-up metres turned
    to Blender's z-up (z_up False: as they are, for a prototype in its own frame), one material
    per group."""
    import numpy as np
    m = plant if isinstance(plant, sylva.Mesh) else plant.mesh
    v = m.vertices
    tris = m.triangles
    groups = m.groups
    uvs_all = m.uvs
    if drop_obstacles and any(g["material"] == OBSTACLE_MATERIAL for g in groups):
        groups = [dict(g) for g in groups if g["material"] != OBSTACLE_MATERIAL]
        keep = np.concatenate([np.arange(g["first"], g["first"] + g["count"]) for g in groups])
        used, tris = np.unique(tris[keep], return_inverse=True)
        tris = tris.reshape(-1, 3)
        v, uvs_all = v[used], uvs_all[used]
        at = 0
        for g in groups:  # the kept groups, renumbered from 0
            g["first"], at = at, at + g["count"]
    tris = np.ascontiguousarray(tris, dtype=U32)
    co = np.empty_like(v)
    co[:, 0], co[:, 1], co[:, 2] = (v[:, 0], -v[:, 2], v[:, 1]) if z_up else (v[:, 0], v[:, 1], v[:, 2])
    nt = len(tris)
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(v))
    me.vertices.foreach_set("co", co.ravel())
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", tris.ravel())
    _edges(me, tris, len(v))
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", np.arange(0, 3 * nt, 3, dtype=U32))
    me.polygons.foreach_set("loop_total", np.full(nt, 3, dtype=U32))
    kinds = {0: "Bark", 1: "Leaf", 2: "Flower", 3: "Plain"}
    index = np.zeros(nt, dtype=U32)
    for k, g in enumerate(groups):
        leaf = g["kind"] in (1, 2)
        me.materials.append(_material(f"{name} {kinds.get(g['kind'], 'Plain')} {g['material']}", g["rgb"], leaf))
        index[g["first"]:g["first"] + g["count"]] = k
    if len(groups) > 1:  # one group: every face's index is 0 already (setting it cost 0.6 ms a willow)
        me.polygons.foreach_set("material_index", index)
    uv = me.uv_layers.new(name="UVMap")
    uvs = np.take(uvs_all.astype(np.float32, copy=False), tris.ravel(), axis=0)
    uvs[:, 1] = 1.0 - uvs[:, 1]  # glTF's v runs down a texture, Blender's up
    uv.data.foreach_set("uv", uvs.ravel())
    me.update()
    return bpy.data.objects.new(name, me)


def curve_object(plant, name: str) -> bpy.types.Object:
    """The skeleton as Bézier curves, one spline per stem (axis), with the radius per point:
    the Blender plug-in's (and Sapling's) editable output."""
    sk = plant.skeleton
    nodes = sk.nodes
    cu = bpy.data.curves.new(name, "CURVE")
    cu.dimensions = "3D"
    cu.bevel_depth = 1.0  # radius × 1: the tube's width is the point's radius
    cu.bevel_resolution = 2
    cu.use_fill_caps = True
    by_axis: dict[int, list[int]] = {}
    for i, n in enumerate(nodes):
        if n["kind"] in (0, 1):  # roots and segment ends draw the stems; organs do not
            by_axis.setdefault(int(n["axis"]), []).append(i)
    for axis, ids in by_axis.items():
        start = int(nodes[ids[0]]["parent"])
        chain = ([start] if start >= 0 else []) + ids
        if len(chain) < 2:
            continue
        sp = cu.splines.new("BEZIER")
        sp.bezier_points.add(len(chain) - 1)
        for bp, i in zip(sp.bezier_points, chain):
            x, y, z = (float(c) for c in nodes[i]["pos"])
            bp.co = (x, -z, y)
            bp.handle_left_type = bp.handle_right_type = "AUTO"
            bp.radius = float(nodes[ids[0] if i == start else i]["radius"])
    cu.materials.append(_material(f"{name} Bark", (0.35, 0.25, 0.18), False))
    return bpy.data.objects.new(name, cu)


# The models already loaded, by file (path, size, and the newest modification time of its
# folder's files, which it may read) and model name: a redo or a second tree of the same file
# neither compiles it again nor asks its schema again (both were a third of the add-on's time
# on Sapling's smallest presets, docs/blender.md). A model is not changed by building it
# (--set values compile a program of their own).
_loaded: dict = {}


def _stamp(path: str) -> tuple[int, int]:
    newest = os.stat(path).st_mtime_ns
    with os.scandir(os.path.dirname(path) or ".") as it:
        for e in it:
            if e.is_file():
                newest = max(newest, e.stat().st_mtime_ns)
    return os.path.getsize(path), newest


def load_model(path: str, model: str = ""):
    path = bpy.path.abspath(path)
    key = (path, *_stamp(path), model)
    m = _loaded.get(key)
    if m is None:
        f = sylva.load(path)
        m = f[model] if model else f.model
        if len(_loaded) >= 32:  # a session's files; the oldest goes
            del _loaded[next(iter(_loaded))]
        _loaded[key] = m
    return m


def add_tree(context, path: str, model: str = "", seed: int = -1, steps: int = -1, output: str = "MESH",
             leaves: str = "copied", overrides: dict | None = None, location=(0.0, 0.0, 0.0), m=None,
             scene_block: bool = False, lod: int = 0, impostor: bool = False, impostor_view: int = 0,
             wind: float = 0.0, wind_seconds: float = 0.0):
    """Build the model and put it in the scene under an empty named after it; returns the empty.
    m: the model already loaded from path (or compiled from the scene's inputs). lod, impostor
    and wind: as `sylva mesh --lod --impostor --wind` (realtime.py)."""
    m = m or load_model(path, model)
    kw = dict(overrides or {})
    if seed >= 0:
        kw["seed"] = seed
    rt = {k: v for k, v in (("lod", lod), ("impostor", impostor), ("wind", wind)) if v}
    if rt and output == "CURVES":
        raise ValueError("levels of detail, the impostor and wind are made of the mesh: choose Output: Mesh")
    if impostor and impostor_view:
        rt["impostor_view"] = impostor_view
    if wind and wind_seconds:
        rt["wind_seconds"] = wind_seconds
    # the mesh `sylva mesh -o tree.obj` writes: two-sided leaves, triangles without area dropped
    # (with levels or wind, the .glb's: one-sided leaves, drawn from both sides)
    plant = m.build(None if steps < 0 else steps, until="skeleton" if output == "CURVES" else "mesh",
                    leaves=leaves, optimize=output != "CURVES", scene=scene_block, **rt, **kw)
    coll = context.collection
    root = bpy.data.objects.new(m.name, None)
    root.empty_display_type = "PLAIN_AXES"
    root.location = location
    root["sylva_file"] = path
    root["sylva_model"] = m.name
    coll.objects.link(root)
    instanced = leaves == "instanced"
    arm = None
    if plant.levels:  # NAME_LOD0 is the tree's mesh
        obj = realtime.add_levels(context, plant, m.name, root, mesh_object, instanced)[0]
        if instanced:
            root["sylva_leaf_instances"] = obj["sylva_leaf_instances"]
    else:
        obj = curve_object(plant, m.name + " stems") if output == "CURVES" else mesh_object(plant, m.name + " mesh", scene_block)
        coll.objects.link(obj)
        obj.parent = root
        if plant.wind is not None:
            arm = realtime.armature(context, plant.wind, m.name, root, coll)
            realtime.skin(obj, arm, realtime.bone_names(m.name, plant.wind), plant.wind.skin_joints,
                          plant.wind.skin_weights)
        if instanced:
            root["sylva_leaf_instances"] = leaf_instances.add(
                plant.leaf_sets(), m.name, mesh_object, root, coll, arm,
                realtime.bone_names(m.name, plant.wind) if arm else None)
    obj["sylva_nodes"] = plant.info["nodes"]
    return root


def add_ecosystem(context, path: str, m, seed: int, years: int, overrides: dict, location, terrain):
    """Run an ecosystem block and put its last snapshot in the scene as collection instances
    under an empty named after it (forest.py); returns the empty."""
    run = m.run(None if years < 0 else years, seed=None if seed < 0 else seed, **overrides)
    root = bpy.data.objects.new(m.name, None)
    root.empty_display_type = "PLAIN_AXES"
    root.location = location
    root["sylva_file"] = path
    root["sylva_model"] = m.name
    context.collection.objects.link(root)
    root["sylva_plants"] = forest.add_forest(context, m.file, m, run, terrain, root, mesh_object)
    return root


def _models(self, context):
    path = bpy.path.abspath(getattr(self, "filepath", "") or "")
    try:
        names = sylva.load(path).models if os.path.isfile(path) else []
    except Exception:  # a broken file lists nothing; adding it reports the error
        names = []
    return [("", "First model", "the file's first model")] + [(n, n, "") for n in names]


class SYLVA_OT_add_tree(bpy.types.Operator):
    """Add a plant grown by Sylva from a model file or the species library"""
    bl_idname = "mesh.sylva_tree_add"
    bl_label = "Sylva Tree"
    bl_options = {"REGISTER", "UNDO"}

    species: EnumProperty(name="Species", items=library.enum_items,
                          description="a species of the library shipped with Sylva (instead of File)")
    filepath: StringProperty(name="File", subtype="FILE_PATH",
                             description="a .syl model, an Arbaro .xml species, a Pafčo .cfg or a Sapling preset .py")
    model: StringProperty(name="Model", description="the model's name in the file (empty: its first)")
    seed: IntProperty(name="Seed", default=-1, min=-1, description="the random seed (-1: the model's)")
    steps: IntProperty(name="Steps", default=-1, min=-1, max=10000,
                       description="derivation steps or years of growth (-1: the model's)")
    output: EnumProperty(name="Output", items=OUTPUTS, default="MESH")
    leaves: EnumProperty(name="Leaves", items=LEAVES, default="copied")
    params: CollectionProperty(type=schema.SylvaParam, name="Parameters")
    params_for: StringProperty(options={"HIDDEN"}, description="the file and model the parameters are of")
    overrides: StringProperty(name="More parameters", description="--set values: NAME=VALUE NAME=VALUE …")
    use_scene: BoolProperty(name="From the scene", default=False,
                            description="a curvetree's trunk is the active curve and its envelope the selected "
                                        "mesh; a grow block's obstacles are the selected meshes; an ecosystem's "
                                        "terrain is the selected mesh")
    lod: IntProperty(name="LOD levels", default=0, min=0, max=8,
                     description="levels of detail NAME_LOD0 .. NAME_LODn in a collection (sylva mesh --lod)")
    impostor: BoolProperty(name="Impostor", default=False,
                           description="the last level is a card of crossed billboards with the plant's baked "
                                       "picture (sylva mesh --impostor)")
    impostor_view: IntProperty(name="Impostor pixels", default=256, min=16, max=1024,
                               description="pixels a side of each baked view (--impostor-view)")
    wind: FloatProperty(name="Wind", default=0.0, min=0.0, max=60.0, unit="VELOCITY",
                        description="wind speed in m/s (0: none): an armature with the sway's action, the mesh "
                                    "skinned to it (sylva mesh --wind)")
    wind_seconds: FloatProperty(name="Wind loop", default=4.0, min=0.5, max=60.0, unit="TIME_ABSOLUTE",
                                description="the length of the looping sway, seconds (--wind-seconds)")

    def source(self) -> str:
        return library.path(self.species) if self.species != library.NONE else self.filepath

    def draw(self, context):
        col = self.layout.column()
        for prop in ("species", "filepath", "model", "seed", "steps", "output", "leaves", "use_scene", *REALTIME):
            col.prop(self, prop)
        schema.draw(col, self.params)
        col.prop(self, "overrides")

    def execute(self, context):
        try:
            path = self.source()
            if not path:
                self.report({"ERROR"}, "Sylva: choose a model file or a species")
                return {"CANCELLED"}
            m = load_model(path, self.model)
            key = f"{path}|{m.name}"
            given = True
            if self.params_for != key:  # a new model: its parameters at its values
                given = schema.fill(self.params, m, keep=not self.params_for)
                self.params_for = key
            kw = schema.overrides(self.params) if given else {}  # rows just filled at the model's values
            kw.update(_overrides(self.overrides))
            where = tuple(context.scene.cursor.location)
            with scene.Inputs(path) as io:
                text, said, planted = scene.rewrite(context, path, m, io) if self.use_scene else (None, "", False)
                if text is not None:  # the scene's objects are in world coordinates: the tree too
                    m, where = sylva.compile(text, path)[m.name], (0.0, 0.0, 0.0)
                if not m.is_plant:  # an ecosystem block: its plants, run as `sylva ecosystem`
                    root = add_ecosystem(context, path, m, self.seed, self.steps, kw, where,
                                         scene.inputs(context)[1][0] if text is not None else None)
                else:
                    root = add_tree(context, path, self.model, self.seed, self.steps, self.output, self.leaves,
                                    kw, where, m=m, scene_block=planted,
                                    **{p: getattr(self, p) for p in REALTIME})
            if said:
                root["sylva_scene"] = said
                self.report({"INFO"}, f"Sylva: {said}")
        except (sylva.SylvaError, ValueError, OSError, KeyError, TypeError) as e:
            self.report({"ERROR"}, f"Sylva: {e}")
            return {"CANCELLED"}
        return {"FINISHED"}


class SylvaSettings(bpy.types.PropertyGroup):
    species: EnumProperty(name="Species", items=library.enum_items)
    filepath: StringProperty(name="File", subtype="FILE_PATH")
    model: EnumProperty(name="Model", items=_models)
    seed: IntProperty(name="Seed", default=-1, min=-1)
    steps: IntProperty(name="Steps", default=-1, min=-1, max=10000)
    output: EnumProperty(name="Output", items=OUTPUTS, default="MESH")
    leaves: EnumProperty(name="Leaves", items=LEAVES, default="copied")
    overrides: StringProperty(name="Parameters")
    use_scene: BoolProperty(name="From the scene", default=False)
    lod: IntProperty(name="LOD levels", default=0, min=0, max=8)
    impostor: BoolProperty(name="Impostor", default=False)
    impostor_view: IntProperty(name="Impostor pixels", default=256, min=16, max=1024)
    wind: FloatProperty(name="Wind", default=0.0, min=0.0, max=60.0, unit="VELOCITY")
    wind_seconds: FloatProperty(name="Wind loop", default=4.0, min=0.5, max=60.0, unit="TIME_ABSOLUTE")


class SYLVA_PT_panel(bpy.types.Panel):
    bl_label = "Sylva"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Sylva"

    def draw(self, context):
        s = context.scene.sylva
        col = self.layout.column()
        col.label(text="Library")
        col.template_icon_view(s, "species", show_labels=True, scale=5.0)
        col.prop(s, "species", text="")
        for prop in ("filepath", "model", "seed", "steps", "output", "leaves", "overrides", "use_scene", *REALTIME):
            col.prop(s, prop)
        op = col.operator(SYLVA_OT_add_tree.bl_idname, text="Add tree", icon="OUTLINER_OB_MESH")
        for prop in ("species", "filepath", "model", "seed", "steps", "output", "leaves", "overrides", "use_scene",
                     *REALTIME):
            setattr(op, prop, getattr(s, prop))


def _menu(self, context):
    self.layout.operator(SYLVA_OT_add_tree.bl_idname, text="Sylva Tree", icon="OUTLINER_OB_MESH")


CLASSES = (*schema.CLASSES, SylvaSettings, SYLVA_OT_add_tree, SYLVA_PT_panel)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.Scene.sylva = bpy.props.PointerProperty(type=SylvaSettings)
    bpy.types.VIEW3D_MT_mesh_add.append(_menu)


def unregister():
    bpy.types.VIEW3D_MT_mesh_add.remove(_menu)
    del bpy.types.Scene.sylva
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
    library.free()
    _loaded.clear()
    schema.free()
