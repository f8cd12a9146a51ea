#!/usr/bin/env python3
"""Check a `sylva animate` frame directory with the PNG reader of inspect.py (standard
library only), so that the cases test what the pictures show.

  frames.py count DIR        "N frames WxH" when DIR holds frame_0000.png .. frame_{N-1}.png,
                             every one a PNG of that size, and nothing else named frame_*
  frames.py grows DIR        "camera fixed" when the leftmost and rightmost pixel columns
                             (far from a plant in the middle) are the same in every frame;
                             "plant grows" when the pixels that differ from frame 0 (by more
                             than 24 in a channel) are never fewer than in the frame before,
                             and more in the last frame than in the first
  frames.py pulls DIR        "horizon steady" when the horizon (framing.py) lies within 5% of
                             the height in every frame: the camera pulls back, it does not turn;
                             "plant readable" when in every frame but the first the plant
                             rises above the horizon to the top 35% of the picture (the first
                             may be empty: an axiom that draws nothing)
  frames.py corner A B       "only the top left corner changed" when the pixels where A and B
                             differ all lie in the top left 1/4 x 1/4 of the picture (and
                             some do)
Exit status 1, with the reason, when the files are not what they claim to be.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from inspect import fail, png  # noqa: E402  (tests/oracle/inspect.py, not the standard module)


def frames(d):
    names = sorted(n for n in os.listdir(d) if n.startswith("frame_"))
    want = ["frame_%04d.png" % i for i in range(len(names))]
    if names != want:
        fail("frame files are not frame_0000.png .. in order: %s" % names[:5])
    return [png(os.path.join(d, n)) for n in names]


def rgb_rows(img):
    w, h, bpp, rows = img
    return [bytes(r[x * bpp + c] for x in range(w) for c in range(3)) for r in rows]


def main():
    what = sys.argv[1]
    if what == "count":
        imgs = frames(sys.argv[2])
        sizes = {(i[0], i[1]) for i in imgs}
        if len(sizes) != 1:
            fail("frames of several sizes: %s" % sorted(sizes))
        w, h = sizes.pop()
        print("%d frames %dx%d" % (len(imgs), w, h))
    elif what == "grows":
        imgs = [rgb_rows(i) for i in frames(sys.argv[2])]
        w = len(imgs[0][0]) // 3
        col = lambda rows, x: bytes(r[3 * x + c] for r in rows for c in range(3))  # noqa: E731
        fixed = all(col(f, x) == col(imgs[0], x) for f in imgs for x in (0, w - 1))
        print("camera fixed" if fixed else "camera moved: an edge column changed")
        base = imgs[0]
        counts = []
        for f in imgs:
            n = 0
            for ra, rb in zip(base, f):
                for x in range(w):
                    if max(abs(ra[3 * x + c] - rb[3 * x + c]) for c in range(3)) > 24:
                        n += 1
            counts.append(n)
        grows = all(b >= a for a, b in zip(counts, counts[1:])) and counts[-1] > counts[0]
        print("plant grows" if grows else "plant pixels per frame: %s" % counts)
    elif what == "pulls":
        from framing import measure_image
        m = [measure_image(i) for i in frames(sys.argv[2])]
        steady = max(h for h, _, _ in m) - min(h for h, _, _ in m) <= 0.05  # the ground ends 40 sizes away: a row or two
        print("horizon steady" if steady else "horizon rows: %s" % [round(h, 2) for h, _, _ in m])
        tops = [t for _, t, _ in m[1:]]
        print("plant readable" if all(t <= 0.35 for t in tops) else "plant's top per frame: %s"
              % [round(t, 2) for t in tops])
    elif what == "corner":
        a, b = png(sys.argv[2]), png(sys.argv[3])
        if (a[0], a[1]) != (b[0], b[1]):
            fail("pictures of different sizes")
        w, h = a[0], a[1]
        ra, rb = rgb_rows(a), rgb_rows(b)
        xs, ys = [], []
        for y in range(h):
            for x in range(w):
                if ra[y][3 * x:3 * x + 3] != rb[y][3 * x:3 * x + 3]:
                    xs.append(x)
                    ys.append(y)
        if not xs:
            print("no pixel changed")
        elif max(xs) < w // 4 and max(ys) < h // 4:
            print("only the top left corner changed")
        else:
            print("changed up to %d,%d of %dx%d" % (max(xs), max(ys), w, h))
    else:
        fail("unknown check " + what)


if __name__ == "__main__":
    main()
