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
        return [(r["kind"], float(r["x"]), float(r["y"]), float(r["z"]), float(r["radius"])) for r in csv.DictReader(f)]


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
    for p in a:
        k, hit, best = cell(p), None, None
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((k[0], k[1] + dx, k[2] + dy, k[3] + dz), ()):
                        q = b[j]
                        d = max(abs(p[c] - q[c]) for c in (1, 2, 3, 4))
                        if not used[j] and d <= tol and (best is None or d < best):
                            hit, best = j, d
        if hit is None: misses.append(p)
        else: used[hit] = True
    if misses:
        print(f"{len(misses)} of {len(a)} points unmatched, first: {misses[:3]}")
        return 1
    print(f"same {len(a)} points")
    return 0


sys.exit(main())
