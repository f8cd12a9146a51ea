#!/usr/bin/env python3
"""Write the example DEM, a valley with slopes of every aspect, as a 16-bit greyscale PNG.

  make_valley.py [SIZE [OUT.png]]      (default 256, examples/ecosystem/valley.png)

Standard library only. On the unit square (x east, z south): a round basin centred at
(0.5, 0.42) whose sides face every way (1 - exp(-(r / 0.3)^2)), an outlet valley from it down
to the southern edge,
two hills, and a few octaves of value noise for texture. Heights 0..65535 map to the range
given to `sylva terrain --heights`: docs/terrain.md uses 200,1400 with --cell 25 (the 25 m
cells of the Slovenian DEM Zamuda's thesis used).
"""
import math
import struct
import sys
import zlib


def lattice(i, k, seed):
    """A fixed pseudo-random value in 0..1 for a lattice point (an integer hash)."""
    h = (i * 374761393 + k * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65535.0


def value_noise(x, z, seed):
    i, k = math.floor(x), math.floor(z)
    fx, fz = x - i, z - k
    sx, sz = fx * fx * (3 - 2 * fx), fz * fz * (3 - 2 * fz)
    a, b = lattice(i, k, seed), lattice(i + 1, k, seed)
    c, d = lattice(i, k + 1, seed), lattice(i + 1, k + 1, seed)
    return (a + (b - a) * sx) * (1 - sz) + (c + (d - c) * sx) * sz


def height(x, z):
    r = math.hypot(x - 0.5, z - 0.42)
    basin = 1 - math.exp(-((r / 0.3) ** 2))
    # the outlet: a trough from the basin's centre to the south edge, deeper downstream
    if z > 0.42:
        w = 0.06 + 0.05 * (z - 0.42)
        basin -= (0.55 + 0.35 * (z - 0.42)) * math.exp(-(((x - 0.5 - 0.08 * math.sin(6 * z)) / w) ** 2)) * min(1, (z - 0.42) / 0.15)
    hills = 0.35 * math.exp(-((x - 0.18) ** 2 + (z - 0.8) ** 2) / 0.01) + 0.3 * math.exp(-((x - 0.85) ** 2 + (z - 0.75) ** 2) / 0.015)
    noise = sum(value_noise(x * 6 * 2 ** o, z * 6 * 2 ** o, o) * 0.5 ** o for o in range(4)) / 1.875
    return 0.62 * basin + hills + 0.05 * noise


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 256
    out = sys.argv[2] if len(sys.argv) > 2 else "examples/ecosystem/valley.png"
    h = [[height((i + 0.5) / size, (k + 0.5) / size) for i in range(size)] for k in range(size)]
    lo = min(min(r) for r in h)
    hi = max(max(r) for r in h)
    raw = b"".join(b"\0" + struct.pack(">%dH" % size, *(round((v - lo) / (hi - lo) * 65535) for v in r)) for r in h)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 16, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(out, "wb") as f:
        f.write(png)


main()
