"""Tables are pandas DataFrames when pandas is importable and numpy record arrays otherwise
(docs/python.md): both ways hold the same columns and values."""
import os
import sys

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def tables():
    plant = sylva.load(os.path.join(ROOT, "examples", "abop", "fig1_24e_plant.syl")).model
    run = sylva.load(os.path.join(ROOT, "examples", "ecosystem", "meadow.syl")).model.run(3, snapshots=[3])
    return {"compare": sylva.compare(plant, seeds=[1, 2], steps=3), "years": run.years,
            "snapshot": run.snapshots[3]}


def columns(t):
    return list(t.columns) if hasattr(t, "columns") else list(t.dtype.names)


def test_pandas_and_numpy_tables_agree(monkeypatch):
    pd = pytest.importorskip("pandas")
    with_pd = tables()
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now raises ImportError
    without = tables()
    for name, t in with_pd.items():
        r = without[name]
        assert isinstance(t, pd.DataFrame) and isinstance(r, np.recarray), name
        assert columns(t) == columns(r) and len(t) == len(r), name
        for c in columns(t):
            a, b = np.asarray(t[c]), np.asarray(r[c])
            if a.dtype.kind in "fc":
                np.testing.assert_allclose(a, b, err_msg=f"{name}.{c}")
            else:
                assert [str(x) for x in a] == [str(x) for x in b], f"{name}.{c}"


def test_record_arrays_without_pandas(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    t = tables()
    assert all(isinstance(v, np.recarray) for v in t.values())
    assert list(t["compare"]["seed"]) == [1, 2] and set(t["compare"]["model"]) == {"Plant1_24e"}
    assert (t["snapshot"]["height"] > 0).all()
