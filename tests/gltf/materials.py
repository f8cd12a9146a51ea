#!/usr/bin/env python3
"""The materials of .glb files, read back: name, base colour texture (its image decoded) and
alpha mode.

    materials.py FILE.glb...    prints, per file, its materials' names (sorted, each once) with
                                 the name of the image each one's texture shows (or "-") and
                                 MASK for alpha-tested ones; exits 1 when an image is no PNG"""
import os
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from glbio import read_glb  # noqa: E402


def fail(msg):
    print(msg)
    sys.exit(1)


def png_ok(data):
    """A PNG whose chunks' CRCs hold and whose IDAT inflates."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return False
    at, idat = 8, b""
    while at < len(data):
        n = int.from_bytes(data[at:at + 4], "big")
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + n]
        if zlib.crc32(kind + body) != int.from_bytes(data[at + 8 + n:at + 12 + n], "big"):
            return False
        idat += body if kind == b"IDAT" else b""
        at += 12 + n
    return len(zlib.decompress(idat)) > 0


for path in sys.argv[1:]:
    js, bin_ = read_glb(path, fail)
    seen = set()
    for m in js.get("materials", []):
        tex = m.get("pbrMetallicRoughness", {}).get("baseColorTexture")
        image = "-"
        if tex:
            img = js["images"][js["textures"][tex["index"]]["source"]]
            view = js["bufferViews"][img["bufferView"]]
            at = view.get("byteOffset", 0)
            if not png_ok(bin_[at:at + view["byteLength"]]):
                fail("%s: the image of %s is no PNG" % (path, m.get("name")))
            image = img.get("name", "?")
        seen.add("%s:%s%s" % (m.get("name", "(unnamed)"), image, " MASK" if m.get("alphaMode") == "MASK" else ""))
    print(" ".join(sorted(seen)))
