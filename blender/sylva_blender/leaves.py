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
from sylva import _core


def add(sets, name: str, mesh_object, parent, collection, arm=None, bone_names=None, suffix: str = "",
        hide: bool = False) -> int:
    """The sets (sylva.LeafSet, a plant's or a level's) as face instances under parent, each
    set an emitter "NAME leavesK" (+ suffix) with its leaf object "NAME leafK" as child;
    returns how many leaves. mesh_object(mesh, name, z_up=False) makes the leaf object from
    the prototype. With arm (the wind's armature) each leaf's face is skinned whole to the
    bone of its joint (LeafSet.joints, the joint the .glb puts it under): the face moves as
    the bone, and its leaf with it, turned and carried with the tip. hide: an export level
    (hidden in the viewport and renders)."""
    total = 0
    sep = "_" if suffix else " "
    for k, ls in enumerate(sets):
        n = len(ls)
        total += n
        # the squares in Sylva's y-up frame (the package's C helper), turned to Blender's z-up
        quads = np.asarray(_core.instance_quads(ls.translations, ls.rotations, ls.scales))
        corners = np.empty_like(quads)
        corners[:, 0], corners[:, 1], corners[:, 2] = quads[:, 0], -quads[:, 2], quads[:, 1]
        me = bpy.data.meshes.new(f"{name}{sep}leaves{k}{suffix}")
        me.vertices.add(4 * n)
        me.vertices.foreach_set("co", corners.ravel())
        me.loops.add(4 * n)
        me.loops.foreach_set("vertex_index", np.arange(4 * n, dtype=np.uint32))  # uint32: foreach_set's fast path
        ring = np.arange(4 * n, dtype=np.uint32)  # each face's four sides, given (no search in update())
        me.edges.add(4 * n)
        me.edges.foreach_set("vertices", np.stack([ring, ring - ring % 4 + (ring + 1) % 4], axis=1).ravel())
        me.loops.foreach_set("edge_index", ring)
        me.polygons.add(n)
        me.polygons.foreach_set("loop_start", np.arange(0, 4 * n, 4, dtype=np.uint32))
        me.polygons.foreach_set("loop_total", np.full(n, 4, dtype=np.uint32))
        me.update()
        emitter = bpy.data.objects.new(f"{name}{sep}leaves{k}{suffix}", me)
        emitter.instance_type = "FACES"
        emitter.use_instance_faces_scale = True
        emitter.show_instancer_for_render = False
        emitter.show_instancer_for_viewport = False
        collection.objects.link(emitter)
        emitter.parent = parent
        if arm is not None and ls.joints is not None:
            for j in np.unique(ls.joints).tolist():
                face = np.flatnonzero(ls.joints == j)
                emitter.vertex_groups.new(name=bone_names[j]).add(
                    (4 * face[:, None] + np.arange(4)).ravel().tolist(), 1.0, "REPLACE")
            emitter.modifiers.new("Wind", "ARMATURE").object = arm
        proto = mesh_object(ls.proto, f"{name}{sep}leaf{k}{suffix}", z_up=False)
        collection.objects.link(proto)
        proto.parent = emitter
        if hide:
            emitter.hide_set(True)
            emitter.hide_render = True
    return total
