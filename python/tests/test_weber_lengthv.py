"""Weber–Penn lengths at level 2 and deeper against Arbaro's law (docs/weberpenn.md): each
stem draws its children's most length once, Length ± LengthV of their level, so a level-2 stem
is that draw × (its parent's length − 0.6 × its offset on the parent): the ratio lies within
Length ± LengthV, is the same for the children of one parent, and varies from parent to parent
when LengthV > 0; with LengthV = 0 it is Length itself. Measured on the skeleton (the stems'
polylines), a few ms a tree."""
import numpy as np
import pytest

import sylva

MODEL = """weber t {{
  convention arbaro
  Levels 3
  Scale 10
  BaseSize 0.2
  0BaseSplits 0
  Leaves 0
  Length 1 0.5 {l2} 0.4
  LengthV 0 0 {v2} 0
  Branches 1 8 5 0
  CurveRes 4 4 3 1
  SegSplits 0 0 0 0
  Taper 1 1 1 1
  Flare 0
}}
"""


def ratios(l2: float, v2: float, seed: int) -> dict[int, list[float]]:
    """{level-1 stem's axis: [length / (its length − 0.6 offset) of each level-2 child]}."""
    sk = sylva.compile(MODEL.format(l2=l2, v2=v2)).model.skeleton(seed=seed)
    n = sk.nodes
    pos = n["pos"].astype(np.float64)
    step = np.where(n["parent"] >= 0, np.linalg.norm(pos - pos[np.maximum(n["parent"], 0)], axis=1), 0.0)
    along = np.zeros(len(n))  # distance from the node's axis's base, along the axis
    length: dict[int, float] = {}
    first: dict[int, int] = {}
    for i in range(len(n)):  # a parent comes before its children
        a, p = int(n["axis"][i]), int(n["parent"][i])
        if n["kind"][i] not in (0, 1):
            continue
        if a not in first:
            first[a] = i
            along[i] = step[i]  # from the attachment on the parent
        else:
            along[i] = along[p] + step[i]
        length[a] = max(length.get(a, 0.0), along[i])
    out: dict[int, list[float]] = {}
    for a, i in first.items():
        if n["order"][i] != 2:
            continue
        host = int(n["parent"][i])
        pa = int(n["axis"][host])
        offset = along[host]
        out.setdefault(pa, []).append(length[a] / (length[pa] - 0.6 * offset))
    return out


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_level2_lengths_vary_per_parent_within_arbaros_bounds(seed):
    r = ratios(0.5, 0.2, seed)
    assert len(r) >= 4
    per_parent = [np.mean(v) for v in r.values()]
    for v in r.values():
        assert max(v) - min(v) < 1e-3 * max(v)  # one draw per parent
    assert 0.3 - 1e-3 <= min(per_parent) and max(per_parent) <= 0.7 + 1e-3
    assert max(per_parent) - min(per_parent) > 0.02  # drawn per parent, not once


def test_level2_lengths_without_lengthv_are_length():
    for v in ratios(0.5, 0.0, 1).values():
        assert np.allclose(v, 0.5, rtol=1e-3)
