#!/usr/bin/env python3
"""Oracles for `sylva ecosystem` (tests/cases/ecosystem.test), standard library only.

  ecosystem.py flat N CELL                 a flat ESRI grid of N x N cells on stdout
  ecosystem.py valley N CELL               a V-shaped valley draining south (wet floor, dry ridges)
  ecosystem.py thinning SPECIES.CSV        the slope of log density on log mean crown area over
                                           the years the canopy is closed (cover >= 0.3)
  ecosystem.py yoda DIR W                  the slope of log mean mass (mass ∝ height³, geometric
                                           similarity) on log density over the snapshots
                                           DIR/plants-*.csv of a W x W stand whose canopy is
                                           closed (crown cover >= 0.3, from the radii)
  ecosystem.py clark PLANTS.CSV SPECIES W  Clark and Evans' R of the species' plants on a W x W
                                           square (R < 1 clustered, 1 random, > 1 regular)
  ecosystem.py under PLANTS.CSV LARGE SPECIES...   (LARGE "*": any species)
                                           the share of each species' established plants
                                           (aged 2 or more) whose circle a taller LARGE
                                           plant's circle overlaps: they live under it
  ecosystem.py mean PLANTS.CSV SPECIES GRID.ASC
                                           the mean of the grid at the species' plants
"""
import csv
import math
import sys


def grid_header(n, cell):
    return "ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g\n" % (n, n, cell)


def flat(n, cell):
    sys.stdout.write(grid_header(n, cell))
    for _ in range(n):
        print(" ".join(["10"] * n))


def valley(n, cell):
    sys.stdout.write(grid_header(n, cell))
    for k in range(n):  # row 0 is the north
        row = []
        for i in range(n):
            across = abs(i - (n - 1) / 2) * cell * 0.4  # the sides rise 0.4 in 1
            row.append("%.3f" % (across + (n - k) * cell * 0.05))  # the floor falls south
        print(" ".join(row))


def thinning(path):
    by_year = {}
    for r in csv.DictReader(open(path)):
        by_year.setdefault(int(r["year"]), []).append(r)
    xs, ys = [], []
    for year, rows in sorted(by_year.items()):
        count = sum(int(r["count"]) for r in rows)
        cover = sum(float(r["cover"]) for r in rows)
        if count < 10 or cover < 0.3:
            continue
        xs.append(math.log(cover / count))  # mean crown area (over the terrain's area)
        ys.append(math.log(count))
    if len(xs) < 5:
        print("too few closed-canopy years: %d" % len(xs))
        return
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print("closed-canopy years >= 5; slope %s" % ("in [-1.25, -0.75]" if -1.25 <= slope <= -0.75 else "%.3f" % slope))


def yoda(folder, w):
    import glob
    xs, ys = [], []
    for path in sorted(glob.glob(folder + "/plants-*.csv")):
        rows = list(csv.DictReader(open(path)))
        if len(rows) < 10:
            continue
        cover = sum(math.pi * float(r["radius"]) ** 2 for r in rows) / (w * w)
        if cover < 0.3:
            continue
        mass = sum(float(r["height"]) ** 3 for r in rows) / len(rows)
        xs.append(math.log(len(rows) / (w * w)))
        ys.append(math.log(mass))
    if len(xs) < 5:
        print("too few closed-canopy snapshots: %d" % len(xs))
        return
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print("closed-canopy snapshots >= 5; mass slope %s" % ("in [-1.75, -1.25]" if -1.75 <= slope <= -1.25 else "%.3f" % slope))


def points(path, species):
    return [(float(r["x"]), float(r["z"])) for r in csv.DictReader(open(path)) if r["species"] == species]


def clark(path, species, w):
    p = points(path, species)
    n = len(p)
    if n < 30:
        print("too few plants: %d" % n)
        return
    cell = {}
    size = w / math.sqrt(n) * 2
    for idx, (x, z) in enumerate(p):
        cell.setdefault((int(x // size), int(z // size)), []).append(idx)
    total = 0
    for idx, (x, z) in enumerate(p):
        ci, ck, best, ring = int(x // size), int(z // size), math.inf, 1
        while True:  # widen until the nearest found lies within the searched square
            for a in range(ci - ring, ci + ring + 1):
                for b in range(ck - ring, ck + ring + 1):
                    for j in cell.get((a, b), []):
                        if j != idx:
                            best = min(best, math.hypot(p[j][0] - x, p[j][1] - z))
            if best <= ring * size or ring > 64:
                break
            ring += 1
        total += best
    density = n / (w * w)
    r = (total / n) / (0.5 / math.sqrt(density))
    print("%s: %s" % (species, "clustered (R < 0.8)" if r < 0.8 else "random (0.9 <= R <= 1.15)"
                      if 0.9 <= r <= 1.15 else "R = %.3f" % r))


def under(path, large, species):
    rows = list(csv.DictReader(open(path)))
    big = [(float(r["x"]), float(r["z"]), float(r["radius"]), float(r["height"])) for r in rows
           if large in ("*", r["species"])]
    size = 2 * max([b[2] for b in big] + [1e-9])
    cell = {}
    for b in big:
        cell.setdefault((int(b[0] // size), int(b[1] // size)), []).append(b)
    for sp in species:
        n = hit = 0
        for r in rows:
            if r["species"] != sp or int(r["age"]) < 2:
                continue
            x, z, rad, h = float(r["x"]), float(r["z"]), float(r["radius"]), float(r["height"])
            ci, ck = int(x // size), int(z // size)
            n += 1
            hit += any(math.hypot(b[0] - x, b[1] - z) < b[2] + rad and b[3] > h
                       for a in range(ci - 1, ci + 2) for c in range(ck - 1, ck + 2) for b in cell.get((a, c), []))
        print("%s %.4f %d" % (sp, hit / n if n else float("nan"), n))


def mean_at(path, species, grid):
    lines = open(grid).read().split("\n")
    head = {}
    i = 0
    while lines[i].split()[0].lower() in ("ncols", "nrows", "xllcorner", "yllcorner", "cellsize", "nodata_value"):
        k, v = lines[i].split()
        head[k.lower()] = float(v)
        i += 1
    nx, nz, cs = int(head["ncols"]), int(head["nrows"]), head["cellsize"]
    values = [[float(v) for v in line.split()] for line in lines[i:i + nz]]
    x0, z0 = head["xllcorner"], -(head["yllcorner"] + nz * cs)  # north is -z
    total, n = 0.0, 0
    for x, z in points(path, species):  # Sylva's z grows south, from the grid's northern edge
        col = min(nx - 1, max(0, int((x - x0) / cs)))
        row = min(nz - 1, max(0, int((z - z0) / cs)))
        total += values[row][col]
        n += 1
    print("%.6f" % (total / n if n else float("nan")))


if __name__ == "__main__":
    a = sys.argv[1:]
    if a[0] == "flat":
        flat(int(a[1]), float(a[2]))
    elif a[0] == "valley":
        valley(int(a[1]), float(a[2]))
    elif a[0] == "thinning":
        thinning(a[1])
    elif a[0] == "yoda":
        yoda(a[1], float(a[2]))
    elif a[0] == "clark":
        clark(a[1], a[2], float(a[3]))
    elif a[0] == "under":
        under(a[1], a[2], a[3:])
    elif a[0] == "mean":
        mean_at(a[1], a[2], a[3])
