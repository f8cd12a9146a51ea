#!/usr/bin/env python3
"""Oracle for sylva ecosystem's pictures and .glb (docs/ecosystem.md#pictures), from the files alone.

  ecorender.py glb FOREST.glb PLANTS.csv      instances = the CSV's plants, at their positions, in their cells
  ecorender.py seen VIEW.png EMPTY.png STATS PLANTS.csv   each plant shows where the camera projects it
  ecorender.py terrain VIEW.png STATS         only terrain (green) and sky (blue), the terrain's middle is ground
STATS is sylva's --stats output: the line "view Y: camera EX EY EZ target TX TY TZ fov F size W H".
The projection is computed here: a pinhole camera, right = forward x up, pixels y down."""
import csv
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import png, pixel  # noqa: E402  (tests/oracle/inspect.py)


def fail(why):
    print("ecorender: " + why)
    sys.exit(1)


def plants(path):
    with open(path) as f:
        return [(float(r["x"]), float(r["y"]), float(r["z"]), float(r["height"])) for r in csv.DictReader(f)]


def camera(path):
    for line in open(path):
        w = line.split()
        if len(w) >= 15 and w[0] == "view" and w[2] == "camera":
            v = [float(x) for x in w[3:6] + w[7:10]]
            return v[:3], v[3:], float(w[11]), int(w[13]), int(w[14])
    fail("no camera line in " + path)


def norm(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def project(cam, p):
    eye, target, fov, w, h = cam
    f = norm([target[i] - eye[i] for i in range(3)])
    r = norm([-f[2], 0.0, f[0]])
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    q = [p[i] - eye[i] for i in range(3)]
    z = sum(q[i] * f[i] for i in range(3))
    ty = math.tan(math.radians(fov) / 2)
    tx = ty * w / h
    sx = sum(q[i] * r[i] for i in range(3)) / (z * tx)
    sy = sum(q[i] * u[i] for i in range(3)) / (z * ty)
    return (sx + 1) / 2 * w, (1 - sy) / 2 * h


def check_glb(path, table):
    data = open(path, "rb").read()
    n = struct.unpack("<I", data[12:16])[0]
    doc = json.loads(data[20:20 + n])
    binary = data[20 + n + 8:]
    got, cells = [], set()
    for node in doc["nodes"]:
        ext = node.get("extensions", {}).get("EXT_mesh_gpu_instancing")
        if not ext:
            continue
        a = doc["accessors"][ext["attributes"]["TRANSLATION"]]
        v = doc["bufferViews"][a["bufferView"]]
        off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        x0, z0, x1, z1 = node["extras"]["bounds"]
        cells.add((x0, z0, x1, z1))
        for i in range(a["count"]):
            t = struct.unpack_from("<3f", binary, off + 12 * i)
            if not (x0 - 1e-3 <= t[0] <= x1 + 1e-3 and z0 - 1e-3 <= t[2] <= z1 + 1e-3):
                fail("instance at %r lies outside its cell %r" % (t, node["extras"]["bounds"]))
            got.append(t)
    want = [p[:3] for p in plants(table)]
    if len(got) != len(want):
        fail("%d instances for %d plants" % (len(got), len(want)))
    for a, b in zip(sorted(got), sorted(want)):
        if max(abs(a[i] - b[i]) for i in range(3)) > 2e-3:  # the CSV has 3 decimals
            fail("instance %r is not at plant %r" % (a, b))
    if len(want) < 10:
        fail("only %d plants: too few to tell" % len(want))
    print("instances = plants; at their positions; inside their cells (%d cells)" % len(cells))


def check_seen(view, empty, stats, table):
    img, bare, cam = png(view), png(empty), camera(stats)
    w, h = img[0], img[1]
    diff = [(x, y) for y in range(h) for x in range(w)
            if max(abs(a - b) for a, b in zip(pixel(img, x, y), pixel(bare, x, y))) > 24]
    if not diff:
        fail("the plants change no pixel")
    for x, y, z, height in plants(table):
        mx, my = project(cam, (x, y + height / 2, z))
        near = [(px, py) for px, py in diff if abs(px + 0.5 - mx) <= 2 and abs(py + 0.5 - my) <= 2]
        if not near:
            fail("nothing drawn within 2 pixels of (%.1f, %.1f), where the plant's middle projects" % (mx, my))
        tx, ty = project(cam, (x, y + height, z))
        if not any(abs(px + 0.5 - tx) <= 2.5 and abs(py + 0.5 - ty) <= 2.5 for px, py in diff):
            fail("nothing drawn near the plant's top at (%.1f, %.1f)" % (tx, ty))
        if any(py + 0.5 < ty - 3 and abs(px + 0.5 - tx) < 1 for px, py in diff):
            fail("something drawn above the plant's top at (%.1f, %.1f)" % (tx, ty))
    print("every plant shows where the camera projects it")


def check_terrain(view, stats):
    img, cam = png(view), camera(stats)
    w, h = img[0], img[1]
    green = 0
    for y in range(h):
        for x in range(w):
            r, g, b = pixel(img, x, y)
            if g > r and g > b:
                green += 1
            elif not (b >= r and b >= g):
                fail("pixel (%d, %d) = %r is neither ground nor sky" % (x, y, (r, g, b)))
    cx, cy = project(cam, cam[1])
    r, g, b = pixel(img, int(cx), int(cy))
    if not (g > r and g > b) or green < w * h // 10:
        fail("the terrain is not where the camera looks")
    print("only terrain and sky")


if __name__ == "__main__":
    a = sys.argv[1:]
    if a[:1] == ["glb"] and len(a) == 3:
        check_glb(a[1], a[2])
    elif a[:1] == ["seen"] and len(a) == 5:
        check_seen(*a[1:])
    elif a[:1] == ["terrain"] and len(a) == 3:
        check_terrain(*a[1:])
    else:
        fail("usage: see the docstring")
