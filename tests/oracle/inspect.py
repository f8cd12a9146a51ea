#!/usr/bin/env python3
"""Read Sylva's output files with the Python standard library only, so that CLI cases check
what is in them rather than a few magic bytes.

  inspect.py png FILE            "png WxH", after decoding every row (zlib, the 5 filters)
  inspect.py png FILE sky        also "sky above ground" when the top row's middle pixel is
                                 blue-dominant and the bottom row's is green-dominant
  inspect.py png FILE at X Y     also the pixel's "r g b"
  inspect.py png FILE blue       also "N blue pixels" (blue above red and green: sky)
  inspect.py glb FILE            "glb: T triangles, M materials" from the JSON chunk, after
                                 checking the header, the chunks and every accessor's range
  inspect.py glb FILE nodes      also "nodes: NAME ..." (the node names, in order) and, with
                                 MSFT_lod on the scene's node, "MSFT_lod: ID ..."
  inspect.py obj FILE            "obj: V vertices, T triangles" (polygons split into fans)
  inspect.py ply FILE            "ply: V vertices, F faces" after reading every element of a
                                 binary little-endian file to its exact end
Exit status 1, with the reason, when the file is not what it claims to be.
"""

import json
import struct
import sys
import zlib


def fail(why):
    print("inspect: " + why)
    sys.exit(1)


def png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail("not a PNG signature")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]:
            fail("bad CRC in chunk %r" % kind)
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + n
    if not ihdr:
        fail("no IHDR")
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        fail("not 8-bit RGB(A), non-interlaced (depth %d, colour type %d)" % (depth, ctype))
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * bpp
    if len(raw) != h * (stride + 1):
        fail("image data is %d bytes, not %d" % (len(raw), h * (stride + 1)))
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            elif f != 0:
                fail("unknown filter %d" % f)
        rows.append(line)
        prev = line
    return w, h, bpp, rows


def pixel(img, x, y):
    w, h, bpp, rows = img
    return tuple(rows[y][x * bpp:x * bpp + 3])


def glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack("<4sII", data[:12])
    if magic != b"glTF" or version != 2 or length != len(data):
        fail("bad GLB header")
    n, kind = struct.unpack("<I4s", data[12:20])
    if kind != b"JSON":
        fail("first chunk is not JSON")
    doc = json.loads(data[20:20 + n].decode("utf-8"))
    pos = 20 + n
    bin_len = 0
    if pos < len(data):
        bn, bkind = struct.unpack("<I4s", data[pos:pos + 8])
        if bkind != b"BIN\x00" or pos + 8 + bn != len(data):
            fail("bad BIN chunk")
        bin_len = bn
    if doc.get("asset", {}).get("version") != "2.0":
        fail("asset.version is not 2.0")
    views = doc.get("bufferViews", [])
    for v in views:
        if v.get("byteOffset", 0) + v["byteLength"] > bin_len:
            fail("a bufferView runs past the BIN chunk")
    size = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
    comp = {5121: 1, 5123: 2, 5125: 4, 5126: 4}
    accessors = doc.get("accessors", [])
    for a in accessors:
        v = views[a["bufferView"]]
        if a.get("byteOffset", 0) + a["count"] * size[a["type"]] * comp[a["componentType"]] > v["byteLength"]:
            fail("an accessor runs past its bufferView")
    tris = 0
    for mesh in doc.get("meshes", []):
        for prim in mesh["primitives"]:
            if prim.get("mode", 4) != 4:
                fail("a primitive is not triangles")
            tris += accessors[prim["indices"]]["count"] // 3
    return tris, len(doc.get("materials", [])), doc


def obj(path):
    nv = nt = 0
    for line in open(path, encoding="utf-8"):
        t = line.split()
        if t and t[0] == "v":
            nv += 1
        elif t and t[0] == "f":
            if len(t) < 4:
                fail("a face with fewer than three vertices")
            for ref in t[1:]:
                i = int(ref.split("/")[0])
                if not (1 <= i <= nv or -nv <= i <= -1):
                    fail("face vertex %d out of range" % i)
            nt += len(t) - 3
    return nv, nt


def ply(path):
    data = open(path, "rb").read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        fail("not a PLY header")
    types = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f",
             "double": "d"}
    elements = []
    for line in data[:end].decode("ascii").splitlines()[1:]:
        t = line.split()
        if t[0] == "format" and t[1:] != ["binary_little_endian", "1.0"]:
            fail("not binary little endian")
        elif t[0] == "element":
            elements.append((t[1], int(t[2]), []))
        elif t[0] == "property":
            elements[-1][2].append(t[1:])
    pos, counts = end + len(b"end_header\n"), {}
    for name, n, props in elements:
        for _ in range(n):
            for p in props:
                if p[0] == "list":
                    k = struct.unpack_from("<" + types[p[1]], data, pos)[0]
                    pos += struct.calcsize("<" + types[p[1]]) + k * struct.calcsize("<" + types[p[2]])
                else:
                    pos += struct.calcsize("<" + types[p[0]])
        counts[name] = n
    if pos != len(data):
        fail("%d bytes after the last element" % (len(data) - pos) if pos < len(data) else "file ends early")
    return counts.get("vertex", 0), counts.get("face", 0)


def main():
    what, path, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    if what == "png":
        img = png(path)
        w, h = img[0], img[1]
        print("png %dx%d" % (w, h))
        if rest[:1] == ["sky"]:
            top, bottom = pixel(img, w // 2, 0), pixel(img, w // 2, h - 1)
            sky = top[2] > top[1] and top[2] > top[0]
            ground = bottom[1] > bottom[2] and bottom[1] > bottom[0]
            print("sky above ground" if sky and ground else "top %s, bottom %s" % (top, bottom))
        elif rest[:1] == ["blue"]:
            n = sum(1 for y in range(h) for x in range(w) if pixel(img, x, y)[2] > max(pixel(img, x, y)[:2]))
            print("%d blue pixels" % n)
        elif rest[:1] == ["at"]:
            print("%d %d %d" % pixel(img, int(rest[1]), int(rest[2])))
    elif what == "glb":
        tris, mats, doc = glb(path)
        print("glb: %d triangles, %d materials" % (tris, mats))
        if rest[:1] == ["nodes"]:
            nodes = doc.get("nodes", [])
            print("nodes: " + " ".join(n.get("name", "?") for n in nodes))
            lod = nodes[doc["scenes"][0]["nodes"][0]].get("extensions", {}).get("MSFT_lod") if nodes else None
            if lod:
                print("MSFT_lod: " + " ".join(str(i) for i in lod["ids"]))
    elif what == "ply":
        print("ply: %d vertices, %d faces" % ply(path))
    elif what == "obj":
        print("obj: %d vertices, %d triangles" % obj(path))
    else:
        fail("unknown kind " + what)


if __name__ == "__main__":
    main()
