#!/usr/bin/env python3
"""Independent checks of Sylva's leaf modes, reading the .glb files with nothing but the
glTF 2.0 and EXT_mesh_gpu_instancing specifications (and the PNG one, via zlib).

  leaves.py DIR   (DIR holds the files tests/run-leaves made)

One line per check, "ok NAME" or "FAIL NAME: why"; the last line counts them."""
import json, math, os, struct, sys, zlib
from glbio import triangles as mode_triangles

D = sys.argv[1]
results = []


def check(name, cond, why=""):
    results.append(bool(cond))
    print(("ok " if cond else "FAIL ") + name + ("" if cond else ": " + why))


def glb(path):
    b = open(path, "rb").read()
    magic, version, total = struct.unpack_from("<III", b, 0)
    assert magic == 0x46546C67 and version == 2 and total == len(b)
    jlen, jtype = struct.unpack_from("<II", b, 12)
    js = json.loads(b[20:20 + jlen])
    blen, _ = struct.unpack_from("<II", b, 20 + jlen)
    return js, b[28 + jlen:28 + jlen + blen]


SIZE = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
FMT = {5126: "f", 5125: "I", 5123: "H", 5122: "h", 5120: "b"}
NORM = {5122: 32767.0, 5120: 127.0, 5123: 65535.0}  # KHR_mesh_quantization's normalized types


def accessor(js, bin_, i):
    a = js["accessors"][i]
    v = js["bufferViews"][a["bufferView"]]
    k, f = SIZE[a["type"]], FMT[a["componentType"]]
    off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    stride = v.get("byteStride", 0)
    if stride:  # padded elements: read each one where it starts
        flat = []
        for j in range(a["count"]):
            flat.extend(struct.unpack_from("<%d%s" % (k, f), bin_, off + j * stride))
    else:
        flat = struct.unpack_from("<%d%s" % (a["count"] * k, f), bin_, off)
    if a.get("normalized"):
        flat = [max(x / NORM[a["componentType"]], -1.0) for x in flat]
    return [tuple(flat[j * k:(j + 1) * k]) for j in range(a["count"])] if k > 1 else list(flat)


def leaf_material(js, m):
    return js["materials"][m]["name"].startswith("leaf")


def rotate(q, p):  # unit quaternion (x, y, z, w) applied to p
    x, y, z, w = q
    tx, ty, tz = 2 * (y * p[2] - z * p[1]), 2 * (z * p[0] - x * p[2]), 2 * (x * p[1] - y * p[0])
    return (p[0] + w * tx + y * tz - z * ty, p[1] + w * ty + z * tx - x * tz, p[2] + w * tz + x * ty - y * tx)


def leaf_vertices(js, bin_, mesh):
    """Positions of the vertices the leaf primitives of a mesh use, in vertex order (each
    primitive's own: above 65,535 vertices a group is cut into primitives of their own windows)."""
    used = {}
    for p in js["meshes"][mesh]["primitives"]:
        if leaf_material(js, p["material"]):
            a = js["accessors"][p["attributes"]["POSITION"]]
            pos = accessor(js, bin_, p["attributes"]["POSITION"])
            stride = js["bufferViews"][a["bufferView"]].get("byteStride") or 4 * SIZE[a["type"]]
            first = a.get("byteOffset", 0) // stride  # the window's first vertex in the mesh
            for i in accessor(js, bin_, p["indices"]):
                used[first + i] = pos[i]
    return [used[k] for k in sorted(used)]


def instances(js, bin_):
    """(prototype leaf positions, T, R, S) per instanced node (no SCALE: 1, as the
    extension says)."""
    out = []
    for n in js["nodes"]:
        ext = n.get("extensions", {}).get("EXT_mesh_gpu_instancing")
        if ext:
            at = ext["attributes"]
            T = accessor(js, bin_, at["TRANSLATION"])
            S = accessor(js, bin_, at["SCALE"]) if "SCALE" in at else [(1.0, 1.0, 1.0)] * len(T)
            out.append((leaf_vertices(js, bin_, n["mesh"]), T, accessor(js, bin_, at["ROTATION"]), S))
    return out


