"""Leaves as instances (Leaves: Instanced): one leaf object instanced on the faces of an
emitter mesh, a square face per leaf, instead of a copy of the blade per leaf — what
`sylva mesh --leaves instanced` writes into a .glb with EXT_mesh_gpu_instancing, made with
Blender's own face instancing.

Each leaf's face is centred on the leaf's position, its first edge along the leaf's heading H,
its normal along U = H × L, and its area the leaf's size squared: Blender turns the prototype's
+x to the first edge and +z to the normal, and scales it by the square root of the area, so a
vertex p of the prototype lands at pos + R(size p) as Sylva places it (docs/mesh.md, Leaves).
The prototype is a leaf of size 1 with its base at the origin, along +x, across +y, facing +z.
One emitter and prototype a material, as Sylva makes one instance set a material."""
from __future__ import annotations

import bpy
import numpy as np

INSTANCED = ("leaf", "needle")  # the organ kinds drawn as leaf instances


def _prototype(name: str, material) -> bpy.types.Object:
    """A leaf blade of length 1 and width 0.4 along +x, its base at the origin."""
    me = bpy.data.meshes.new(name)
    me.from_pydata([(0, 0, 0), (0.35, 0.2, 0), (1, 0, 0), (0.35, -0.2, 0)], [], [(0, 3, 2, 1)])
    me.materials.append(material)
    me.update()
    return bpy.data.objects.new(name, me)


def add(plant, kinds: list[str], name: str, material_for, parent, collection) -> int:
    """The plant's leaves as face instances under parent; returns how many."""
    org = plant.skeleton.organs
    wanted = [kinds.index(k) for k in INSTANCED if k in kinds]
    org = org[np.isin(org["kind"], wanted)]
    for k, mat in enumerate(np.unique(org["material"])):
        o = org[org["material"] == mat]
        n = len(o)

        def blender(v):  # Sylva's y-up to Blender's z-up, as the mesh is turned
            return np.stack([v[:, 0], -v[:, 2], v[:, 1]], axis=1)

        pos, h, u = blender(o["pos"]), blender(o["h"]), blender(o["u"])
        side = np.cross(u, h)  # across the leaf, so that the face's normal is u
        a = (o["size"] / 2)[:, None]
        corners = np.stack([pos - a * h - a * side, pos + a * h - a * side, pos + a * h + a * side,
                            pos - a * h + a * side], axis=1).astype(np.float32)
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
        proto = _prototype(f"{name} leaf{k}", material_for(int(mat)))
        collection.objects.link(proto)
        proto.parent = emitter
    return len(org)
