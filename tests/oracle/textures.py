#!/usr/bin/env python3
"""Read the textures Sylva wrote, with the Python standard library only (tests/cases/textures.test).

  textures.py glb FILE   each image: its name, MIME type and whether its bytes equal the file
                         of that name in the working folder; each material: its texture's
                         image, alpha mode, sampler wrap and base colour factor
  textures.py cards FILE each node's alpha-tested (MASK) materials: the node's name and the
                         share of its texture's texels with alpha 128 or more (a card's outline)
  textures.py vt FILE    an OBJ's largest u, and its v range (OBJ writes 1 - v)
  textures.py solid FILE R G B A   writes a 16 x 16 RGBA PNG of one colour (zlib, no filter)
  textures.py tint PLAIN.png TEXTURED.png R G B LEAST
                         of the pixels where the two renders differ (the tree), whether at
                         least the fraction LEAST in TEXTURED are of the hue of (R, G, B) (the
                         component largest there at least twice each other one), and none
                         in PLAIN; exit 1 with the counts when not
"""

import json
import os
import struct
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import png, pixel  # noqa: E402  (tests/oracle/inspect.py)


def read_glb(path):
    """The JSON chunk of a .glb, parsed, and its binary chunk's bytes."""
    d = open(path, "rb").read()
    n = struct.unpack("<I", d[12:16])[0]
    return json.loads(d[20:20 + n]), d[20 + n + 8:]


def glb(path):
    j, b = read_glb(path)
    for im in j["images"]:
        v = j["bufferViews"][im["bufferView"]]
        at = v.get("byteOffset", 0)
        same = b[at:at + v["byteLength"]] == open(im["name"], "rb").read()
        print(im["name"], im["mimeType"], "same bytes" if same else "differ")
    for m in j["materials"]:
        t = m["pbrMetallicRoughness"].get("baseColorTexture")
        tex = j["textures"][t["index"]] if t else None
        wrap = j["samplers"][tex["sampler"]]["wrapS"] if tex else None
        print(m["name"], j["images"][tex["source"]]["name"] if tex else "-", m.get("alphaMode", "OPAQUE"),
              "repeat" if wrap == 10497 else "clamp", m["pbrMetallicRoughness"]["baseColorFactor"][:3])


def cards(path):
    j, b = read_glb(path)
    for node in j["nodes"]:
        if "mesh" not in node:
            continue
        for p in j["meshes"][node["mesh"]]["primitives"]:
            m = j["materials"][p["material"]]
            if m.get("alphaMode") != "MASK":
                continue
            im = j["images"][j["textures"][m["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]]
            v = j["bufferViews"][im["bufferView"]]
            at = v.get("byteOffset", 0)
            with tempfile.NamedTemporaryFile(suffix=".png") as f:
                f.write(b[at:at + v["byteLength"]])
                f.flush()
                w, h, bpp, rows = png(f.name)
            inside = sum(1 for r in rows for x in range(w) if r[x * bpp + 3] >= 128)
            print(node.get("name", "-"), "%.4f" % (inside / (w * h)))


def vt(path):
    uv = [tuple(map(float, l.split()[1:3])) for l in open(path) if l.startswith("vt ")]
    print("u up to %g, v over %g" % (max(u for u, v in uv), max(v for u, v in uv) - min(v for u, v in uv)))


def solid(path, r, g, b, a):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    rows = b"".join(b"\0" + bytes([int(r), int(g), int(b), int(a)]) * 16 for _ in range(16))
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 16, 16, 8, 6, 0, 0, 0)) +
                           chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def tint(plain, textured, r, g, b, least):
    a, t = png(plain), png(textured)
    rgb = (float(r), float(g), float(b))
    k = max(range(3), key=lambda c: rgb[c])

    def of_hue(p):
        return all(p[k] >= 2 * p[c] for c in range(3) if c != k) and p[k] > 20

    tree = [(x, y) for y in range(a[1]) for x in range(a[0]) if pixel(a, x, y) != pixel(t, x, y)]
    hue_t = sum(of_hue(pixel(t, x, y)) for x, y in tree)
    hue_a = sum(of_hue(pixel(a, x, y)) for x, y in tree)
    if len(tree) < 20 or hue_t < float(least) * len(tree) or hue_a:
        print("%d pixels differ; of the texture's hue %d textured, %d plain" % (len(tree), hue_t, hue_a))
        sys.exit(1)
    print("where the renders differ, at least %s of the textured pixels are of the texture's hue; none plain" % least)


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "solid":
        solid(sys.argv[2], *sys.argv[3:7])
    elif cmd == "tint":
        tint(sys.argv[2], sys.argv[3], *sys.argv[4:8])
    else:
        {"glb": glb, "cards": cards, "vt": vt}[cmd](sys.argv[2])
