"""A .glb's leaf instances (EXT_mesh_gpu_instancing) per level of detail and per wind joint,
read from its JSON with no Blender, as tests/blender/addon_leaves.py prints the add-on's:
    leaf_levels LEVEL:COUNT,...  and  leaf_joints LEVEL:STEM:COUNT,...
The level is the NAME_LODk node the set hangs under, the stem the set's _stemN suffix (with
wind the writer splits each set by the joint its leaves follow).
    python3 glb_leaves.py FILE.glb"""
import json
import re
import struct
import sys

data = open(sys.argv[1], "rb").read()
n = struct.unpack("<I", data[12:16])[0]
gltf = json.loads(data[20:20 + n])
nodes, accessors = gltf["nodes"], gltf["accessors"]
levels, joints = {}, {}


def walk(i, level):
    node = nodes[i]
    t = node.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes", {}).get("TRANSLATION")
    if t is not None:
        count = accessors[t]["count"]
        levels[level] = levels.get(level, 0) + count
        stem = re.search(r"_stem(\d+)$", node.get("name", ""))
        key = (level, int(stem.group(1)) if stem else -1)
        joints[key] = joints.get(key, 0) + count
    for c in node.get("children", []):
        walk(c, level)


for i, node in enumerate(nodes):
    m = re.fullmatch(r".*_LOD(\d+)", node.get("name", ""))
    if m:
        walk(i, int(m.group(1)))
print("leaf_levels " + ",".join(f"{k}:{v}" for k, v in sorted(levels.items())))
print("leaf_joints " + ",".join(f"{lv}:{st}:{c}" for (lv, st), c in sorted(joints.items())))
