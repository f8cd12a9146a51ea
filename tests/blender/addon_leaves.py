"""Instanced leaves on every level of detail, following the wind, in the Blender process of
addon_more.py (runpy'd at its end with `added` and the model): the add-on adds MODEL with
levels of detail, instanced leaves and wind, and this prints, for tests/run-blender to compare
with the .glb `sylva mesh --lod 2 --leaves instanced --wind 6` writes:
  leaf_levels LEVEL:COUNT,...   Blender's evaluated leaf instances per level (the emitters of
                                NAME_leavesK_LODk), against the .glb's instance counts per LODk;
  leaf_joints LEVEL:STEM:COUNT,...  per level, how many leaves follow each stem's bone (the
                                emitter's vertex groups), against the .glb's sets per joint;
  leaf_sway ...                 at frames 5 and 17 every instance's matrix is its rest matrix
                                carried by its bone's pose (rigid with the bone), the leaves
                                moved, and each leaf moved as the nearest LOD0 bark vertex
                                (within a tenth of the sway)."""
import bpy
import numpy
from mathutils.kdtree import KDTree

added, model = globals()["added"], globals()["leaves_model"]

bpy.ops.object.select_all(action="DESELECT")
r, lod0 = added(filepath=model, lod=2, leaves="instanced", wind=6.0, wind_seconds=2.0)
root = lod0.parent if lod0 else None
name = root.name if root else "?"
arm = next((o for o in root.children if o.type == "ARMATURE"), None) if root else None
emitters = [o for o in root.children if o.instance_type == "FACES"] if root else []
level_of = {e.name: int(e.name.rsplit("_LOD", 1)[1]) for e in emitters}


def instances():
    """[(level, emitter name, matrix)] of every evaluated leaf instance under root."""
    dg = bpy.context.evaluated_depsgraph_get()
    return [(level_of[i.parent.original.name], i.parent.original.name, i.matrix_world.copy())
            for i in dg.object_instances if i.is_instance and i.parent and i.parent.original.name in level_of]


for e in emitters:  # the export levels, hidden, shown for the count
    e.hide_set(False)
arm.data.pose_position = "REST"
rest = instances()
arm.data.pose_position = "POSE"
per_level = {}
for lv, _, _ in rest:
    per_level[lv] = per_level.get(lv, 0) + 1
print(f"leaf_levels result={r} {','.join(f'{k}:{v}' for k, v in sorted(per_level.items()))}")
# the bone of each instance: its emitter's face's vertex group (faces in instance order)
bone_of = {}
joints = {}
for e in emitters:
    groups = {g.index: g.name for g in e.vertex_groups}
    faces = [groups[e.data.vertices[p.vertices[0]].groups[0].group] if e.data.vertices[p.vertices[0]].groups else None
             for p in e.data.polygons]
    bone_of[e.name] = faces
    for b in faces:
        key = (level_of[e.name], int(b.rsplit("_stem", 1)[1]) if b else -1)
        joints[key] = joints.get(key, 0) + 1
print("leaf_joints " + ",".join(f"{lv}:{st}:{n}" for (lv, st), n in sorted(joints.items())))
# sway: the instances of an emitter come in the order of its faces
size = max(max(abs(c) for c in m.translation) for _, _, m in rest) if rest else 1.0
lod0_obj = bpy.data.objects.get(f"{name}_LOD0")
co0 = numpy.empty(3 * len(lod0_obj.data.vertices))
lod0_obj.data.vertices.foreach_get("co", co0)
co0 = co0.reshape(-1, 3)
tree = KDTree(len(co0))
for i, c in enumerate(co0):
    tree.insert(c, i)
tree.balance()
nearest = [tree.find(m.translation)[1] for lv, _, m in rest if lv == 0]
rigid_dev = moved = near_dev = 0.0
for f in (5, 17):
    bpy.context.scene.frame_set(f)
    now = instances()
    seen = {}
    for (lv, en, m0), (_, _, m1) in zip(rest, now):
        k = seen.get(en, 0)
        seen[en] = k + 1
        pb = arm.pose.bones[bone_of[en][k]]
        carried = arm.matrix_world @ pb.matrix @ pb.bone.matrix_local.inverted() @ arm.matrix_world.inverted() @ m0
        rigid_dev = max(rigid_dev, max(abs(a - b) for ra, rb in zip(carried, m1) for a, b in zip(ra, rb)))
        moved = max(moved, (m1.translation - m0.translation).length)
    ev = lod0_obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    co = numpy.empty(3 * len(ev.vertices))
    ev.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    lod0_obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()
    leaf_moves = [numpy.array(m1.translation - m0.translation) for (lv, _, m0), (_, _, m1) in zip(rest, now) if lv == 0]
    bark_moves = [co[i] - co0[i] for i in nearest]
    near_dev = max(near_dev, max(float(numpy.linalg.norm(a - b)) for a, b in zip(leaf_moves, bark_moves)))
bpy.context.scene.frame_set(0)
print(f"leaf_sway instances={len(rest)} rigid={'yes' if rigid_dev < 1e-4 * size else 'no (%.3g)' % rigid_dev} "
      f"moved={'yes' if moved > 1e-3 * size else 'no'} with_bark={'yes' if near_dev < 0.1 * moved else 'no (%.3g of %.3g)' % (near_dev, moved)}")
