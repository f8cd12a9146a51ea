#!/usr/bin/env python3
"""Checks of a Weber-Penn tree's skeleton (sylva skeleton -o t.json) against independent
figures: Arbaro's measured counts and sizes, and the model's own formulas.

  weber_check.py counts T.json STEMS LEAVES PCT      stems (clones included) and leaves
                                                     within PCT % of the given figures
  weber_check.py levels T.json N0/N1/...             stems per level, exactly
  weber_check.py size T.json HEIGHT WIDTH PH PW      Arbaro's height (top of the stem axes)
                                                     and width (farthest corner of their
                                                     bounding box from the axis) within PH, PW %
"""
import json, math, sys


def load(path):
    d = json.load(open(path))
    return d['nodes'], d.get('organs', [])


def per_level(nodes):
    axes = {}
    for n in nodes:
        axes.setdefault(n['axis'], n['order'])
    per = {}
    for o in axes.values():
        per[o] = per.get(o, 0) + 1
    return len(axes), [per.get(i, 0) for i in range(max(per) + 1)] if per else []


def within(what, got, want, pct):
    off = abs(got - want) / want * 100 if want else (0 if got == 0 else 100)
    if off <= pct:
        print(f"{what} within {pct:g}% of {want:g}")
    else:
        print(f"{what} {got:g}, {off:.1f}% from {want:g} (more than {pct:g}%)")


def main():
    mode, path = sys.argv[1], sys.argv[2]
    nodes, organs = load(path)
    if mode == 'counts':
        stems, _ = per_level(nodes)
        within('stems', stems, float(sys.argv[3]), float(sys.argv[5]))
        within('leaves', len(organs), float(sys.argv[4]), float(sys.argv[5]))
    elif mode == 'levels':
        _, per = per_level(nodes)
        print('/'.join(str(x) for x in per))
    elif mode == 'size':
        # Sylva is Y up; Arbaro's height is the highest axis point, its width the farthest
        # corner of the axes' horizontal bounding box
        xs = [n['x'] for n in nodes]; ys = [n['y'] for n in nodes]; zs = [n['z'] for n in nodes]
        h = max(ys)
        w = math.sqrt(max(min(xs) ** 2 + min(zs) ** 2, max(xs) ** 2 + max(zs) ** 2))
        within('height', h, float(sys.argv[3]), float(sys.argv[5]))
        within('width', w, float(sys.argv[4]), float(sys.argv[6]))
    else:
        sys.exit('unknown mode ' + mode)


main()
