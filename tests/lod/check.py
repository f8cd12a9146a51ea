#!/usr/bin/env python3
"""Independent reader for sylva's LOD .glb files and impostor PNGs (python3 stdlib only).

  check.py glb FILE LEVELS [--max-last-share S] [--billboards K] [--clusters-from K]
      node names NAME_LOD0..NAME_LODn, MSFT_lod ids on LOD0, screen coverages decreasing,
      triangle counts decreasing, leaf area of every geometric level within 15% of
      LOD0's (leaves thinned to 1/2, then 1/4, enlarged by 1/sqrt(keep); or gathered on
      cluster cards), the billboard level's embedded atlas 2K*view x view with an
      alpha-MASK material. The leaf area is what the leaves show: the area of the
      triangles of leaf materials, twice for a double-sided material (one face drawn from
      both sides), times the share of the texture an alpha-MASK material keeps (alpha >=
      1/2, decoded from the embedded PNG; such a triangle's UVs must lie in the unit
      square its texture covers). With --clusters-from K: levels K..n have their leaves on
      cluster cards (MASK, double-sided, the "leafcluster" image: alpha 0 at its corners
      and edges, leaves at its centre, between 10% and 90% of it kept) and no other leaf
      triangles, levels below K none.
  check.py modes FILE LEVELS MODE
      levels of detail with --leaves MODE (cards, instanced, instanced-cards): NAME_LODk
      nodes, MSFT_lod ids; cards: each level's leaf material alpha-tested (MASK) and
      double-sided, textured with the leafcard image; instanced modes: each level's leaves
      are child nodes with EXT_mesh_gpu_instancing whose instance counts fall by about half
      a level (Weber-Penn's leaf quality), nothing leafy in the levels' own meshes.
  check.py atlas COLOR NORMAL GRID VIEW
      PNG round trip: size GRID*VIEW square RGBA; alpha 0 at every view's corners (outside
      the framed bounding sphere), > 0 somewhere near every view's centre; normals unit
      length where the plant is.
  check.py compare NEW OLD [--alpha-mean A] [--alpha-far F] [--color-mean C]
      two colour atlases of one plant (RGBA, same size), e.g. one baked with fewer samples
      against one baked with more: the mean |alpha difference| over all pixels at most A
      (0..255), the share of pixels whose alpha differs by more than 64 (a quarter: one of
      four samples) at most F, the mean |colour difference| where both see the plant at
      most C. Prints the figures.
Prints "ok ..." lines; exits 1 with "FAIL ..." on the first failed check."""
import json, math, struct, sys, zlib
import os
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "gltf"))
from glbio import read_glb as _read_glb, triangles  # noqa: E402


def fail(msg):
    print("FAIL " + msg)
    sys.exit(1)


def read_glb(path):
    return _read_glb(path, fail)


def accessor(js, bin_, i):
    a = js["accessors"][i]
    v = js["bufferViews"][a["bufferView"]]
    off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[a["type"]] * a["count"]
    fmt = "<%d%s" % (n, {5126: "f", 5125: "I", 5123: "H", 5121: "B"}[a["componentType"]])
    return struct.unpack_from(fmt, bin_, off)


_fills = {}


