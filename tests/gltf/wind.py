#!/usr/bin/env python3
"""Independent reader of a skinned .glb from `sylva mesh --wind` (python3 stdlib only).

  wind.py FILE.glb SKELETON.csv LEVELS SECONDS [UNSKINNED.glb] [--leaves-at-nodes]

With levels of detail every skinned node is checked; UNSKINNED.glb, the same chain written
without --wind, must have the same vertices and triangles in each level (the rest pose of
each level is its unskinned level), and every level but the billboards is skinned. With
instanced leaves, each set hangs from the joint its leaves follow (or, with levels, from
the level's copy of it), and at rest the leaves are where UNSKINNED.glb has them; a leaf
at a skeleton node hangs from that node's stem's joint (--leaves-at-nodes: every leaf is at
one, as an L-system's ~leaf is).

SKELETON.csv is `sylva skeleton` of the same model. Checks:
  - one joint per stem of branch order < LEVELS (a stem: a root, or a node whose order
    differs from its parent's), each joint at its stem's base, and each joint's parent the
    joint of the stem it grows on (compared as multisets of (base, parent base) pairs);
  - JOINTS_0 in range and WEIGHTS_0 summing to 1 at every vertex;
  - the blend at a stem's base: each non-root joint's extras.sylva_wind blend [a, l] and
    direction u are the skeleton's (a = min(R, L/4), l = min(4 r, L/4): R the parent's radius
    at the base, r the stem's base radius, L its length; u its first segment), and every
    vertex's weights are smoothstep(t) on the stem's joint and 1 - smoothstep(t) on its
    parent, t = clamp((max(s, d - a - l) - a) / l, 0, 1) with s = (p - base).u and
    d = |p - base| (to a byte);
  - the rest pose (node transforms, no animation) times the inverse bind matrices is the
    identity, and skinning every vertex at rest gives the unskinned mesh;
  - one looping animation: key times 0 .. SECONDS increasing, rotations unit quaternions,
    each joint's angle within its amplitude (extras.sylva_wind) and the model's bound,
    the first and last keys equal;
  - _BRANCH_LEVEL are the skeleton's orders, _PHASE in [0, 2 pi), _STIFFNESS in (0, 1].
Prints "ok ..." lines, or "FAIL ..." and exits 1."""
import csv, json, math, struct, sys
from glbio import read_glb as _read_glb, triangles

AT_NODES = False
BOUND = 0.1 + math.sqrt(2) * 0.12  # directed + undirected caps (docs/mesh.md#wind)
SIZES = {5126: ("f", 4), 5125: ("I", 4), 5123: ("H", 2), 5121: ("B", 1), 5122: ("h", 2), 5120: ("b", 1)}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def fail(msg):
    print("FAIL wind: " + msg)
    sys.exit(1)


def read_glb(path):
    return _read_glb(path, fail)


def accessor(js, bin_, i):
    a = js["accessors"][i]
    v = js["bufferViews"][a["bufferView"]]
    ch, size = SIZES[a["componentType"]]
    k = WIDTH[a["type"]]
    off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    stride = v.get("byteStride", k * size)
    if stride == k * size:
        flat = struct.unpack_from("<%d%s" % (k * a["count"], ch), bin_, off)
    else:  # padded elements (quantized VEC3s)
        flat = [x for n in range(a["count"]) for x in struct.unpack_from("<%d%s" % (k, ch), bin_, off + n * stride)]
    if a.get("normalized") and ch in "bh":  # the signed normalized types
        flat = [max(x / (2 ** (8 * size - 1) - 1), -1.0) for x in flat]
    elif a.get("normalized"):
        flat = [x / (2 ** (8 * size) - 1) for x in flat]  # the unsigned normalized types
    return [flat[k * n:k * n + k] for n in range(a["count"])]


def matmul(a, b):  # column-major 4x4
    return [sum(a[r + 4 * k] * b[k + 4 * c] for k in range(4)) for c in range(4) for r in range(4)]


def trs(node):
    t = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    s = node.get("scale", [1, 1, 1])
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    m = [r[0] * s[0], r[1] * s[0], r[2] * s[0], 0, r[3] * s[1], r[4] * s[1], r[5] * s[1], 0,
         r[6] * s[2], r[7] * s[2], r[8] * s[2], 0, t[0], t[1], t[2], 1]
    return m


