#!/usr/bin/env python3
"""One object of an OBJ file, read independently of Sylva: its vertices moved by -(dx, dy, dz)
and rounded to 1e-3, then its triangles counted per material (`tris MATERIAL N`).

usage: obj_part.py FILE.obj OBJECT [dx dy dz]"""
import sys


def main():
    path, name = sys.argv[1], sys.argv[2]
    d = [float(x) for x in sys.argv[3:6]] if len(sys.argv) >= 6 else [0.0, 0.0, 0.0]
    cur, mtl, verts, tris = None, None, [], {}
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "o":
            cur = w[1]
        elif w[0] == "usemtl":
            mtl = w[1]
        elif w[0] == "v" and cur == name:
            verts.append(" ".join("%.3f" % (float(w[1 + k]) - d[k]) + "" for k in range(3)))
        elif w[0] == "f" and cur == name:
            tris[mtl] = tris.get(mtl, 0) + len(w) - 3
    for v in verts:
        print("v", v.replace("-0.000", "0.000"))
    for m in sorted(tris):
        print("tris", m, tris[m])


main()
