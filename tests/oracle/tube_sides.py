#!/usr/bin/env python3
# tube_sides.py FILE.obj: the sides of the trunk and of the branches of a tree's OBJ mesh, read
# from its faces alone (tests/cases/curvetree_rings.test). The tubes are the connected parts of
# the bark's triangles; a capped tube of c rings of S sides has c (S + 1) + 2 vertices (a seam
# vertex a ring, a cap centre an end) and 2 S c triangles (2 S a segment, S a cap). The trunk
# is the part holding the lowest vertex; a part that does not fit the counts prints as None.
import sys

v, faces, mat = [], [], None
for line in open(sys.argv[1]):
    w = line.split()
    if not w: continue
    if w[0] == 'v': v.append(tuple(map(float, w[1:4])))
    elif w[0] == 'usemtl': mat = w[1]
    elif w[0] == 'f' and mat.startswith('bark'): faces.append([int(x.split('/')[0]) - 1 for x in w[1:]])
parent = {}
def find(a):
    while parent.setdefault(a, a) != a:
        parent[a] = parent[parent[a]]; a = parent[a]
    return a
for f in faces:
    for x in f[1:]: parent[find(x)] = find(f[0])
verts, tris = {}, {}
for f in faces:
    r = find(f[0]); tris[r] = tris.get(r, 0) + 1
for x in list(parent): r = find(x); verts[r] = verts.get(r, 0) + 1
# the trunk: the part with the lowest vertex
low = min(parent, key=lambda x: v[x][1]); trunk = find(low)
def sides(r):
    V, T = verts[r], tris[r]
    c = V - 2 - T // 2            # rings: V - 2 = c (S + 1) and T = 2 S c
    return T // (2 * c) if c > 0 and T % (2 * c) == 0 and V == c * (T // (2 * c) + 1) + 2 else None
branch = sorted({sides(r) for r in verts if r != trunk}, key=str)
print("trunk", sides(trunk), "branches", " ".join(map(str, branch)), "tubes", len(verts))
