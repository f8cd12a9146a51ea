#!/usr/bin/env python3
"""A tree's habit measured on its skeleton (a `sylva skeleton` CSV), against bands a species
must fall in: nothing below the ground; the trunk's tip high in the tree; the trunk near the
vertical through its foot; crown width over height; the share of twigs that hang.
Usage: habit.py T.csv [--ratio LO HI] [--trunk-tip F] [--lean MAX] [--hanging LO HI];
prints the measures, exit 1 naming each band missed."""
import argparse
import csv
import math
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("--ratio", nargs=2, type=float)
    ap.add_argument("--trunk-tip", type=float)
    ap.add_argument("--lean", type=float)
    ap.add_argument("--hanging", nargs=2, type=float)
    a = ap.parse_args()
    with open(a.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    pos = {r["id"]: (float(r["x"]), float(r["y"]), float(r["z"])) for r in rows}
    nodes = [r for r in rows if r["kind"] in ("root", "internode")]
    kids = {}
    for r in nodes:
        kids.setdefault(r["parent"], []).append(r)
    root = pos[nodes[0]["id"]]
    ys = [p[1] for p in pos.values()]
    height = max(ys) - root[1]
    width = max(max(p[i] for p in pos.values()) - min(p[i] for p in pos.values()) for i in (0, 2))
    trunk = [r for r in nodes if r["order"] == "0"]
    tip = max(pos[r["id"]][1] for r in trunk if not any(k["order"] == "0" for k in kids.get(r["id"], [])))
    lean = max(math.hypot(pos[r["id"]][0] - root[0], pos[r["id"]][2] - root[2]) for r in trunk)
    twigs = [r for r in nodes if r["kind"] == "internode" and r["id"] not in kids]
    hang = sum(pos[r["id"]][1] < pos[r["parent"]][1] for r in twigs) / max(1, len(twigs))
    m = {"lowest": min(ys) - root[1], "height": height, "width/height": width / height,
         "trunk tip/height": (tip - root[1]) / height, "lean/height": lean / height, "hanging twigs": hang}
    print("  ".join(f"{k} {v:.3g}" for k, v in m.items()))
    bad = []
    if m["lowest"] < -1e-4: bad.append("below the ground")
    if a.ratio and not a.ratio[0] <= m["width/height"] <= a.ratio[1]: bad.append("width/height")
    if a.trunk_tip is not None and m["trunk tip/height"] < a.trunk_tip: bad.append("trunk tip")
    if a.lean is not None and m["lean/height"] > a.lean: bad.append("lean")
    if a.hanging and not a.hanging[0] <= hang <= a.hanging[1]: bad.append("hanging twigs")
    for b in bad: print("out of band:", b)
    return 1 if bad else 0


sys.exit(main())
