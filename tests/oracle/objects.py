#!/usr/bin/env python3
"""A scene's objects, read back from an OBJ (`o NAME` sections) or a .glb (the scene's nodes):
per object its name, its triangles and the box of the vertices they use.

    objects.py FILE.obj|FILE.glb    prints "NAME TRIANGLES xmin..xmax ymin..ymax zmin..zmax" a line"""
import json
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "gltf"))
from glbio import read_glb, triangles  # noqa: E402


def fail(msg):
    print(msg)
    sys.exit(1)


def box(points):
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return " ".join("%.2f..%.2f" % (lo[k], hi[k]) for k in range(3))


def obj(path):
    verts, objects = [], []
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(tuple(map(float, w[1:4])))
        elif w[0] == "o":
            objects.append([w[1], 0, set()])
        elif w[0] == "f":
            if not objects:
                fail("a face before any object")
            ix = [int(x.split("/")[0]) - 1 for x in w[1:]]
            objects[-1][1] += len(ix) - 2
            objects[-1][2].update(ix)
    for name, tris, used in objects:
        print(name, tris, box([verts[i] for i in used]))


def glb(path):
    js, bin_ = read_glb(path, fail)

    def acc(i):
        a = js["accessors"][i]
        v = js["bufferViews"][a["bufferView"]]
        at = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        k = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[a["type"]]
        fmt = {5126: "f", 5125: "I", 5123: "H"}[a["componentType"]]
        vals = struct.unpack_from("<%d%s" % (a["count"] * k, fmt), bin_, at)
        return [vals[j:j + k] for j in range(0, len(vals), k)] if k > 1 else list(vals)
    for n in js["scenes"][js.get("scene", 0)]["nodes"]:
        node = js["nodes"][n]
        tris, pts = 0, []
        for pr in js["meshes"][node["mesh"]]["primitives"]:
            pos = acc(pr["attributes"]["POSITION"])
            t = triangles(acc(pr["indices"]), pr.get("mode", 4))
            tris += len(t)
            pts += [pos[i] for tri in t for i in tri]
        print(node["name"], tris, box(pts))


(obj if sys.argv[1].endswith(".obj") else glb)(sys.argv[1])