def stems_of(csv_path, levels):
    rows = [r for r in csv.DictReader(open(csv_path)) if r["kind"] in ("root", "internode")]
    node = {int(r["id"]): r for r in rows}
    stem_of, stems = {}, []
    for r in rows:  # parents precede children
        i, p = int(r["id"]), int(r["parent"])
        par = node.get(p)
        if par is not None and par["order"] == r["order"]:
            stem_of[i] = stem_of[p]
            continue
        base = tuple(float((par or r)[c]) for c in "xyz")
        first = tuple(float(r[c]) for c in "xyz")
        stems.append({"order": int(r["order"]), "base": base, "parent": stem_of.get(p, -1), "length": 0.0,
                      "radius": 0.0, "parent_radius": float(par["radius"]) if par is not None else 0.0,
                      "dir": unit([a - b for a, b in zip(first, base)]) if par is not None else None,
                      "first": math.dist(first, base)})
        stem_of[i] = len(stems) - 1
    for r in rows:  # length and base radius, along the internodes
        st = stems[stem_of[int(r["id"])]]
        par = node.get(int(r["parent"]))
        if r["kind"] == "internode" and par is not None:
            st["length"] += math.dist([float(r[c]) for c in "xyz"], [float(par[c]) for c in "xyz"])
            if st["radius"] <= 0 and float(r["radius"]) > 0:
                st["radius"] = float(r["radius"])
    for st in stems:  # the parent's joint: the nearest ancestor stem with a joint
        q = st["parent"]
        while q >= 0 and stems[q]["order"] >= levels:
            q = stems[q]["parent"]
        st["joint_parent"] = stems[q]["base"] if q >= 0 else None
    global NODE_JOINT
    NODE_JOINT = []  # (position, base of the joint its stem follows) of every node
    for r in rows:
        q = stem_of[int(r["id"])]
        while q >= 0 and stems[q]["order"] >= levels:
            q = stems[q]["parent"]
        if q >= 0:
            NODE_JOINT.append((tuple(float(r[c]) for c in "xyz"), stems[q]["base"]))
    for st in stems:
        L = st["length"]
        st["blend"] = (min(st["parent_radius"], L / 4), min(4 * st["radius"], L / 4)) \
            if st["joint_parent"] is not None and st["dir"] is not None else (0.0, 0.0)
    return [s for s in stems if s["order"] < levels], {int(r["order"]) for r in rows}


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v) if n > 0 else None


def own_weight(p, base, blend, u):
    """The weight (0..255) of a stem's joint at p: smoothstep of t along its base."""
    a, l = blend
    x = [p[c] - base[c] for c in range(3)]
    s = sum(x[c] * u[c] for c in range(3))
    t = min(1.0, max(0.0, (max(s, math.sqrt(sum(c * c for c in x)) - a - l) - a) / l))
    return 255 * t * t * (3 - 2 * t)


def key(p, scale):
    return tuple(round(c / scale, 4) for c in p) if p is not None else ()


