#!/usr/bin/env python3
"""Two skeleton CSVs (sylva skeleton) hold the same points: every row of one is matched by a
row of the other of the same kind, position and radius within TOL (the nearest unused one),
one to one, whatever the
order of the rows (two engines may walk a tree in different orders).
Usage: same_points.py A.csv B.csv [TOL]; prints "same N points" or the first misses, exit 1."""
import csv
import math
import sys


def rows(path):
    with open(path, newline="") as f:
        r = csv.reader(f)
        h = next(r, [])
        k, x, y, z, rad = (h.index(c) for c in ("kind", "x", "y", "z", "radius"))
        return [(w[k], float(w[x]), float(w[y]), float(w[z]), float(w[rad])) for w in r if w]


def main():
    a, b = rows(sys.argv[1]), rows(sys.argv[2])
    tol = float(sys.argv[3]) if len(sys.argv) > 3 else 2e-4
    if len(a) != len(b):
        print(f"{len(a)} rows against {len(b)}")
        return 1
    cell = lambda p: (p[0], math.floor(p[1] / tol), math.floor(p[2] / tol), math.floor(p[3] / tol))
    grid = {}
    for i, p in enumerate(b):
        grid.setdefault(cell(p), []).append(i)
    used, misses = [False] * len(b), []
    near = [(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)]
    get, floor = grid.get, math.floor
    for p in a:  # the nearest unused row of b within tol, the first of equals in this order
        kind, px, py, pz, pr = p
        kx, ky, kz = floor(px / tol), floor(py / tol), floor(pz / tol)
        hit, best = None, None
        for dx, dy, dz in near:
            for j in get((kind, kx + dx, ky + dy, kz + dz), ()):
                if used[j]: continue
                q = b[j]
                d = max(abs(px - q[1]), abs(py - q[2]), abs(pz - q[3]), abs(pr - q[4]))
                if d <= tol and (best is None or d < best):
                    hit, best = j, d
        if hit is None: misses.append(p)
        else: used[hit] = True
    if misses:
        print(f"{len(misses)} of {len(a)} points unmatched, first: {misses[:3]}")
        return 1
    print(f"same {len(a)} points")
    return 0


sys.exit(main())
