"""What `sylva mesh --lod N --impostor --wind SPEED` writes into a .glb, made as Blender objects
(docs/blender.md): the levels of detail as NAME_LOD0 .. NAME_LODn in a collection of their own,
the impostor's crossed billboards as the last level with the baked atlas packed into its
material, and the wind as an armature — a bone per wind joint, from the stem's base along it —
with an action of its keys, every level but the billboards skinned to it with the .glb's
weights (vertex groups and an Armature modifier).

Sylva's joints have no rest rotation and turn in their parent's frame (glTF's skin). A Blender
bone has a rest orientation R (its y along the bone); its pose rotation that gives the same
motion is R⁻¹ q R, q turned from Sylva's y-up axes to Blender's z-up ones."""
from __future__ import annotations

import bpy
import numpy as np
from mathutils import Vector


LINEAR = bpy.types.Keyframe.bl_rna.properties["interpolation"].enum_items["LINEAR"].value


def _z_up(v):
    """Sylva's (x, y, z), y up, as Blender's (x, -z, y)."""
    v = np.asarray(v, dtype=np.float64)
    return np.stack([v[..., 0], -v[..., 2], v[..., 1]], axis=-1)


def _qmul(a, b):
    """Hamilton products of quaternions (w, x, y, z) along the last axis."""
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw], axis=-1)


def bone_names(name: str, wind) -> list[str]:
    return [f"{name}_stem{int(s)}" for s in wind.joints["stem"]]


def armature(context, wind, name: str, parent, collection) -> bpy.types.Object:
    """The wind's joints as bones (parents first, as Sylva lists them) and its keys as the
    action "NAME wind" on the bones' quaternions, frames 0 .. seconds × the scene's fps, linear
    between keys and cyclic."""
    arm = bpy.data.armatures.new(f"{name} wind")
    obj = bpy.data.objects.new(f"{name} wind", arm)
    collection.objects.link(obj)
    obj.parent = parent
    heads = _z_up(wind.heads)
    stems = wind.stems[wind.joints["stem"]]
    dirs = _z_up(stems["dir"])
    length = np.maximum(stems["length"], 1e-3)
    names = bone_names(name, wind)
    view_layer = context.view_layer
    active = view_layer.objects.active
    view_layer.objects.active = obj
    bpy.ops.object.mode_set(mode="EDIT")
    bones = []
    for j, n in enumerate(names):
        b = arm.edit_bones.new(n)
        b.head = Vector(heads[j])
        d = dirs[j] if np.linalg.norm(dirs[j]) > 0 else np.array([0.0, 0.0, 1.0])
        b.tail = Vector(heads[j] + d * length[j])
        p = int(wind.joints["parent"][j])
        if p >= 0:
            b.parent = bones[p]
        bones.append(b)
    bpy.ops.object.mode_set(mode="OBJECT")
    view_layer.objects.active = active
    # the pose rotations R⁻¹ q R of every key, R each bone's rest orientation
    rest = np.array([tuple(arm.bones[n].matrix_local.to_quaternion()) for n in names])  # (joints, 4) w, x, y, z
    q = wind.rotations  # (joints, keys, 4) x, y, z, w in Sylva's axes
    q = np.concatenate([q[..., 3:4], _z_up(q[..., :3])], axis=-1)
    inv = rest * np.array([1.0, -1.0, -1.0, -1.0])
    basis = _qmul(_qmul(inv[:, None, :], q), rest[:, None, :])
    scene = context.scene
    frames = wind.times * scene.render.fps / scene.render.fps_base
    action = bpy.data.actions.new(f"{name} wind")
    for j, n in enumerate(names):
        pb = obj.pose.bones[n]
        pb.rotation_mode = "QUATERNION"
        path = f'pose.bones["{n}"].rotation_quaternion'
        for c in range(4):
            fc = action.fcurves.new(path, index=c, action_group=n)
            fc.keyframe_points.add(len(frames))
            fc.keyframe_points.foreach_set("co", np.stack([frames, basis[j, :, c]], axis=1).astype(np.float32).ravel())
            # linear between keys, as glTF's sampler (a Bézier would overshoot the sway's bound)
            fc.keyframe_points.foreach_set("interpolation", np.full(len(frames), LINEAR, dtype=np.int32))
            fc.modifiers.new("CYCLES")
            fc.update()
    obj.animation_data_create().action = action
    return obj


