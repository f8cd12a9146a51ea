#!/usr/bin/env python3
"""Helpers of tests/cases/terrain.test, standard library only.

  terrain.py dem NX NZ CELL SEED      print a smooth, irregular ESRI ASCII grid (no flat cell)
  terrain.py compare OURS GDAL TOL [angle]
                                      compare two ASCII grids cell by cell where GDAL has a
                                      value (gdaldem leaves the border as NODATA); `angle`
                                      compares directions modulo 360, and where GDAL has
                                      NODATA inside (a flat cell's aspect) OURS must be -1.
                                      Prints "N cells agree within TOL" or the first cell
                                      that does not, and exits 1.
  terrain.py interior FILE            "min MIN max MAX" of the grid's interior cells
  terrain.py png8 FILE W H V...       write an 8-bit greyscale PNG of the values V (row by row)
  terrain.py pngrgb FILE              write a 2 x 2 RGB PNG (not a DEM)
"""
import math
import random
import struct
import sys
import zlib


def read_asc(path):
    head, rows = {}, []
    with open(path) as f:
        tokens = f.read().split()
    i = 0
    while not _number(tokens[i]):
        head[tokens[i].lower()] = float(tokens[i + 1])
        i += 2
    nx, nz = int(head["ncols"]), int(head["nrows"])
    values = [float(v) for v in tokens[i:]]
    if len(values) != nx * nz:
        sys.exit("%s: %d values, not %d x %d" % (path, len(values), nx, nz))
    rows = [values[k * nx:(k + 1) * nx] for k in range(nz)]
    return head, rows


def _number(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def dem(nx, nz, cell, seed):
    rnd = random.Random(seed)
    waves = [(rnd.uniform(0.05, 0.4), rnd.uniform(0.05, 0.4), rnd.uniform(0, 6.3), rnd.uniform(5, 40)) for _ in range(6)]
    print("ncols %d\nnrows %d\nxllcenter 1000.5\nyllcenter -250.25\ncellsize %s\nNODATA_value -9999" % (nx, nz, cell))
    for k in range(nz):
        row = []
        for i in range(nx):
            h = 500 + 0.8 * i * float(cell) - 0.3 * k * float(cell)
            for a, b, p, amp in waves:
                h += amp * math.sin(a * i + b * k + p)
            row.append("%.3f" % h)
        print(" ".join(row))


def compare(ours, gdal, tol, angle):
    ho, ro = read_asc(ours)
    hg, rg = read_asc(gdal)
    nodata = hg.get("nodata_value", -9999)
    n = 0
    for k in range(len(rg)):
        for i in range(len(rg[k])):
            g, o = rg[k][i], ro[k][i]
            inside = 0 < k < len(rg) - 1 and 0 < i < len(rg[k]) - 1
            if g == nodata:
                if inside and angle and o != -1:
                    print("cell %d,%d: gdaldem has no aspect (flat), ours is %g" % (i, k, o))
                    sys.exit(1)
                continue
            d = abs(g - o)
            if angle:
                d = min(d % 360, 360 - d % 360)
            if d > tol:
                print("cell %d,%d: ours %.9g, gdaldem %.9g" % (i, k, o, g))
                sys.exit(1)
            n += 1
    print("%d cells agree within %g" % (n, tol))


def interior(path):
    _, rows = read_asc(path)
    vals = [v for row in rows[1:-1] for v in row[1:-1]]
    print("min %.3f max %.3f" % (min(vals), max(vals)))


def png(path, w, h, colour, raw):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def main():
    cmd = sys.argv[1]
    if cmd == "dem":
        dem(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], int(sys.argv[5]))
    elif cmd == "compare":
        compare(sys.argv[2], sys.argv[3], float(sys.argv[4]), len(sys.argv) > 5 and sys.argv[5] == "angle")
    elif cmd == "interior":
        interior(sys.argv[2])
    elif cmd == "png8":
        w, h = int(sys.argv[3]), int(sys.argv[4])
        v = [int(x) for x in sys.argv[5:]]
        png(sys.argv[2], w, h, 0, b"".join(b"\0" + bytes(v[k * w:(k + 1) * w]) for k in range(h)))
    elif cmd == "pngrgb":
        png(sys.argv[2], 2, 2, 2, b"\0" + bytes(6) + b"\0" + bytes(6))
    else:
        sys.exit("terrain.py: unknown command " + cmd)


main()
