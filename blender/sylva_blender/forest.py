"""An `ecosystem` block in the scene: the selected mesh is its terrain (an OBJ terrain, as
`sylva terrain` reads one), the run's last snapshot a forest of collection instances — one
collection per species and age class, meshed once, each plant an empty that instances it —
so a snapshot of 100,000 plants is a handful of meshes.

The looks are the ones `sylva ecosystem` renders (docs/ecosystem.md, Pictures): three age
classes by the share h / height_max (below 1/3, below 2/3, above), an L-system's class c its
derivation at step round(n (c + 1) / 3) of its n steps, a grow block's at that share of its
years, other kinds one look; each look scaled to height 1 with its base at the origin; each
plant the look scaled to its height, standing on the terrain, turned about the vertical by a
hash of its id. (Sylva's renderer also gives a class three variants; the add-on one.)"""
from __future__ import annotations

import math

import bpy
from mathutils import Matrix, Vector


def age_class(height: float, height_max: float) -> int:
    share = height / height_max if height_max > 0 else 1.0
    return 0 if share < 1 / 3 else 1 if share < 2 / 3 else 2


def _turn(pid: int) -> float:
    """A plant's turn about the vertical from its id (a 64-bit mix): the same every snapshot."""
    x = (pid * 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
    x ^= x >> 31
    return (x % 3600) / 3600 * 2 * math.pi


def look(file, model_name: str, c: int, name: str, mesh_object) -> bpy.types.Collection:
    """The collection of one species' look at age class c: its mesh at height 1, base at 0."""
    coll = bpy.data.collections.get(name) or bpy.data.collections.new(name)
    for o in list(coll.objects):
        coll.objects.unlink(o)
    m = file[model_name]
    n = m.steps if m.has_steps else 0
    steps = max(1, round(n * (c + 1) / 3)) if n > 0 else None
    obj = mesh_object(m.build(steps, optimize=True), name)
    zs = [v.co.z for v in obj.data.vertices]
    top = max(zs) if zs else 1.0
    if top > 0:
        obj.data.transform(Matrix.Scale(1.0 / top, 4))
    coll.objects.link(obj)
    return coll


def ground(terrain, x: float, y: float) -> float:
    """The terrain's height under (x, y) in world coordinates (a ray down its evaluated mesh);
    0 where the ray misses it."""
    inv = terrain.matrix_world.inverted()
    o = inv @ Vector((x, y, 1.0e6))
    d = (inv.to_3x3() @ Vector((0.0, 0.0, -1.0))).normalized()
    hit, loc, _, _ = terrain.ray_cast(o, d)
    return (terrain.matrix_world @ loc).z if hit else 0.0


def add_forest(context, file, m, run, terrain, root, mesh_object) -> int:
    """The run's last snapshot under root as collection instances; returns how many."""
    years = sorted(run.snapshots.keys())
    if not years:
        raise ValueError(f"{m.name}: the run has no snapshot")
    plants = run.plants(years[-1])
    params = m.params
    species = run.species
    looks_parent = bpy.data.collections.new(f"{m.name} looks")
    context.scene.collection.children.link(looks_parent)
    looks_parent.hide_render = True
    context.view_layer.layer_collection.children[looks_parent.name].exclude = True
    looks: dict = {}
    for p in plants:
        s = species[int(p["species"])]
        hmax = float(params[f"{s}.height_max"].value)
        c = age_class(float(p["height"]), hmax)
        key = (s, c)
        if key not in looks:
            looks[key] = look(file, params[f"{s}.model"].value, c, f"{m.name} {s} age {c}", mesh_object)
            looks_parent.children.link(looks[key])
        # Sylva's (x, z) is Blender's (x, -y)
        x, y = float(p["x"]), -float(p["z"])
        z = ground(terrain, x, y) if terrain is not None else 0.0
        e = bpy.data.objects.new(f"{s}.{int(p['id'])}", None)
        e.instance_type = "COLLECTION"
        e.instance_collection = looks[key]
        h = float(p["height"])
        e.matrix_world = Matrix.LocRotScale(Vector((x, y, z)), Matrix.Rotation(_turn(int(p["id"])), 3, "Z").to_quaternion(),
                                            Vector((h, h, h)))
        context.collection.objects.link(e)
        e.parent = root
    return len(plants)
