#!/usr/bin/env python3
"""How a plant's picture is framed, measured on the PNG alone (a sylva render or an animate
frame: a plant on a grass ground under a blue sky). Sky pixels are blue-most (b >= r, g);
the horizon is the first row, from the top, where the picture's left and right edges stop
being sky; the plant's top is the first row with a non-sky pixel in the middle three fifths.

  framing.py PNG... [--horizon LO HI] [--top MAX] [--width MIN]
     horizon row / height in [LO, HI] (an eye-level view shows its horizon inside the frame);
     the plant's top row / height at most MAX (the plant reaches up the frame: readable);
     the plant's widest row against the sky at least MIN of the width.
Prints the measures per picture; exit 1 when one is out of its band."""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import png, pixel  # noqa: E402  (tests/oracle/inspect.py)


def sky(p):
    return p[2] >= p[0] and p[2] >= p[1]


def measure(path):
    return measure_image(png(path))


def measure_image(img):
    w, h = img[0], img[1]
    edge = [next((y for y in range(h) if not sky(pixel(img, x, y))), h) for x in (0, w - 1)]
    horizon = min(edge)
    top = next((y for y in range(horizon) if any(not sky(pixel(img, x, y)) for x in range(w // 5, w - w // 5))),
               horizon)
    widest = 0
    for y in range(top, horizon - max(2, h // 25)):
        xs = [x for x in range(w) if not sky(pixel(img, x, y))]
        if xs: widest = max(widest, xs[-1] - xs[0] + 1)
    return horizon / h, top / h, widest / w


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("png", nargs="+")
    ap.add_argument("--horizon", nargs=2, type=float)
    ap.add_argument("--top", type=float)
    ap.add_argument("--width", type=float)
    a = ap.parse_args()
    bad = 0
    for path in a.png:
        hz, top, wid = measure(path)
        out = []
        if a.horizon and not a.horizon[0] <= hz <= a.horizon[1]: out.append("horizon")
        if a.top is not None and top > a.top: out.append("plant's top")
        if a.width is not None and wid < a.width: out.append("plant's width against the sky")
        print("%s: horizon %.2f  plant's top %.2f  widest %.2f%s" % (os.path.basename(path), hz, top, wid,
              "  OUT OF BAND: " + ", ".join(out) if out else ""))
        bad += bool(out)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