def check_blend(js, joints, base, parent, want, scale, pos, jw, ww, path):
    """Each joint's blend against the skeleton's stems, each vertex's weights against it."""
    nodes = js["nodes"]
    blend = {}
    for k, j in enumerate(joints):
        ex = nodes[j]["extras"]["sylva_wind"]
        pb = key(base[parent[j]], scale) if parent.get(j) in base else ()
        cands = [s for s in want if key(s["base"], scale) == key(base[j], scale) and key(s["joint_parent"], scale) == pb]
        if "blend" not in ex:
            if any(s["blend"][1] > 0 for s in cands) and not any(s["blend"][1] <= 0 for s in cands):
                fail(f"joint {j}: no blend at its base")
            continue
        b, u = tuple(ex["blend"]), tuple(ex["direction"])
        tol = 1e-4 * max(1.0, scale)  # the CSV has 6 digits
        if not any(abs(b[0] - s["blend"][0]) <= tol and abs(b[1] - s["blend"][1]) <= tol and s["dir"] is not None
                   and max(abs(x - y) for x, y in zip(u, s["dir"])) <= 1e-3 + 1e-5 * scale / max(s["first"], 1e-9)
                   for s in cands):
            fail(f"joint {j}: blend {b} along {u} is not a skeleton stem's "
                 f"({[(s['blend'], s['dir']) for s in cands]})")
        blend[k] = (b, u)
    pjoint = {k: joints.index(parent[j]) if parent.get(j) in joints else -1 for k, j in enumerate(joints)}
    children = {}
    for k, q in pjoint.items():
        children.setdefault(q, []).append(k)
    blended = 0
    for p, jj, w in zip(pos, jw, ww):
        w8 = [round(x * 255) for x in w]
        used = [(j, x) for j, x in zip(jj, w8) if x > 0]
        if len(used) == 2:  # a child joint and its parent
            (j0, x0), (j1, x1) = used
            own, other, x = (j0, j1, x0) if pjoint[j0] == j1 else (j1, j0, x1) if pjoint[j1] == j0 else (None, None, 0)
            if own is None or own not in blend:
                fail(f"vertex {p}: weights on joints {jj} that are not a stem's joint and its parent")
            if abs(own_weight(p, base[joints[own]], *blend[own]) - x) > 1.01:
                fail(f"vertex {p}: weight {x} of joint {own}, the formula gives "
                     f"{own_weight(p, base[joints[own]], *blend[own]):.2f}")
            blended += 1
        elif len(used) == 1:  # all the joint's: its own stem's past the blend, or a child's before it
            j = used[0][0]
            ok = j not in blend or own_weight(p, base[joints[j]], *blend[j]) >= 253.99
            ok = ok or any(c in blend and own_weight(p, base[joints[c]], *blend[c]) <= 1.01 for c in children.get(j, []))
            if not ok:
                fail(f"vertex {p}: weight 1 on joint {j}, but it lies in the blend of that joint's base")
        else:
            fail(f"vertex {p}: weights {w}")
    print(f"ok {path}: {len(blend)} stem bases with a blend, {blended} vertices on two joints, as the formula")


def check_skinned(js, bin_, node, joints, rest, base, parent, want, scale, orders, path):
    """One skinned node: weights, rest pose, blend and shader attributes."""
    path = f"{path} {node['name']}"
    # every primitive's vertices (above 65,535 vertices each has its own window of them)
    attrs = {p["attributes"]["POSITION"]: p["attributes"] for p in js["meshes"][node["mesh"]]["primitives"]}
    pos, jw, ww = [], [], []
    for a in attrs.values():
        pos += accessor(js, bin_, a["POSITION"])
        jw += accessor(js, bin_, a["JOINTS_0"])
        ww += accessor(js, bin_, a["WEIGHTS_0"])
    worst = 0.0
    for p, jj, w in zip(pos, jw, ww):
        if abs(sum(w) - 1) > 1e-6 or any(x < 0 for x in w):
            fail(f"weights {w} do not sum to 1")
        if any(j >= len(joints) for j, x in zip(jj, w) if x > 0):
            fail(f"joint index {jj} out of range")
        q = [0.0, 0.0, 0.0]
        for j, x in zip(jj, w):
            if x:
                m = rest[j]
                for r in range(3):
                    q[r] += x * (m[r] * p[0] + m[r + 4] * p[1] + m[r + 8] * p[2] + m[r + 12])
        worst = max(worst, max(abs(q[r] - p[r]) for r in range(3)))
    if worst > 1e-5 * scale:
        fail(f"the skinned rest pose moves a vertex by {worst:.3g}")
    print(f"ok {path}: {len(pos)} vertices, weights sum to 1, rest pose = the unskinned mesh")
    check_blend(js, joints, base, parent, want, scale, pos, jw, ww, path)
    for name, lo, hi, integral in (("_BRANCH_LEVEL", 0, 65535, True), ("_PHASE", 0, 2 * math.pi, False),
                                   ("_STIFFNESS", 1e-9, 1, False)):
        vals = {v[0] for a in attrs.values() for v in accessor(js, bin_, a[name])}
        if any(not (lo <= v <= hi) for v in vals) or (integral and not vals <= {float(o) for o in orders}):
            fail(f"{name} values out of range: {sorted(vals)[:5]}")
    print(f"ok {path}: _BRANCH_LEVEL, _PHASE, _STIFFNESS in range")