def png_rgba(data):
    """Decode an 8-bit RGBA, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    p, idat, w = 8, b"", 0
    while p < len(data):
        n, t = struct.unpack_from(">I4s", data, p)
        c = data[p + 8:p + 8 + n]
        if t == b"IHDR":
            w, h, depth, ctype = struct.unpack_from(">IIBB", c)
            assert depth == 8 and ctype == 6, "not RGBA8"
        elif t == b"IDAT":
            idat += c
        p += 12 + n
    raw, rows, prev, bpp, q = zlib.decompress(idat), [], bytearray(w * 4), 4, 0
    for _ in range(h):
        f, line = raw[q], bytearray(raw[q + 1:q + 1 + w * 4])
        q += 1 + w * 4
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows


def skeleton_leaves(path):
    return sum(1 for line in open(path) if line.rstrip().endswith(",leaf"))


def farthest(a, b, tol):
    """The largest distance (max norm) from a point of a to its nearest point of b, looked up
    in a grid of cells of size tol: the writer reorders vertices for the GPU's caches
    (meshoptimizer), so the two lists hold the same points in different orders."""
    grid = {}
    for q in b:
        grid.setdefault(tuple(int(math.floor(c / tol)) for c in q), []).append(q)
    worst = 0.0
    for q in a:
        cell = tuple(int(math.floor(c / tol)) for c in q)
        best = math.inf
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for r in grid.get((cell[0] + dx, cell[1] + dy, cell[2] + dz), ()):
                        best = min(best, max(abs(q[k] - r[k]) for k in range(3)))
        worst = max(worst, best)
    return worst


# 1. instances: count, and the transforms put the prototype where the copied leaves are
copied_js, copied_bin = glb(os.path.join(D, "mesh.glb"))
inst_js, inst_bin = glb(os.path.join(D, "instanced.glb"))
sets = instances(inst_js, inst_bin)
nleaves = skeleton_leaves(os.path.join(D, "skeleton.csv"))
count = sum(len(t) for _, t, _, _ in sets)
check("instance count equals the skeleton's leaves", count == nleaves > 0, "%d instances, %d leaves" % (count, nleaves))
check("extension in extensionsUsed, not extensionsRequired",
      "EXT_mesh_gpu_instancing" in inst_js.get("extensionsUsed", []) and
      "EXT_mesh_gpu_instancing" not in inst_js.get("extensionsRequired", []))

def check_placed(name, copied_js, copied_bin, inst_js, inst_bin):
    """The instances put the prototype where the copied leaves are."""
    # the plant node's transform (KHR_mesh_quantization: a translation and a uniform scale)
    # applies to its children, the instance sets
    root = inst_js["nodes"][0]
    T0, k0 = root.get("translation", [0, 0, 0]), root.get("scale", [1, 1, 1])[0]
    quantized = "KHR_mesh_quantization" in inst_js.get("extensionsRequired", [])
    moved = []
    for proto, T, R, S in instances(inst_js, inst_bin):
        for t, r, s in zip(T, R, S):
            check_unit = abs(math.sqrt(sum(c * c for c in r)) - 1) < (1e-5 if not quantized else 1e-4)
            if not check_unit: moved = None; break
            moved += [tuple(T0[k] + k0 * (t[k] + v[k]) for k in range(3))
                      for v in (rotate(r, (p[0] * s[0], p[1] * s[1], p[2] * s[2])) for p in proto)]
        if moved is None: break
    copied = leaf_vertices(copied_js, copied_bin, 0)
    scale = max(max(abs(c) for c in p) for p in copied) if copied else 1
    # quantized: translations, rotations and scales are 16-bit steps of the plant's half size k0
    tol = 1e-5 * scale + (4 * k0 / 32767 if quantized else 0)
    err = max(farthest(moved, copied, tol), farthest(copied, moved, tol)) if moved and copied else math.inf
    check(name + "instances reproduce the copied leaves' vertices", moved and len(moved) == len(copied) and err <= tol,
          "%s moved, %d copied, max error %g" % (len(moved) if moved else "no", len(copied), err))


check_placed("", copied_js, copied_bin, inst_js, inst_bin)
check("instanced file has no copied leaves", not leaf_vertices(inst_js, inst_bin, 0))

# 2. the size of the leaves: instance data and the prototype against the copied leaves
def leaf_bytes(js, mesh):
    n = 0
    for p in js["meshes"][mesh]["primitives"]:
        if leaf_material(js, p["material"]):
            n += js["accessors"][p["indices"]]["count"] * (2 if js["accessors"][p["indices"]]["componentType"] == 5123 else 4)
    return n + len(leaf_vertices(js, copied_bin if js is copied_js else inst_bin, mesh)) * 32
copied_leaf = leaf_bytes(copied_js, 0)
inst_leaf = sum(len(p) * 32 for p, _, _, _ in sets) + sum(
    inst_js["bufferViews"][inst_js["accessors"][a]["bufferView"]]["byteLength"]
    for n in inst_js["nodes"] for a in n.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes", {}).values())
check("instanced leaves take <= 1/4 of the copied leaves' bytes", inst_leaf * 4 <= copied_leaf,
      "%d vs %d" % (inst_leaf, copied_leaf))
print("note: files %d (copied) and %d (instanced) bytes, ratio %.3f" % (
    os.path.getsize(os.path.join(D, "mesh.glb")), os.path.getsize(os.path.join(D, "instanced.glb")),
    os.path.getsize(os.path.join(D, "instanced.glb")) / os.path.getsize(os.path.join(D, "mesh.glb"))))

# 3. cards: material, one quad per leaf, and the alpha is the leaf's silhouette
def ovate(s): return math.sin(math.pi * s ** 0.75) ** 0.9
for name, instanced in (("cards.glb", False), ("instanced-cards.glb", True)):
    js, bin_ = glb(os.path.join(D, name))
    mats = [m for m in js["materials"] if m["name"].startswith("leaf")]
    check(name + ": leaf material is alpha-tested and double-sided",
          mats and all(m.get("alphaMode") == "MASK" and 0 < m.get("alphaCutoff", 0.5) < 1 and m.get("doubleSided")
                       for m in mats))
    if instanced:
        protos = [p for p, _, _, _ in instances(js, bin_)]
        check(name + ": the prototype is one quad", protos and all(len(p) == 4 for p in protos))
    else:
        check(name + ": one quad per leaf", len(leaf_vertices(js, bin_, 0)) == 4 * nleaves)
    tex = js["materials"][js["materials"].index(mats[0])]["pbrMetallicRoughness"]["baseColorTexture"]["index"]
    view = js["bufferViews"][js["images"][js["textures"][tex]["source"]]["bufferView"]]
    w, h, rows = png_rgba(bin_[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])
    if name == "cards.glb":
        # every texel whose square lies wholly outside the ovate outline is 0; wholly inside, 255
        bad = 0
        for y in range(h):
            s0, s1 = y / h, (y + 1) / h
            ws = [ovate(s0 + (s1 - s0) * i / 8) for i in range(9)]
            lo, hi = min(ws) - 0.02, max(ws) + 0.02  # the outline's range over the row, with slack
            for x in range(w):
                a = rows[y][4 * x + 3]
                t0, t1 = abs(2 * x / w - 1), abs(2 * (x + 1) / w - 1)
                tn, tf = (0 if (2 * x / w - 1) * (2 * (x + 1) / w - 1) <= 0 else min(t0, t1)), max(t0, t1)
                if tn > hi and a != 0: bad += 1
                if tf < lo and 0 < s0 and s1 < 1 and a != 255: bad += 1
        check("cards: alpha 0 outside the ovate outline, 255 inside", bad == 0, "%d texels wrong" % bad)
        area = sum(ovate((i + 0.5) / 2000) for i in range(2000)) / 2000  # of the card, by quadrature
        cover = sum(r[4 * x + 3] for r in rows for x in range(w)) / (255 * w * h)
        check("cards: coverage is the ovate leaf's area", abs(cover - area) < 0.01, "%.4f vs %.4f" % (cover, area))

# 4. indices: 16-bit in every primitive; above 65,535 vertices a group is cut into primitives
# that each use a window of at most 65,535 vertices, and put together they are the same
# triangles as the OBJ writer's one list of the same mesh
def windows(js, bin_, mesh):
    """Per primitive: (material, its index type, its window's first vertex and size, its
    triangles as indices of the whole mesh)."""
    out = []
    for p in js["meshes"][mesh]["primitives"]:
        a = js["accessors"][p["attributes"]["POSITION"]]
        stride = js["bufferViews"][a["bufferView"]].get("byteStride") or 4 * SIZE[a["type"]]
        first = a.get("byteOffset", 0) // stride
        out.append((p["material"], js["accessors"][p["indices"]]["componentType"], first, a["count"],
                    [first + i for i in accessor(js, bin_, p["indices"])]))
    return out


def obj_faces(path):
    """Positions and, per material in order, the triangles (0-based) of an OBJ file."""
    pos, faces, mat = [], {}, None
    for line in open(path):
        w = line.split()
        if not w: continue
        if w[0] == "v": pos.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "usemtl": mat = w[1]
        elif w[0] == "f": faces.setdefault(mat, []).extend(int(x.split("/")[0]) - 1 for x in w[1:4])
    return pos, faces


for name in ("u16.glb", "big.glb", "big-instanced.glb"):
    js, bin_ = glb(os.path.join(D, name))
    prims = [w for m in range(len(js["meshes"])) for w in windows(js, bin_, m)]
    ok = all(t == 5123 and n <= 65535 and all(first <= i < first + n for i in tri) for _, t, first, n, tri in prims)
    nv = max(first + n for _, _, first, n, _ in windows(js, bin_, 0))
    groups = len({mat for mat, _, _, _, _ in windows(js, bin_, 0)})
    split = len(windows(js, bin_, 0)) > groups
    check("%s: %d vertices, 16-bit indices within each primitive's window, %s" %
          (name, nv, "cut into primitives" if nv > 65535 else "one primitive a group"),
          ok and split == (nv > 65535) and (nv <= 65535) == (name == "u16.glb"))
js, bin_ = glb(os.path.join(D, "big.glb"))
opos, ofaces = obj_faces(os.path.join(D, "big.obj"))
gpos = {}
tris = {}
base = 0  # a scene (hedge.syl) is one mesh per object, numbered on in the OBJ as in the meshes' order
for mesh in js["meshes"]:
    top = base
    for p in mesh["primitives"]:
        a = js["accessors"][p["attributes"]["POSITION"]]
        first = base + a.get("byteOffset", 0) // (js["bufferViews"][a["bufferView"]].get("byteStride") or 12)
        for i, q in enumerate(accessor(js, bin_, p["attributes"]["POSITION"])): gpos[first + i] = q
        top = max(top, first + a["count"])
        tris.setdefault(js["materials"][p["material"]]["name"], []).extend(first + i for i in accessor(js, bin_, p["indices"]))
    base = top
size = max(abs(c) for q in opos for c in q)
same_pos = len(gpos) == len(opos) and all(max(abs(gpos[i][k] - opos[i][k]) for k in range(3)) <= 1e-6 * size
                                          for i in range(len(opos)))
check("big.glb: its primitives put together are the OBJ's triangles", tris == ofaces and same_pos,
      "%d/%d triangles, positions %s" % (sum(len(t) for t in tris.values()) // 3,
                                         sum(len(t) for t in ofaces.values()) // 3, "same" if same_pos else "differ"))

# 5. a Weber-Penn palm (leaves of one size): the size goes into the prototype (no SCALE), the
# instances still put it where the copied leaves are, the instanced file is at most a quarter
# of the copied one, and its quantized branches are the float ones to half a 16-bit step of
# the node's scale k (positions: k / 65,534, with float rounding), normals to 1/254, and UVs
# (16-bit steps of their range, given back by the bark material's KHR_texture_transform) to
# half a step of that range
def bark_vertices(js, bin_):
    """{vertex of the mesh: (position, normal, uv as the texture sees it)} of the bark
    primitives of mesh 0, and the largest half step of the UVs (0: floats)."""
    out, half = {}, 0.0
    for p in js["meshes"][0]["primitives"]:
        mat = js["materials"][p["material"]]
        if mat["name"].startswith("bark"):
            a = js["accessors"][p["attributes"]["POSITION"]]
            first = a.get("byteOffset", 0) // (js["bufferViews"][a["bufferView"]].get("byteStride") or 12)
            P, N = accessor(js, bin_, p["attributes"]["POSITION"]), accessor(js, bin_, p["attributes"]["NORMAL"])
            T = accessor(js, bin_, p["attributes"]["TEXCOORD_0"])
            tt = mat["pbrMetallicRoughness"]["baseColorTexture"].get("extensions", {}).get("KHR_texture_transform", {})
            o, s = tt.get("offset", [0, 0]), tt.get("scale", [1, 1])
            if js["accessors"][p["attributes"]["TEXCOORD_0"]].get("normalized"):
                half = max(half, max(s) / 131070)
            for i in set(accessor(js, bin_, p["indices"])):
                out[first + i] = (P[i], N[i], (o[0] + s[0] * T[i][0], o[1] + s[1] * T[i][1]))
    return out, half


pm_js, pm_bin = glb(os.path.join(D, "palm-mesh.glb"))
pi_js, pi_bin = glb(os.path.join(D, "palm-instanced.glb"))
inst_nodes = [n for n in pi_js["nodes"] if "EXT_mesh_gpu_instancing" in n.get("extensions", {})]
check("palm: leaves of one size, sets without SCALE",
      inst_nodes and all("SCALE" not in n["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] for n in inst_nodes))
check_placed("palm: ", pm_js, pm_bin, pi_js, pi_bin)
sizes = [os.path.getsize(os.path.join(D, f)) for f in ("palm-mesh.glb", "palm-instanced.glb")]
check("palm: the instanced file is at most 1/4 of the copied one", sizes[1] * 4 <= sizes[0],
      "%d vs %d bytes" % (sizes[1], sizes[0]))
(fl, _), (qu, half) = bark_vertices(pm_js, pm_bin), bark_vertices(pi_js, pi_bin)
root = pi_js["nodes"][0]
T0, k0 = root["translation"], root["scale"][0]
ep = max((max(abs(T0[k] + k0 * qu[i][0][k] - fl[i][0][k]) for k in range(3)) for i in fl if i in qu), default=math.inf)
en = max((max(abs(qu[i][1][k] - fl[i][1][k]) for k in range(3)) for i in fl if i in qu), default=math.inf)
check("palm: quantized branch vertices are the float ones (positions within k/65534, normals 1/254)",
      fl and fl.keys() == qu.keys() and ep <= k0 * (1 / 65534 + 1e-6) and en <= 1 / 254,
      "%d/%d vertices, position error %g (bound %g), normal error %g" % (len(qu), len(fl), ep, k0 / 65534, en))
eu = max((max(abs(qu[i][2][k] - fl[i][2][k]) for k in range(2)) for i in fl if i in qu), default=math.inf)
check("palm: bark UVs are 16-bit, KHR_texture_transform gives them back within half a step",
      half > 0 and "KHR_texture_transform" in pi_js.get("extensionsRequired", []) and eu <= half * (1 + 1e-3) + 1e-6,
      "UV error %g (bound %g)" % (eu, half))


def triangles(js, bin_, p, first):
    """A primitive's triangles (indices of the whole mesh, each turned to start at its least
    index, winding kept) by glTF's rule for its mode: 4 a list, 5 a strip whose triangle i is
    (v_i, v_i+1+i%2, v_i+2-i%2); triangles without area (a strip's joins) dropped."""
    tris = mode_triangles([first + i for i in accessor(js, bin_, p["indices"])], p.get("mode", 4))
    if tris is None: return None
    return [min(t[k:] + t[:k] for k in range(3)) for t in tris]


def bark_triangles(js, bin_):
    out = []
    for p in js["meshes"][0]["primitives"]:
        if js["materials"][p["material"]]["name"].startswith("bark"):
            a = js["accessors"][p["attributes"]["POSITION"]]
            first = a.get("byteOffset", 0) // (js["bufferViews"][a["bufferView"]].get("byteStride") or 12)
            out.extend(triangles(js, bin_, p, first) or [])
    return sorted(out)


ft, qt = bark_triangles(pm_js, pm_bin), bark_triangles(pi_js, pi_bin)
check("palm: the quantized file's bark is triangle strips that are the float file's list of triangles",
      all(p.get("mode") == 5 for p in pi_js["meshes"][0]["primitives"]) and ft and qt == ft,
      "%d/%d triangles" % (len(qt), len(ft)))
print("note: palm files %d (copied) and %d (instanced) bytes, ratio %.3f" % (sizes[0], sizes[1], sizes[1] / sizes[0]))

print("leaves: %d passed, %d failed" % (sum(results), len(results) - sum(results)))
sys.exit(0 if all(results) else 1)