def texture_fill(js, bin_, mat):
    """The share of an alpha-MASK material's texture kept by its cutoff (1 when opaque)."""
    if mat.get("alphaMode") != "MASK":
        return 1.0
    src = js["textures"][mat["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]
    if src not in _fills:
        v = js["bufferViews"][js["images"][src]["bufferView"]]
        w, h, ch, rows = read_png(bin_[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]])
        cut = 255 * mat.get("alphaCutoff", 0.5)
        _fills[src] = sum(r[4 * x + 3] >= cut for r in rows for x in range(w)) / (w * h) if ch == 4 else 1.0
    return _fills[src]


def as_list(idx, mode):
    """A primitive's indices as a flat triangle list (glbio.triangles: a strip's joins dropped)."""
    tris = triangles(idx, mode)
    if tris is None: fail(f"primitive mode {mode}: not triangles")
    return [v for t in tris for v in t]


def mesh_stats(js, bin_, m, shown=True):
    """Triangles, and the leaf area the leaf materials' triangles show (see the header);
    shown=False: the leaf triangles' own area, one face, whatever their texture and sides."""
    tris, leaf = 0, 0.0
    for p in js["meshes"][m]["primitives"]:
        idx = as_list(accessor(js, bin_, p["indices"]), p.get("mode", 4))
        tris += len(idx) // 3
        mat = js["materials"][p["material"]]
        if not mat["name"].startswith("leaf"):
            continue
        pos = accessor(js, bin_, p["attributes"]["POSITION"])
        k = texture_fill(js, bin_, mat) * (2 if mat.get("doubleSided") else 1) if shown else 1
        if mat.get("alphaMode") == "MASK":
            uv = accessor(js, bin_, p["attributes"]["TEXCOORD_0"])
            if any(not (-1e-6 <= uv[2 * i + c] <= 1 + 1e-6) for i in set(idx) for c in (0, 1)):
                fail(f"mesh {m}: an alpha-tested leaf's UVs leave the unit square")
        area = 0.0
        for t in range(0, len(idx), 3):
            a, b, c = (pos[3 * idx[t + k]:3 * idx[t + k] + 3] for k in range(3))
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            x = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            area += 0.5 * math.sqrt(sum(q * q for q in x))
        leaf += k * area
    return tris, leaf


def read_png(data):
    """RGB or RGBA 8-bit PNG, non-interlaced: (width, height, channels, rows of bytes)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail("not a PNG")
    at, idat, w = 8, b"", 0
    while at < len(data):
        n, kind = struct.unpack_from(">I4s", data, at)
        body = data[at + 8:at + 8 + n]
        if zlib.crc32(kind + body) != struct.unpack_from(">I", data, at + 8 + n)[0]:
            fail("PNG chunk CRC")
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, lace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or lace:
                fail("PNG: unexpected format")
            ch = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat)
    stride, rows, prev = w * ch, [], bytearray(w * ch)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, ch, rows


def check_clusters(js, bin_, nodes, n, first):
    """Levels first..n-1 draw leaves on cluster cards only; levels below, none."""
    for k in range(n):
        mats = leaf_materials(js, nodes[k]["mesh"])
        named = [js["images"][js["textures"][m["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]]
                 .get("name") if "baseColorTexture" in m["pbrMetallicRoughness"] else None for m in mats]
        if k < first:
            if "leafcluster" in named:
                fail(f"LOD{k} has cluster cards (clusters from LOD{first})")
            continue
        if not mats or any(nm != "leafcluster" for nm in named):
            fail(f"LOD{k}: leaves not all on cluster cards ({named})")
        for m in mats:
            if m.get("alphaMode") != "MASK" or not m.get("doubleSided"):
                fail(f"LOD{k}: cluster material not alpha-tested and double-sided")
        src = js["textures"][mats[0]["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]
        v = js["bufferViews"][js["images"][src]["bufferView"]]
        w, h, ch, rows = read_png(bin_[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]])
        if ch != 4 or any(rows[y][4 * x + 3] for y in (0, h - 1) for x in range(w)) or \
                any(rows[y][4 * x + 3] for y in range(h) for x in (0, w - 1)):
            fail(f"LOD{k}: cluster texture {w}x{h}x{ch}, alpha not 0 at its edges")
        if not any(rows[h // 2 + d][4 * (w // 2 + e) + 3] >= 128 for d in range(-h // 8, h // 8) for e in range(-w // 8, w // 8)):
            fail(f"LOD{k}: cluster texture empty near its centre")
        f = texture_fill(js, bin_, mats[0])
        if not 0.1 <= f <= 0.9:
            fail(f"LOD{k}: cluster texture keeps {f:.3f} of the card")


def check_glb(path, levels, max_last, billboards, clusters_from=-1):
    js, bin_ = read_glb(path)
    nodes = js["nodes"]
    n = levels + 1
    if len(nodes) != n:
        fail(f"{len(nodes)} nodes, want {n}")
    base = nodes[0]["name"][:-len("_LOD0")]
    for k, nd in enumerate(nodes):
        if nd["name"] != f"{base}_LOD{k}":
            fail(f"node {k} is named {nd['name']}")
    if "MSFT_lod" not in js.get("extensionsUsed", []):
        fail("MSFT_lod not in extensionsUsed")
    if nodes[0]["extensions"]["MSFT_lod"]["ids"] != list(range(1, n)):
        fail("MSFT_lod ids")
    cov = nodes[0]["extras"]["MSFT_screencoverage"]
    if len(cov) != n or any(not (cov[k] > cov[k + 1] > 0) for k in range(n - 1)):
        fail(f"screen coverages {cov}")
    if js["scenes"][0]["nodes"] != [0]:
        fail("the scene should show LOD0 only")
    stats = [mesh_stats(js, bin_, nd["mesh"]) for nd in nodes]
    tris = [t for t, _ in stats]
    if any(tris[k + 1] >= tris[k] for k in range(n - 1)):
        fail(f"triangles do not decrease: {tris}")
    if max_last and tris[-1] > max_last * tris[0]:
        fail(f"LOD{n - 1} has {tris[-1]} triangles, more than {max_last} of LOD0's {tris[0]}")
    geometric = n - (1 if billboards else 0)
    area0 = stats[0][1]
    for k in range(1, geometric):  # thinned to >= 1/4, the survivors enlarged to make up for it
        if area0 > 0 and abs(stats[k][1] - area0) > 0.15 * area0:
            fail(f"LOD{k} leaf area {stats[k][1]:.4g}, want {area0:.4g} +-15% (LOD0's)")
    if billboards:
        last = js["meshes"][nodes[-1]["mesh"]]
        mat = js["materials"][last["primitives"][0]["material"]]
        if mat.get("alphaMode") != "MASK" or tris[-1] != 4 * billboards:
            fail("billboard level: material or triangle count")
        img = js["images"][js["textures"][mat["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]]
        v = js["bufferViews"][img["bufferView"]]
        w, h, ch, rows = read_png(bin_[v["byteOffset"]:v["byteOffset"] + v["byteLength"]])
        if ch != 4 or w != 2 * billboards * h:
            fail(f"billboard atlas {w}x{h}x{ch}")
        if any(r[3] for r in (rows[0][:4 * w],)) or not any(rows[h // 2][4 * x + 3] for x in range(w)):
            fail("billboard atlas alpha: not 0 at the top row or nothing across the middle")
    if clusters_from >= 0:
        check_clusters(js, bin_, nodes, geometric, clusters_from)
    print(f"ok {path}: {n} levels, triangles {tris}, leaf area {[round(a / area0, 3) if area0 else 0 for _, a in stats]}")


def leaf_materials(js, mesh):
    return [js["materials"][p["material"]] for p in js["meshes"][mesh]["primitives"]
            if js["materials"][p["material"]]["name"].startswith("leaf")]


def card_material_ok(js, mat):
    if mat.get("alphaMode") != "MASK" or not mat.get("doubleSided"):
        return False
    tex = mat["pbrMetallicRoughness"].get("baseColorTexture")
    return tex is not None and js["images"][js["textures"][tex["index"]]["source"]]["name"] == "leafcard"


def check_modes(path, levels, mode):
    js, _ = read_glb(path)
    nodes = js["nodes"]
    n = levels + 1
    base = nodes[0]["name"][:-len("_LOD0")]
    if [nd["name"] for nd in nodes[:n]] != [f"{base}_LOD{k}" for k in range(n)]:
        fail(f"{path}: nodes {[nd['name'] for nd in nodes[:n]]}")
    if nodes[0]["extensions"]["MSFT_lod"]["ids"] != list(range(1, n)) or js["scenes"][0]["nodes"] != [0]:
        fail(f"{path}: MSFT_lod ids or scene")
    counts = []
    for k in range(n):
        nd = nodes[k]
        own = leaf_materials(js, nd["mesh"]) if "mesh" in nd else []
        if mode == "cards":
            if not own or not all(card_material_ok(js, m) for m in own):
                fail(f"{path}: LOD{k}'s leaves are not alpha-tested double-sided cards")
            continue
        if own:
            fail(f"{path}: LOD{k} has leaves in its own mesh with --leaves {mode}")
        c = 0
        for ch in nd.get("children", []):
            inst = nodes[ch]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]
            c += js["accessors"][inst["TRANSLATION"]]["count"]
            if mode == "instanced-cards" and not all(card_material_ok(js, m) for m in leaf_materials(js, nodes[ch]["mesh"])):
                fail(f"{path}: LOD{k}'s instanced cards are not alpha-tested double-sided")
        counts.append(c)
    if mode != "cards":
        if "EXT_mesh_gpu_instancing" not in js.get("extensionsUsed", []):
            fail(f"{path}: EXT_mesh_gpu_instancing not in extensionsUsed")
        for k in range(1, n):
            if not (0.35 * counts[k - 1] <= counts[k] <= 0.65 * counts[k - 1]):
                fail(f"{path}: leaf instances per level {counts}: not about half a level")
    print(f"ok {path}: {n} levels with --leaves {mode}" + (f", instances {counts}" if counts else ""))


def check_atlas(color, normal, grid, view):
    for path, is_normal in ((color, False), (normal, True)):
        w, h, ch, rows = read_png(open(path, "rb").read())
        if (w, h, ch) != (grid * view, grid * view, 4):
            fail(f"{path}: {w}x{h}x{ch}, want {grid * view} square RGBA")
        if is_normal:
            bad = 0
            for y in range(0, h, 7):
                for x in range(0, w, 7):
                    p = rows[y][4 * x:4 * x + 4]
                    if p == b"\0\0\0\0":
                        continue
                    l = math.sqrt(sum((c / 127.5 - 1) ** 2 for c in p[:3]))
                    bad += abs(l - 1) > 0.05
            if bad:
                fail(f"{path}: {bad} normals are not unit length")
            continue
        for row in range(grid):
            for col in range(grid):
                x0, y0 = col * view, row * view
                for cx, cy in ((0, 0), (view - 1, 0), (0, view - 1), (view - 1, view - 1)):
                    if rows[y0 + cy][4 * (x0 + cx) + 3]:
                        fail(f"{path}: view ({col},{row}) has alpha at a corner")
                r = view // 4
                if not any(rows[y][4 * x + 3] for y in range(y0 + view // 2 - r, y0 + view // 2 + r)
                           for x in range(x0 + view // 2 - r, x0 + view // 2 + r)):
                    fail(f"{path}: view ({col},{row}) is empty near its centre")
    print(f"ok {color}: {grid}x{grid} views of {view}, alpha 0 outside the plant, unit normals")


def compare_atlas(new, old, alpha_mean, alpha_far, color_mean):
    wn, hn, cn, rn = read_png(open(new, "rb").read())
    wo, ho, co, ro = read_png(open(old, "rb").read())
    if (wn, hn, cn) != (wo, ho, co) or cn != 4:
        fail(f"{new}: {wn}x{hn}x{cn} against {old}: {wo}x{ho}x{co}")
    da = far = dc = both = 0
    for a, b in zip(rn, ro):
        for i in range(0, len(a), 4):
            d = abs(a[i + 3] - b[i + 3])
            da += d
            far += d > 64
            if a[i + 3] and b[i + 3]:
                both += 1
                dc += abs(a[i] - b[i]) + abs(a[i + 1] - b[i + 1]) + abs(a[i + 2] - b[i + 2])
    n = wn * hn
    am, fs, cm = da / n, far / n, dc / (3 * both) if both else 0.0
    print(f"{new} against {old}: mean |alpha difference| {am:.3f}, share > 64 {fs:.5f}, mean |colour difference| {cm:.3f}")
    if am > alpha_mean or fs > alpha_far or cm > color_mean:
        fail(f"{new}: beyond the tolerance (alpha mean {alpha_mean}, share {alpha_far}, colour {color_mean})")


if __name__ == "__main__":
    a = sys.argv[1:]
    if a and a[0] == "glb":
        opt = dict(zip(a[3::2], a[4::2]))
        check_glb(a[1], int(a[2]), float(opt.get("--max-last-share", 0)), int(opt.get("--billboards", 0)),
                  int(opt.get("--clusters-from", -1)))
    elif a and a[0] == "modes":
        check_modes(a[1], int(a[2]), a[3])
    elif a and a[0] == "atlas":
        check_atlas(a[1], a[2], int(a[3]), int(a[4]))
    elif a and a[0] == "compare":
        opt = dict(zip(a[3::2], a[4::2]))
        compare_atlas(a[1], a[2], float(opt.get("--alpha-mean", 255)), float(opt.get("--alpha-far", 1)),
                      float(opt.get("--color-mean", 255)))
    else:
        print(__doc__)
        sys.exit(2)