def turned(idx, mode):
    """A primitive's triangles as a sorted list, each turned to start at its smallest index
    (its winding kept): a file without wind is quantized and written as strips."""
    tris = triangles([v[0] if isinstance(v, (list, tuple)) else v for v in idx], mode)
    if tris is None: fail(f"primitive mode {mode}: not triangles")
    return sorted(min(t[k:] + t[:k] for k in range(3)) for t in tris)


def check_levels(js, bin_, skinned, other):
    """Each level of the same chain written without wind has the same vertices as this
    one's (whose rest pose is its vertices); every level but the billboards is skinned."""
    ojs, obin = read_glb(other)
    mine = {n["name"]: (i, n) for i, n in enumerate(js["nodes"]) if "mesh" in n}
    count = 0
    for n in ojs["nodes"]:
        if "mesh" not in n or "_LOD" not in n["name"]:
            continue
        if n["name"] not in mine:
            fail(f"no node {n['name']} (of {other})")
        i, m = mine[n["name"]]
        billboards = "sylva_billboards" in n.get("extras", {})
        if (i in skinned) == billboards:
            fail(f"{n['name']}: {'skinned' if billboards else 'not skinned'}")
        for k, (mp, op) in enumerate(zip(js["meshes"][m["mesh"]]["primitives"], ojs["meshes"][n["mesh"]]["primitives"])):
            ours = accessor(js, bin_, mp["attributes"]["POSITION"])
            theirs = accessor(ojs, obin, op["attributes"]["POSITION"])
            tol = 0.0
            if ojs["accessors"][op["attributes"]["POSITION"]]["componentType"] != 5126:  # quantized: 16 bits
                theirs = [transform_point(trs(n), p) for p in theirs]
                tol = 2 * max(n.get("scale", [1])) / 32767
            if len(ours) != len(theirs) or any(abs(a - b) > tol for p, q in zip(ours, theirs) for a, b in zip(p, q)) or \
                    turned(accessor(js, bin_, mp["indices"]), mp.get("mode", 4)) != \
                    turned(accessor(ojs, obin, op["indices"]), op.get("mode", 4)):
                fail(f"{n['name']}: primitive {k}'s vertices or triangles differ from {other}'s")
        count += 1
    if count < 2:
        fail(f"{other}: {count} levels")
    print(f"ok {other}: {count} levels, each at rest as the skinned file's, {len(skinned)} skinned")


def transform_point(m, p):
    return tuple(m[r] * p[0] + m[r + 4] * p[1] + m[r + 8] * p[2] + m[r + 12] for r in range(3))


def instance_places(js, bin_):
    """Each instanced node's level (its root node's name), the node it hangs from, and the
    world places of its instances at rest."""
    nodes = js["nodes"]
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    def world(i):
        return matmul(world(parent[i]), trs(nodes[i])) if i in parent else trs(nodes[i])
    out = []
    for i, n in enumerate(nodes):
        ext = n.get("extensions", {}).get("EXT_mesh_gpu_instancing")
        if not ext:
            continue
        root = i
        while root in parent:
            root = parent[root]
        w = world(i)
        places = [transform_point(w, t) for t in accessor(js, bin_, ext["attributes"]["TRANSLATION"])]
        out.append((nodes[root]["name"], parent.get(i), places))
    return out


def matched(ours, theirs, tol):
    """Whether two lists of points are the same multiset, to tol."""
    if len(ours) != len(theirs):
        return False
    grid = {}
    for p in theirs:
        grid.setdefault(tuple(math.floor(c / tol) for c in p), []).append(p)
    for p in ours:
        cell = tuple(math.floor(c / tol) for c in p)
        hit = None
        for d in ((a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)):
            for q in grid.get(tuple(x + y for x, y in zip(cell, d)), []):
                if math.dist(p, q) <= tol:
                    hit = (tuple(x + y for x, y in zip(cell, d)), q)
                    break
            if hit:
                break
        if not hit:
            return False
        grid[hit[0]].remove(hit[1])
    return True


