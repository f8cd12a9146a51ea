#!/usr/bin/env python3
"""Words in Sylva's pictures, measured on the PNGs.

  labels.py names IMAGE.png N   a `sylva compare --image` picture: the ruler and the plants'
      names are drawn in one red (r > 150, g and b < 90). The ruler's pole is the column with
      the most red pixels, and all of the ruler (ticks, figures) lies left of it; right of it,
      the columns holding red pixels, in groups separated by empty columns, are the names.
      Prints "N names beside the ruler" when there are at least N such groups.
  labels.py legend MAP.png N    an ecosystem's map-YEAR.png: in its top left corner N rows of
      a swatch, each of another colour, beside white (240) letters on the dark legend box.
      Prints "legend of N species".
  labels.py colourmap MAP.png   a `sylva terrain --maps` NAME-colour.png: the map coloured (most
      of its pixels far from grey), and below it a light legend strip holding dark letters and
      the colour bar from the ramp's dark blue to its yellow. Prints "a coloured map with a legend".
Exit 1 otherwise."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import png, pixel  # noqa: E402  (tests/oracle/inspect.py)


def names(path, want):
    img = png(path)
    w, h = img[0], img[1]
    count = [sum((lambda p: p[0] > 150 and p[1] < 90 and p[2] < 90)(pixel(img, x, y)) for y in range(h)) for x in range(w)]
    red = [c > 0 for c in count]
    pole = max(range(w), key=lambda x: count[x])
    groups, x = 0, pole
    while x < w and red[x]:
        x += 1
    while x < w:
        if red[x]:
            groups += 1
            while x < w and red[x]:
                x += 1
        x += 1
    if groups < want:
        print("%d groups of red columns right of the ruler, %d names wanted" % (groups, want))
        sys.exit(1)
    print("%d names beside the ruler" % want)


def legend(path, want):
    img = png(path)
    s = 2 if img[0] >= 400 else 1
    swatches = set()
    for i in range(want):
        y0 = 3 * s + i * 10 * s
        swatches.add(pixel(img, 6 * s, y0 + 3 * s))
        letters = [pixel(img, x, y0 + y) for y in range(7 * s) for x in range(12 * s, 42 * s)]
        if (240, 240, 240) not in letters:
            print("no letters beside swatch %d" % i)
            sys.exit(1)
    if len(swatches) != want:
        print("%d swatch colours for %d species" % (len(swatches), want))
        sys.exit(1)
    print("legend of %d species" % want)


def colourmap(path):
    img = png(path)
    w, h = img[0], img[1]
    paper = lambda p: min(p) >= 245  # noqa: E731
    # the legend's first row: the first light one down the middle (no ramp colour is light)
    strip = next((y for y in range(h) if paper(pixel(img, w // 2, y))), h)
    legend = [pixel(img, x, y) for y in range(strip, h) for x in range(w)]
    ink = sum(max(p) < 60 and max(p) - min(p) < 20 for p in legend)
    blue = any(p[2] > p[0] + 40 and p[2] > p[1] + 40 and max(p) < 110 for p in legend)
    yellow = any(p[0] > 200 and p[1] > 180 and p[2] < 80 for p in legend)
    mapped = [pixel(img, x, y) for y in range(0, strip, 4) for x in range(0, w, 4)]
    coloured = sum(max(p) - min(p) > 30 for p in mapped)
    if not (strip < h - 10 and ink > 20 and blue and yellow):
        print("no legend below the map (strip from row %d, %d ink pixels, blue %s, yellow %s)" % (strip, ink, blue, yellow))
        sys.exit(1)
    if coloured < 0.5 * len(mapped):
        print("%d of %d map pixels coloured" % (coloured, len(mapped)))
        sys.exit(1)
    print("a coloured map with a legend")


if __name__ == "__main__":
    if sys.argv[1] == "colourmap":
        colourmap(sys.argv[2])
    else:
        {"names": names, "legend": legend}[sys.argv[1]](sys.argv[2], int(sys.argv[3]))
