#!/usr/bin/env python3
"""Properties of a grown skeleton (`sylva grow -o t.csv`) that follow from its grow block,
whatever the growth did: one root at the origin; every internode exactly one internode length
from its parent; radii never larger than the parent's (pipe model: a branch carries its
children); every organ on an internode.
   Usage: skeleton_check.py FILE.csv INTERNODE    prints what holds, one line each
"""

import csv
import math
import sys


def main():
    rows = list(csv.DictReader(open(sys.argv[1], encoding="utf-8")))
    length = float(sys.argv[2])
    nodes = {r["id"]: r for r in rows if r["kind"] in ("root", "internode")}
    roots = [r for r in nodes.values() if r["parent"] == "-1"]
    at = lambda r: [float(r[k]) for k in "xyz"]
    print("one root at the origin" if len(roots) == 1 and at(roots[0]) == [0, 0, 0] else "roots: %d" % len(roots))
    inter = [r for r in nodes.values() if r["kind"] == "internode"]
    # CSV coordinates have 6 significant digits
    tol = lambda r: 1e-5 * max([1.0] + [abs(c) for c in at(r) + at(nodes[r["parent"]])])
    off = [r["id"] for r in inter if abs(math.dist(at(r), at(nodes[r["parent"]])) - length) > tol(r)]
    print("internodes %g long" % length if inter and not off else "%d internodes not %g long" % (len(off), length))
    wider = [r["id"] for r in inter if float(r["radius"]) > float(nodes[r["parent"]]["radius"]) * (1 + 1e-6)]
    print("no branch wider than its parent" if not wider else "%d wider than their parent" % len(wider))
    organs = [r for r in rows if r["kind"] not in ("root", "internode")]
    loose = [r["id"] for r in organs if nodes.get(r["parent"], {}).get("kind") != "internode"]
    print("every organ on an internode" if organs and not loose else "%d organs, %d loose" % (len(organs), len(loose)))


if __name__ == "__main__":
    main()