def check_instances(js, bin_, joints, base, parent, scale, other, path):
    """Instanced leaves of a skinned file: each set hangs from a joint (one plant) or from its
    level's copy of one (levels of detail: NAME_LODk_stemA under NAME_LODk, turned by the same
    sampler as joint stemA), the heavier joint of the blend at each leaf's place; at rest each
    level's leaves are where the file without wind has them."""
    nodes = js["nodes"]
    by_name = {nodes[j]["name"]: k for k, j in enumerate(joints)}
    sampler = {ch["target"]["node"]: ch["sampler"] for ch in js["animations"][0]["channels"]}
    blend = {k: (tuple(nodes[j]["extras"]["sylva_wind"]["blend"]), tuple(nodes[j]["extras"]["sylva_wind"]["direction"]))
             for k, j in enumerate(joints) if "blend" in nodes[j]["extras"]["sylva_wind"]}
    pjoint = {k: joints.index(parent[j]) if parent.get(j) in joints else -1 for k, j in enumerate(joints)}
    levels, total = {}, 0
    extent = max(1e-9, max(max(p[c] for p, _ in NODE_JOINT) - min(p[c] for p, _ in NODE_JOINT) for c in range(3)))
    tol = 1e-5 * extent
    at_node = {}
    for p, b in NODE_JOINT:
        at_node.setdefault(tuple(round(c / tol) for c in p), set()).add(key(b, scale))
    checked = 0
    for level, hang, places in instance_places(js, bin_):
        name = nodes[hang]["name"] if hang is not None else ""
        stem = "stem" + name.rsplit("_stem", 1)[1] if "_stem" in name else name
        if stem not in by_name:
            fail(f"instanced leaves of {level} hang from {name!r}, not a joint")
        k = by_name[stem]
        if hang != joints[k]:
            if name != f"{level}_{stem}" or sampler.get(hang) != sampler.get(joints[k]) or \
                    nodes[hang].get("translation") != nodes[joints[k]].get("translation"):
                fail(f"{name}: not {level}'s copy of joint {stem} turned by its sampler")
        for p in places:
            heavier = k not in blend or own_weight(p, base[joints[k]], *blend[k]) >= 127
            heavier = heavier or any(pjoint[c] == k and c in blend and own_weight(p, base[joints[c]], *blend[c]) <= 128
                                     for c in blend)
            if not heavier:
                fail(f"a leaf at {p} follows joint {stem}, the lighter of its blend")
            # a leaf at a skeleton node hangs from the joint of that node's stem (or, in the
            # blend at a child's base, from the child's parent joint)
            cell = tuple(round(c / tol) for c in p)
            near = set().union(*(at_node.get(tuple(x + d for x, d in zip(cell, dd)), set())
                                 for dd in ((a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1))))
            if near:
                checked += 1
                mine = {key(base[joints[k]], scale)} | {key(base[joints[c]], scale) for c in pjoint if pjoint[c] == k}
                if not near & mine:
                    fail(f"a leaf at {p} hangs from joint {stem}, not from its stem's")
        levels.setdefault(level, []).extend(places)
        total += len(places)
    if not total or (AT_NODES and checked != total):
        fail(f"{total} instanced leaves, {checked} of them at a skeleton node")
    if other:
        ojs, obin = read_glb(other)
        theirs = {}
        for level, _, places in instance_places(ojs, obin):
            theirs.setdefault(level, []).extend(places)
        if sorted(theirs) != sorted(levels):
            fail(f"levels with leaves {sorted(levels)}, {other} has {sorted(theirs)}")
        for level in levels:
            pts = theirs[level]
            extent = max(max(p[c] for p in pts) - min(p[c] for p in pts) for c in range(3))
            if not matched(levels[level], pts, 1e-4 * extent):  # their 16-bit quantization
                fail(f"{level}: the leaves at rest are not where {other} has them")
    print(f"ok {path}: {total} instanced leaves on {len(levels)} levels ({checked} at a node of their joint's stems), "
          f"each hanging from the joint it follows"
          + (f", at rest as {other}'s" if other else ""))


