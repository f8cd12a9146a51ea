#!/usr/bin/env python3
"""Writes the example crowns and trunk curve of examples/curvetree/ (run from this folder):
crown.obj, an ellipsoid (convex); lobed.obj, a sphere with five lobes (not convex: a star
shape seen from above); trunk.obj, an S-bent trunk as Blender exports a curve (`v` and `l`)."""
import math


def sphere(path, centre, radii, lobes=0, depth=0.0, rings=16, segs=32):
    v, f = [], []
    cx, cy, cz = centre
    v.append((cx, cy - radii[1], cz))
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segs):
            ph = 2 * math.pi * j / segs
            k = 1 + depth * math.sin(lobes * ph) * math.sin(th) if lobes else 1
            v.append((cx + radii[0] * k * math.sin(th) * math.cos(ph), cy - radii[1] * math.cos(th),
                      cz + radii[2] * k * math.sin(th) * math.sin(ph)))
    v.append((cx, cy + radii[1], cz))
    top = len(v)
    for j in range(segs):  # counter-clockwise seen from outside
        f.append((1, 2 + (j + 1) % segs, 2 + j))
    for i in range(rings - 2):
        for j in range(segs):
            a = 2 + i * segs + j
            b = 2 + i * segs + (j + 1) % segs
            f.append((a, b, b + segs))
            f.append((a, b + segs, a + segs))
    last = 2 + (rings - 2) * segs
    for j in range(segs):
        f.append((top, last + j, last + (j + 1) % segs))
    with open(path, "w") as out:
        out.write("# %s\n" % path)
        for p in v:
            out.write("v %.5f %.5f %.5f\n" % p)
        for t in f:
            out.write("f %d %d %d\n" % t)


sphere("crown.obj", (0, 6.2, 0), (3.6, 3.6, 3.6))
sphere("lobed.obj", (0, 6.0, 0), (4.0, 3.4, 4.0), lobes=5, depth=0.35)
with open("trunk.obj", "w") as out:
    out.write("# an S-bent trunk, as Blender's OBJ export writes a curve\no Trunk\n")
    n = 12
    for i in range(n + 1):
        t = i / n
        out.write("v %.5f %.5f %.5f\n" % (0.6 * math.sin(2 * math.pi * t) * (1 - t), 9.0 * t, 0.3 * t * t))
    for i in range(1, n + 1):
        out.write("l %d %d\n" % (i, i + 1))
