#!/usr/bin/env python3
"""Read the textures Sylva wrote, with the Python standard library only (tests/cases/textures.test).

  textures.py glb FILE   each image: its name, MIME type and whether its bytes equal the file
                         of that name in the working folder; each material: its texture's
                         image, alpha mode, sampler wrap and base colour factor
  textures.py vt FILE    an OBJ's largest u, and its v range (OBJ writes 1 - v)
"""

import json
import struct
import sys


def glb(path):
    d = open(path, "rb").read()
    n = struct.unpack("<I", d[12:16])[0]
    j = json.loads(d[20:20 + n])
    b = d[20 + n + 8:]
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


def vt(path):
    uv = [tuple(map(float, l.split()[1:3])) for l in open(path) if l.startswith("vt ")]
    print("u up to %g, v over %g" % (max(u for u, v in uv), max(v for u, v in uv) - min(v for u, v in uv)))


if __name__ == "__main__":
    {"glb": glb, "vt": vt}[sys.argv[1]](sys.argv[2])