def main(path, csv_path, levels, seconds, same_as=None):
    js, bin_ = read_glb(path)
    want, orders = stems_of(csv_path, levels)
    skin = js["skins"][0]
    joints = skin["joints"]
    nodes = js["nodes"]
    if len(joints) != len(want):
        fail(f"{len(joints)} joints, want {len(want)} (stems of order < {levels})")
    # world transforms from the node hierarchy, at rest
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    world = {}
    def world_of(i):
        if i not in world:
            world[i] = matmul(world_of(parent[i]), trs(nodes[i])) if i in parent else trs(nodes[i])
        return world[i]
    base = {j: tuple(world_of(j)[12:15]) for j in joints}
    scale = max(1e-9, max(abs(c) for b in base.values() for c in b))
    got = sorted((key(base[j], scale), key(base[parent[j]], scale) if parent.get(j) in base else ()) for j in joints)
    exp = sorted((key(s["base"], scale), key(s["joint_parent"], scale)) for s in want)
    if got != exp:
        bad = sum(1 for a, b in zip(got, exp) if a != b)
        fail(f"joint bases or hierarchy differ from the skeleton's stems ({bad} of {len(got)})")
    print(f"ok {path}: {len(joints)} joints, one per stem of order < {levels}, hierarchy as the skeleton's")
    ibm = accessor(js, bin_, skin["inverseBindMatrices"])
    skinned = [i for i, n in enumerate(nodes) if n.get("skin") == 0]
    if not skinned or any(parent.get(i) is not None for i in skinned):
        fail("the skinned nodes should be root nodes")
    rest = []
    for j, m in zip(joints, ibm):
        e = matmul(world_of(j), list(m))
        if any(abs(e[k] - (1.0 if k % 5 == 0 else 0.0)) > 1e-5 * max(1, scale) for k in range(16)):
            fail(f"joint {j}: rest transform x inverse bind matrix is not the identity")
        rest.append(e)
    for node in skinned:
        check_skinned(js, bin_, nodes[node], joints, rest, base, parent, want, scale, orders, path)
    if same_as and any("_LOD" in n.get("name", "") for n in nodes):
        check_levels(js, bin_, skinned, same_as)
    if any("EXT_mesh_gpu_instancing" in n.get("extensions", {}) for n in nodes):
        check_instances(js, bin_, joints, base, parent, scale, same_as, path)
    anim = js["animations"]
    own = [ch for ch in anim[0]["channels"] if ch["target"]["node"] in joints] if len(anim) == 1 else []
    if len(anim) != 1 or sorted(ch["target"]["node"] for ch in own) != sorted(joints):
        fail("one animation with a channel per joint expected")
    copies = len(anim[0]["channels"]) - len(own)  # the levels' copies of the joints (check_instances)
    if copies % len(joints) or any(not nodes[ch["target"]["node"]]["name"].split("_")[-1].startswith("stem")
                                   for ch in anim[0]["channels"] if ch not in own):
        fail("channels for nodes that are neither joints nor a level's copies of them")
    amp_max = 0.0
    for ch in own:
        smp = anim[0]["samplers"][ch["sampler"]]
        node = ch["target"]["node"]
        if ch["target"]["path"] != "rotation":
            fail(f"channel {ch}")
        times = [t[0] for t in accessor(js, bin_, smp["input"])]
        if times[0] != 0 or abs(times[-1] - seconds) > 1e-6 or any(b <= a for a, b in zip(times, times[1:])):
            fail(f"key times {times[:3]} .. {times[-1]}")
        rot = accessor(js, bin_, smp["output"])
        amp = nodes[node]["extras"]["sylva_wind"]["amplitude"]
        if amp > BOUND + 1e-6:
            fail(f"joint {node}: amplitude {amp} above the model's bound {BOUND:.4f}")
        if rot[0] != rot[-1]:
            fail(f"joint {node}: the first and last keys differ: the loop does not close")
        for q in rot:
            n = math.sqrt(sum(c * c for c in q))
            angle = 2 * math.acos(min(1.0, abs(q[3]) / n))
            if abs(n - 1) > 1e-5 or angle > amp + 1e-5:
                fail(f"joint {node}: rotation {q} (angle {angle:.4f}) beyond its amplitude {amp:.4f}")
            amp_max = max(amp_max, angle)
    if amp_max <= 0:
        fail("nothing moves")
    print(f"ok {path}: {len(times)} keys over {seconds} s, loop closed, largest angle {amp_max:.3f} rad")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--leaves-at-nodes"]
    AT_NODES = len(args) < len(sys.argv) - 1
    if len(args) not in (4, 5):
        print(__doc__)
        sys.exit(2)
    main(args[0], args[1], int(args[2]), float(args[3]), *args[4:])
