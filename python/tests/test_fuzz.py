"""The binding's argument handling under wrong values: every public call, every argument given
each value of a fixed set of wrong types and edge values. Only Python exceptions may come out
(a crash would end the interpreter, and pytest with it); right values must still work after."""
import itertools
import math
import os

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# Wrong types and edges. Whole numbers stay small where they are valid (3): a valid huge step
# count or sample count is a long run, not a wrong argument.
VALUES = [None, True, -1, 0, 3, 2 ** 64, -2 ** 70, 1.5, math.nan, math.inf, -math.inf, "", "F", "x" * 5000,
          "a\x00b", "é", b"F", bytearray(b"F"), [], [1, "a"], {}, {"f": 1}, (1, 2), (0, 0), object(),
          np.int64(3), np.float32(2.5), np.array([1, 2]), lambda *a: 0, sylva]


def survive(fn, *args, **kw):
    try:
        fn(*args, **kw)
    except Exception:  # noqa: BLE001: any Python exception is an answer; a crash is not
        pass


LSYS = "lsystem L {\n derive 2\n extern f(x) = x\n axiom A(1) ?E(2, 0)\n A(x) -> F(f(x)) [+A(x/2)] A(x)\n}\n"


@pytest.fixture(scope="module")
def things():
    m = sylva.compile(LSYS).model
    return m, m.derive(2), m.build(2)


def test_module_calls():
    for v in VALUES:
        survive(sylva.load, v)
        survive(sylva.compile, v)
        survive(sylva.compile, LSYS, name=v)
        survive(sylva.compile, LSYS, angle=v)
        survive(sylva.compile, LSYS, **{"x" * 300: v})
        survive(sylva.compare, v)
        survive(sylva._core.png_rgba, v, 1, 1)
        survive(sylva._core.png_rgba, b"\0" * 4, v, 1)
        survive(sylva._core.compile, v)
        survive(sylva._core.compile, "p", LSYS, None, v)


def test_model_calls(things):
    m, _, _ = things
    derive_kw = ["seed", "threads", "max_modules", "max_memory", "environment", "functions"]
    build_kw = ["until", "seed", "threads", "max_modules", "max_memory", "scene", "leaves", "sides", "age",
                "one_sided", "optimize", "functions"]
    for v in VALUES:
        survive(m.derive, v)
        for k in derive_kw:
            survive(m.derive, 1, **{k: v})
        survive(m.build, v)
        for k in build_kw:
            survive(m.build, 1, **{k: v})
        survive(m.derive, 1, angle=v)
        survive(m.derive, 1, functions={"f": v})
        survive(m.derive, 1, environment=lambda step, q, v=v: q.params.__setitem__(slice(None), v))
        survive(m.derive, 1, functions={"f": lambda x, v=v: v})
        survive(m.setting, v)
        survive(m.render, v, 0)  # 0 wide: everything is read and checked, nothing rendered
        survive(m.interact, 1, size=v, view=None)  # read and refused before any widget is made
        survive(m.run, v)
        survive(m.save, v)
        survive(m.file.__getitem__, v)


def test_result_calls(things, tmp_path):
    _, s, plant = things
    for v in VALUES:
        survive(s.__getitem__, v)
        survive(s.params, v)
        survive(s.params, "F", v)
        survive(plant.render, v, 0)
        survive(plant.render, 0, v)
        for k in ["view", "samples", "transparent", "threads"]:
            survive(plant.render, 0, 8, **{k: v})
        survive(plant.metrics, v)
        survive(plant.mesh.save, v)
        survive(plant.skeleton.picture, v)
        survive(plant._core.write, v)
        survive(plant._core.render, v)
        survive(s._core.gather, v, v)
        survive(s._core.module, v)


def test_ecosystem_calls():
    m = sylva.load(os.path.join(ROOT, "examples", "ecosystem", "meadow.syl")).model
    # the values a run accepts are the other tests' (each a run of the meadow's terrain)
    wrong = [v for v in VALUES if not (v is None or isinstance(v, (int, np.integer, tuple)) and not isinstance(v, bool)
                                       and np.all(np.asarray(v) >= 0) and np.all(np.asarray(v) < 2 ** 32))]
    for k, v in itertools.product(["seed", "snapshots", "threads", "max_plants", "tiles"], wrong):
        survive(m.run, 1, **{"max_plants": 1, k: v})  # a limit of one plant: each run stops at once
    run = m.run(1, snapshots=[1])
    for v in VALUES:
        survive(run.snapshot, v)
        survive(run.plants, v)


def test_still_right_after(things):
    m, _, _ = things
    s = m.derive(2, functions={"f": lambda x: x})
    assert len(s) == len(m.derive(2))
