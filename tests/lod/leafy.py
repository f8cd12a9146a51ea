#!/usr/bin/env python3
"""An impostor's pictures show the leaves its levels draw (issue 27, item 4).

    leafy.py ATLAS.png FILE.glb    prints the share of leaf-coloured texels among the opaque
                                    ones of the octahedral atlas and of the billboards' picture
                                    (the LOD's last level's texture, read out of the .glb)

A leaf-coloured texel is green above red and blue (bark is brown, grey or black: red at least
green). Read with tests/lod/check.py's own PNG and glTF readers."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check import read_glb, read_png  # noqa: E402


def leafy_share(png):
    w, h, ch, rows = read_png(png)
    opaque = leafy = 0
    for row in rows:
        for x in range(w):
            r, g, b = row[ch * x:ch * x + 3]
            if ch == 4 and row[ch * x + 3] < 128:
                continue
            opaque += 1
            leafy += g > r + 8 and g > b + 8
    return leafy / opaque if opaque else 0.0


def billboard_png(path):
    js, bin_ = read_glb(path)
    last = next(m for m in js["materials"] if m.get("name") == "impostor")
    src = js["textures"][last["pbrMetallicRoughness"]["baseColorTexture"]["index"]]["source"]
    view = js["bufferViews"][js["images"][src]["bufferView"]]
    at = view.get("byteOffset", 0)
    return bin_[at:at + view["byteLength"]]


atlas, glb = sys.argv[1:3]
print("atlas %.2f billboards %.2f" % (leafy_share(open(atlas, "rb").read()), leafy_share(billboard_png(glb))))
