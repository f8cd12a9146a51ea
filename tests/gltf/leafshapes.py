#!/usr/bin/env python3
"""Weber–Penn's named leaf shapes in the mesh (docs/weberpenn.md#leaf-shapes), read with the
glTF 2.0 and PNG specifications only (tests/lod/check.py's reader).

  leafshapes.py DIR LENGTH WIDTH SIDES SHAPE...

DIR holds, per SHAPE (a LeafShape word), SHAPE.glb (leaves meshed), SHAPE.csv (`sylva
skeleton`) and, but for sphere, SHAPE-cards.glb (--leaves cards). LENGTH and WIDTH: a leaf's
length and full width in metres (LeafScale / sqrt(LeafQuality) and LeafScaleX times it); SIDES:
the mesh's --sides. Checks: the leaf triangles' area (both faces drawn: half of it) is the
shape's area from its definition in the docs times the number of leaves; a card is the leaf's
length x width and its alpha covers the shape's share of it."""
import math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lod"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check  # noqa: E402  (read_glb, mesh_stats, read_png, accessor)

D, L, W, SIDES = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
results = []


def ok(name, cond, why):
    results.append(bool(cond))
    print(("ok " if cond else "FAIL ") + name + ("" if cond else ": " + why))


def polygon_in_ellipse(m):
    """A regular m-gon inscribed in the ellipse of the leaf (semi-axes L/2, W/2): per L x W."""
    return m / 2 * math.sin(2 * math.pi / m) / 4


PALM_HALF = [(0, 0), (0.1, 0.7), (0.3, 1), (0.6, 0.7), (1, 0)]  # (s, |t|), t = 1 is W/2


def area_per_lw(shape):
    if shape in ("0", "disc"):
        return polygon_in_ellipse(8)
    if shape.startswith("disc"):
        return polygon_in_ellipse(int(shape[4:]) + 2)
    if shape == "square":
        return 1.0
    if shape == "palm":  # two halves, each its trapezoids in (s, t) x (L, W/2); folding keeps it
        half = sum((b[0] - a[0]) * (a[1] + b[1]) / 2 for a, b in zip(PALM_HALF, PALM_HALF[1:]))
        return 2 * half / 2
    raise SystemExit("unknown shape " + shape)


def uv_sphere_area(r, sl, st):
    """The mesher's UV sphere: st stacks of sl planar trapezoids between parallels."""
    a = 0.0
    for i in range(st):
        p0, p1 = math.pi * i / st, math.pi * (i + 1) / st
        r0, r1, z0, z1 = r * math.sin(p0), r * math.sin(p1), -r * math.cos(p0), -r * math.cos(p1)
        c, s = math.cos(math.pi / sl), math.sin(math.pi / sl)
        h = math.hypot(z1 - z0, (r1 - r0) * c)
        a += sl * (r0 + r1) * s * h
    return a


def leaves_in(csv_path, kind):
    return sum(1 for line in open(csv_path) if line.rstrip().endswith("," + kind))


def card_alpha(js, bin_):
    """Mean alpha (0..1) of the leaf material's texture."""
    for mat in js["materials"]:
        if mat["name"].startswith("leaf") and mat.get("alphaMode") == "MASK":
            img = js["images"][js["textures"][mat["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]]
            v = js["bufferViews"][img["bufferView"]]
            data = bin_[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]
            w, h, ch, rows = check.read_png(data)
            return sum(row[x * ch + 3] for row in rows for x in range(w)) / (255.0 * w * h)
    return None


for shape in sys.argv[5:]:
    js, bin_ = check.read_glb(os.path.join(D, shape + ".glb"))
    leaf = sum(check.mesh_stats(js, bin_, m)[1] for m in range(len(js["meshes"])))
    if shape == "sphere":
        n = leaves_in(os.path.join(D, shape + ".csv"), "sphere")
        want = n * uv_sphere_area(L / 2, SIDES, max(SIDES // 2, 3))
        ok("sphere area", n > 0 and abs(leaf - want) <= 1e-3 * want,
           "%d spheres: %.6g m2, want %.6g" % (n, leaf, want))
        continue
    n = leaves_in(os.path.join(D, shape + ".csv"), "leaf")
    want = n * area_per_lw(shape) * L * W
    ok(shape + " area", n > 0 and abs(leaf / 2 - want) <= 1e-3 * want,
       "%d leaves: %.6g m2 a face, want %.6g" % (n, leaf / 2, want))
    js, bin_ = check.read_glb(os.path.join(D, shape + "-cards.glb"))
    cards = sum(check.mesh_stats(js, bin_, m, shown=False)[1] for m in range(len(js["meshes"])))
    ok(shape + " cards", abs(cards - n * L * W) <= 1e-3 * n * L * W,
       "%d cards: %.6g m2, want %d x length x width = %.6g" % (n, cards, n, n * L * W))
    cover = card_alpha(js, bin_)
    ok(shape + " card alpha", cover is not None and abs(cover - area_per_lw(shape)) <= 0.02,
       "alpha covers %s of the card, the shape %.4f" % (cover, area_per_lw(shape)))

print("leafshapes: %d passed, %d failed" % (sum(results), len(results) - sum(results)))
sys.exit(0 if all(results) else 1)
