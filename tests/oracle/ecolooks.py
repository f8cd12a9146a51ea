#!/usr/bin/env python3
"""How an ecosystem's pictures look, from the files alone (standard library only).

  ecolooks.py cone N CELL H          an ESRI grid of N x N cells: a round hill H high in the
                                     middle falling to 0 at the edges' middles
  ecolooks.py leafy VIEW EMPTY MIN   of the pixels where VIEW differs from EMPTY (the same
                                     terrain and camera without plants: the plants' pixels),
                                     at least MIN are leaf-coloured (green over red and blue)
  ecolooks.py covers VIEW MIN        at least MIN of the picture is not sky (terrain, plants)
  ecolooks.py walker STATS GRID      the walker's eye (the --stats camera line) stands in the
                                     middle 70% of the grid's extent each way, above the ground
                                     there, and the ground 50 m ahead is inside the grid
Prints what holds; exit 1 with the measure when it does not."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import png, pixel  # noqa: E402  (tests/oracle/inspect.py)
from ecorender import camera  # noqa: E402


def fail(why):
    print("ecolooks: " + why)
    sys.exit(1)


def cone(n, cell, h):
    print("ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g" % (n, n, cell))
    for k in range(n):
        print(" ".join("%.3f" % max(0.0, h * (1 - math.hypot(i - (n - 1) / 2, k - (n - 1) / 2) / ((n - 1) / 2)))
                       for i in range(n)))


def grid(path):
    head, rows = {}, []
    for line in open(path):
        w = line.split()
        if len(w) == 2 and w[0].isalpha():
            head[w[0].lower()] = float(w[1])
        elif w:
            rows.append([float(x) for x in w])
    return head, rows


def height(head, rows, x, z):
    """Bilinear between cell centres; row 0 is the north (largest z), as ESRI grids are."""
    n, m, c = len(rows), len(rows[0]), head["cellsize"]
    fi = min(max((x - head["xllcorner"]) / c - 0.5, 0), m - 1)
    fk = min(max(n - 1 - ((z - head["yllcorner"]) / c - 0.5), 0), n - 1)
    i, k = min(int(fi), m - 2), min(int(fk), n - 2)
    a, b = fi - i, fk - k
    return ((rows[k][i] * (1 - a) + rows[k][i + 1] * a) * (1 - b) + (rows[k + 1][i] * (1 - a) + rows[k + 1][i + 1] * a) * b)


def leafy(view, empty, least):
    a, b = png(view), png(empty)
    changed = green = 0
    for y in range(a[1]):
        for x in range(a[0]):
            p, q = pixel(a, x, y), pixel(b, x, y)
            if max(abs(u - v) for u, v in zip(p, q)) > 24:
                changed += 1
                green += p[1] > p[0] and p[1] > p[2]
    if changed < a[0] * a[1] // 50:
        fail("the plants change %d pixels: too few to tell" % changed)
    if green < least * changed:
        fail("%.2f of the plants' pixels are leaf-coloured, fewer than %g" % (green / changed, least))
    print("leafy")


def covers(view, least):
    a = png(view)
    ground = sum(1 for y in range(a[1]) for x in range(a[0]) if not (lambda p: p[2] >= p[0] and p[2] >= p[1])(pixel(a, x, y)))
    if ground < least * a[0] * a[1]:
        fail("the terrain covers %.2f of the picture, less than %g" % (ground / (a[0] * a[1]), least))
    print("the terrain fills the frame")


def walker(stats, path):
    eye, target, _, _, _ = camera(stats)
    # Sylva's z runs south (north is -z): the grid's y (north) is -z
    eye, target = (eye[0], eye[1], -eye[2]), (target[0], target[1], -target[2])
    head, rows = grid(path)
    c = head["cellsize"]
    x0, z0, w, d = head["xllcorner"], head["yllcorner"], len(rows[0]) * c, len(rows) * c
    inside = lambda x, z, m: x0 + m * w <= x <= x0 + (1 - m) * w and z0 + m * d <= z <= z0 + (1 - m) * d  # noqa: E731
    if not inside(eye[0], eye[2], 0.15):
        fail("the eye (%.1f, %.1f) is not in the middle 70%% of the terrain" % (eye[0], eye[2]))
    ground = height(head, rows, eye[0], eye[2])
    if not eye[1] > ground + 1:
        fail("the eye is %.2f m high, the ground there %.2f m" % (eye[1], ground))
    dx, dz = target[0] - eye[0], target[2] - eye[2]
    n = math.hypot(dx, dz)
    if not n or not inside(eye[0] + 50 * dx / n, eye[2] + 50 * dz / n, 0):
        fail("the walker looks off the terrain")
    print("the walker stands inside, above the ground, looking across it")


if __name__ == "__main__":
    a = sys.argv[1:]
    if a[:1] == ["cone"] and len(a) == 4:
        cone(int(a[1]), float(a[2]), float(a[3]))
    elif a[:1] == ["leafy"] and len(a) == 4:
        leafy(a[1], a[2], float(a[3]))
    elif a[:1] == ["covers"] and len(a) == 3:
        covers(a[1], float(a[2]))
    elif a[:1] == ["walker"] and len(a) == 3:
        walker(a[1], a[2])
    else:
        fail("usage: see the docstring")