def skin(obj, arm_obj, names: list[str], joints, weights) -> None:
    """Vertex groups of the two joints of each vertex with their weights (bytes over 255), and
    an Armature modifier: the mesh follows the bones as the .glb's skin does."""
    groups = [obj.vertex_groups.new(name=n) for n in names]
    for slot in range(2):
        w = weights[:, slot]
        used = w > 0
        for j, wt in set(zip(joints[used, slot].tolist(), w[used].tolist())):
            idx = np.flatnonzero(used & (joints[:, slot] == j) & (w == wt)).tolist()
            groups[j].add(idx, wt / 255.0, "ADD")
    mod = obj.modifiers.new("Wind", "ARMATURE")
    mod.object = arm_obj


def atlas_image(name: str, rgba) -> bpy.types.Image:
    """An RGBA picture (rows from the top, as Sylva bakes it) as a packed Blender image."""
    h, w, _ = rgba.shape
    img = bpy.data.images.new(name, w, h, alpha=True)
    img.pixels.foreach_set((np.asarray(rgba[::-1], dtype=np.float32) / 255.0).ravel())
    img.pack()
    return img


def card_material(name: str, img) -> bpy.types.Material:
    """An alpha-tested card material textured with img (the billboards' atlas), one-sided."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    bsdf = nt.nodes.get("Principled BSDF")
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = img
    nt.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    nt.links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    # each quad's two faces carry the two views (the one it faces): a face seen from behind is
    # not drawn, in Cycles too (which ignores backface culling)
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
    nt.links.new(bsdf.outputs["BSDF"], mix.inputs[1])
    nt.links.new(nt.nodes.new("ShaderNodeBsdfTransparent").outputs["BSDF"], mix.inputs[2])
    nt.links.new(mix.outputs["Shader"], nt.nodes["Material Output"].inputs["Surface"])
    mat.blend_method = "CLIP"
    mat.shadow_method = "CLIP"
    mat.use_backface_culling = True
    return mat


def add_levels(context, plant, name: str, root, mesh_object, instanced: bool = False) -> list[bpy.types.Object]:
    """NAME_LOD0 .. NAME_LODn in the collection NAME_LODs (inside the scene's), parented to
    root; the billboards' level textured with the impostor's atlas; with wind, an armature
    and every other level skinned to it. instanced: each geometric level's leaves as face
    instances (leaves.py) beside it, NAME_leavesK_LODk, following the wind's bones; the count
    in the level's "sylva_leaf_instances". Returns the level objects."""
    from . import leaves as leaf_instances
    coll = bpy.data.collections.new(f"{name}_LODs")
    context.collection.children.link(coll)
    levels = plant.levels
    wind = plant.wind
    arm = armature(context, wind, name, root, context.collection) if wind is not None else None
    objs = []
    for lv in levels:
        obj = mesh_object(lv.mesh, f"{name}_LOD{lv.level}")
        obj["sylva_lod"] = lv.level
        obj["sylva_screen_coverage"] = lv.coverage
        coll.objects.link(obj)
        obj.parent = root
        if lv.billboards:
            # a quad's two faces lie in one plane, which a ray tracer cannot order: each is
            # moved a thousandth of the impostor's radius along its normal, toward its viewer
            imp = plant.impostor
            co = np.empty(3 * len(obj.data.vertices), np.float32)
            obj.data.vertices.foreach_get("co", co)
            co += (1e-3 * imp.radius * _z_up(lv.mesh.normals)).astype(np.float32).ravel()
            obj.data.vertices.foreach_set("co", co)
            obj.data.update()
            img = atlas_image(f"{name}_billboards", imp.billboard_atlas)
            obj.data.materials.clear()
            obj.data.materials.append(card_material(f"{name} Impostor", img))
            if imp.color is not None:  # the octahedral atlas, for engines that draw it (packed, unused here)
                obj["sylva_impostor_atlas"] = atlas_image(f"{name}_impostor", imp.color).name
                obj["sylva_impostor_normal"] = atlas_image(f"{name}_impostor_normal", imp.normal).name
                obj["sylva_impostor_grid"] = imp.grid
        else:
            if arm is not None:
                skin(obj, arm, bone_names(name, wind), *lv.skin())
            if instanced:
                obj["sylva_leaf_instances"] = leaf_instances.add(
                    lv.leaf_sets(), name, mesh_object, root, coll, arm, bone_names(name, wind) if arm else None,
                    suffix=f"_LOD{lv.level}", hide=lv.level > 0)
        if lv.level > 0:  # the far levels are for export: hidden in the viewport and renders
            obj.hide_set(True)
            obj.hide_render = True
        objs.append(obj)
    return objs
