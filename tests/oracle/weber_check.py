#!/usr/bin/env python3
"""Checks of a Weber-Penn tree's skeleton (sylva skeleton -o t.json) against independent
figures: Arbaro's measured counts and sizes, and the model's own formulas.

  weber_check.py counts T.json STEMS LEAVES PCT      stems (clones included) and leaves
                                                     within PCT % of the given figures
  weber_check.py levels T.json N0/N1/...             stems per level, exactly
  weber_check.py size T.json HEIGHT WIDTH PH PW      Arbaro's height (top of the stem axes)
                                                     and width (farthest corner of their
                                                     bounding box from the axis) within PH, PW %
  weber_check.py species T.json STEMS LEAVES PCT HEIGHT WIDTH PH PW
                                                     counts, then size, of one reading of T.json
  weber_check.py fan T.json N                        N leaves on every last-level stem
  weber_check.py quality T.json Q.json Q             leaf sizes of both; Q.json has Q times the leaves
  weber_check.py inside T.json A Y0 Y1               branch nodes inside |x|, |z| <= A, Y0 <= y <= Y1
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


def check_counts(nodes, organs, stems_want, leaves_want, pct):
    stems, _ = per_level(nodes)
    within('stems', stems, float(stems_want), float(pct))
    within('leaves', len(organs), float(leaves_want), float(pct))


def check_size(nodes, height, width, ph, pw):
    # Sylva is Y up; Arbaro's height is the highest axis point, its width the farthest
    # corner of the axes' horizontal bounding box
    xs = [n['x'] for n in nodes]; ys = [n['y'] for n in nodes]; zs = [n['z'] for n in nodes]
    h = max(ys)
    w = math.sqrt(max(min(xs) ** 2 + min(zs) ** 2, max(xs) ** 2 + max(zs) ** 2))
    within('height', h, float(height), float(ph))
    within('width', w, float(width), float(pw))


def main():
    mode, path = sys.argv[1], sys.argv[2]
    nodes, organs = load(path)
    if mode == 'counts':
        check_counts(nodes, organs, *sys.argv[3:6])
    elif mode == 'species':  # a species file's skeleton: the JSON read once for both checks
        check_counts(nodes, organs, *sys.argv[3:6])
        check_size(nodes, *sys.argv[6:10])
    elif mode == 'levels':
        _, per = per_level(nodes)
        print('/'.join(str(x) for x in per))
    elif mode == 'size':
        check_size(nodes, *sys.argv[3:7])
    elif mode == 'fan':  # every last-level stem has exactly N leaves
        n = int(sys.argv[3])
        axes = {x['axis']: x['order'] for x in nodes}
        last = max(axes.values())
        stems = sum(1 for o in axes.values() if o == last)
        print(f"{len(organs)} leaves on {stems} stems: " + ("%d each" % n if len(organs) == n * stems and stems else "not %d each" % n))
    elif mode == 'quality':  # T.json is LeafQuality 1, sys.argv[3] the same tree with q
        other, q = load(sys.argv[3])[1], float(sys.argv[4])
        size = sorted({round(o['size'], 6) for o in organs}), sorted({round(o['size'], 6) for o in other})
        print('sizes', size[0], size[1])
        r = len(other) / len(organs)
        print('count ratio %s' % ('within 10%% of %g' % q if abs(r / q - 1) <= 0.1 else r))
    elif mode == 'inside':  # every node of order >= 1 inside the box x, z in [-a, a], y in [y0, y1]
        a, y0, y1 = float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
        e = 1e-3
        branch = [x for x in nodes if x['order'] >= 1]
        out = [x for x in branch if not (abs(x['x']) <= a + e and abs(x['z']) <= a + e and y0 - e <= x['y'] <= y1 + e)]
        print(f"{'over 20' if len(branch) > 20 else len(branch)} branch nodes, {len(out)} outside")
    else:
        sys.exit('unknown mode ' + mode)


main()
