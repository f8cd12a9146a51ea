"""Leaves as instances (Leaves: Instanced): one leaf object instanced on the faces of an
emitter mesh, a square face per leaf, instead of a copy of the leaf per leaf — what
`sylva mesh --leaves instanced` writes into a .glb with EXT_mesh_gpu_instancing (the sets of
sylva.Plant.leaf_sets), made with Blender's own face instancing.

The leaf object is the set's prototype, the leaf the mesher itself makes for the model (its
own outline: a Weber–Penn leaf shape, a lobed or needle leaf; one-sided, drawn from both
sides), of size 1 with its base at the origin, along +x, across +y, facing +z. Each leaf's face
is centred on the instance's translation T, its first edge along R x, its normal along R z, and
its area the scale S squared: Blender turns the prototype's +x to the first edge and +z to the
normal and scales it by the square root of the area, so a vertex p of the prototype lands at
T + R (S p) as the .glb places it. One emitter and prototype a leaf material, as Sylva makes one
instance set a material."""
from __future__ import annotations

import bpy
import numpy as np


def _z_up(v):  # Sylva's y-up to Blender's z-up, as the mesh is turned
    return np.stack([v[:, 0], -v[:, 2], v[:, 1]], axis=1)


def _axes(q):
    """The images of +x and +y under unit quaternions q (n, 4: x, y, z, w)."""
    x, y, z, w = q.T.astype(np.float64)
    ax = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=1)
    ay = np.stack([2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)], axis=1)
    return ax, ay


def add(plant, name: str, mesh_object, parent, collection) -> int:
    """The plant's leaves as face instances under parent; returns how many. mesh_object(mesh,
    name, z_up=False) makes the prototype object from a sylva.Mesh."""
    total = 0
    for k, ls in enumerate(plant.leaf_sets()):
        n = len(ls)
        total += n
        ax, ay = _axes(ls.rotations)
        pos, ax, ay = _z_up(ls.translations), _z_up(ax), _z_up(ay)
        a = (ls.scales[:, :1] / 2).astype(np.float64)
        corners = np.stack([pos - a * ax - a * ay, pos + a * ax - a * ay, pos + a * ax + a * ay,
                            pos - a * ax + a * ay], axis=1).astype(np.float32)
        me = bpy.data.meshes.new(f"{name} leaves{k}")
        me.vertices.add(4 * n)
        me.vertices.foreach_set("co", corners.ravel())
        me.loops.add(4 * n)
        me.loops.foreach_set("vertex_index", np.arange(4 * n, dtype=np.int32))
        me.polygons.add(n)
        me.polygons.foreach_set("loop_start", np.arange(0, 4 * n, 4, dtype=np.int32))
        me.polygons.foreach_set("loop_total", np.full(n, 4, dtype=np.int32))
        me.update()
        emitter = bpy.data.objects.new(f"{name} leaves{k}", me)
        emitter.instance_type = "FACES"
        emitter.use_instance_faces_scale = True
        emitter.show_instancer_for_render = False
        emitter.show_instancer_for_viewport = False
        collection.objects.link(emitter)
        emitter.parent = parent
        proto = mesh_object(ls.proto, f"{name} leaf{k}", z_up=False)
        collection.objects.link(proto)
        proto.parent = emitter
    return total
