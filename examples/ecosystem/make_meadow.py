#!/usr/bin/env python3
"""Write the meadow example's DEM, meadow.asc: 40 x 40 m in cells of 0.5 m (80 x 80), an ESRI
ASCII grid. Standard library only.

  make_meadow.py [OUT.asc]      (default examples/ecosystem/meadow.asc)

Gentle ground: it falls 1 in 25 to the south, with a shallow swale (0.8 m deep, 8 m wide)
winding down its middle that gathers the runoff, so the wetness index is high along it and
low on the two rises beside it.
"""
import math
import sys

N, CELL = 80, 0.5


def height(x, z):
    """Metres at (x east, z south), both in 0..40."""
    fall = (40 - z) * 0.04  # 1 in 25 down to the south
    axis = 20 + 4 * math.sin(z / 40 * 2 * math.pi)  # the swale winds
    swale = -0.8 * math.exp(-(((x - axis) / 4) ** 2))
    rise = 0.25 * math.exp(-(((x - 7) / 6) ** 2 + ((z - 15) / 8) ** 2))
    rise += 0.2 * math.exp(-(((x - 33) / 6) ** 2 + ((z - 28) / 9) ** 2))
    return 1 + fall + swale + rise


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "examples/ecosystem/meadow.asc"
    with open(out, "w") as f:
        f.write("ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g\n" % (N, N, CELL))
        for k in range(N):  # row 0 is the north
            f.write(" ".join("%.3f" % height((i + 0.5) * CELL, (k + 0.5) * CELL) for i in range(N)) + "\n")


if __name__ == "__main__":
    main()
