"""The notebook view (docs/python.md, python/sylva/_view.py) and the slider panel: what a
notebook is handed, checked against the writers' own bytes and the runs' own counts. That a
browser draws it is tests/view/notebook.test.mjs's (tests/run-python)."""
import base64
import json
import os
import re
import struct

import numpy as np
import pytest

import sylva
from sylva import _view

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def ex(*p):
    return os.path.join(ROOT, "examples", *p)


def png_size(data: bytes):
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])  # IHDR: width, height


def script(html: str, suffix: str):
    m = re.search(r'<script type="application/json" id="sylva-[0-9a-f]+-' + suffix + r'">(.*?)</script>', html, re.S)
    assert m, suffix
    return json.loads(m.group(1))


@pytest.fixture(scope="module")
def plant():
    return sylva.load(ex("abop", "fig1_24e_plant.syl")).model.build(4)


def test_a_plant_inlines_three_js_its_glb_and_a_picture(plant, tmp_path):
    b = plant._repr_mimebundle_()
    assert png_size(b["image/png"]) == (384, 384)
    html = b["text/html"]
    src = script(html, "js")
    with open(os.path.join(_view._web_dir(), _view.SOURCES["three"]), encoding="utf-8") as f:
        assert src["three"] == f.read()  # three.js itself, not a link to it
    assert set(src) >= set(_view.SOURCES)
    assert "</script" not in html.split('-js">', 1)[1].split("</script>", 1)[0]  # the sources cannot close it
    plant.mesh.save(tmp_path / "p.glb")
    assert base64.b64decode(script(html, "data")["glb"]) == (tmp_path / "p.glb").read_bytes()
    assert not re.search(r'\bsrc="(?!data:)', html)  # nothing loaded from elsewhere
    assert plant.mesh._repr_mimebundle_()["image/png"] == b["image/png"]


def test_a_model_draws_its_plant():
    m = sylva.compile("lsystem T {\n derive 2\n axiom F\n F -> F[+F]F\n}\n").model
    data = script(m._repr_mimebundle_()["text/html"], "data")
    assert base64.b64decode(data["glb"])[:4] == b"glTF"


def test_a_skeleton_is_its_lines(plant):
    sk = plant.skeleton
    b = sk._repr_mimebundle_()
    assert script(b["text/html"], "data")["csv"] == sk.csv()
    pic = sk.picture(200)
    assert pic.shape == (200, 200, 4)
    drawn = (pic[..., :3] != _view.BACKGROUND[:3]).any(2)
    # one segment a node with a parent: a tree of 1 + (segments) nodes, all joined, so the drawn
    # pixels are one 8-connected piece from the root up
    assert len(sk._segments()[0]) == int((sk.parent >= 0).sum()) > 0
    assert drawn.sum() > 200
    colours = {tuple(c) for c in pic[drawn][:, :3]}
    assert colours <= {tuple(c) for c in _view.ORDER_COLOURS}
    assert len(colours) == min(int(sk.order.max()) + 1, len(_view.ORDER_COLOURS))


def test_a_snapshot_is_its_plants_on_the_terrain():
    run = sylva.load(ex("ecosystem", "meadow.syl")).model.run(3)
    year = max(run._snaps)
    snap = run.snapshot(year)
    data = script(snap._repr_mimebundle_()["text/html"], "data")
    p = run.plants(year)
    assert len(data["plants"]) == len(p) == len(snap.plants)
    np.testing.assert_allclose([r[3] for r in data["plants"]], p["height"], atol=1e-3)
    t = data["terrain"]
    assert len(t["heights"]) == t["nx"] * t["nz"]
    alt = run.terrain["altitude"]
    assert t["nx"] <= sylva.Snapshot.MAX_SIDE and min(t["heights"]) >= alt.min() - 1e-3
    assert png_size(snap._repr_png_()) == (384, 384)
    with pytest.raises(KeyError):
        run.snapshot(year + 1000)


def test_an_ecosystem_model_shows_its_last_snapshot():
    m = sylva.load(ex("ecosystem", "meadow.syl")).model
    shown = script(m._repr_mimebundle_()["text/html"], "data")
    run = m.run()
    last = run.plants(max(run._snaps))
    assert len(shown["plants"]) == len(last) > 0
    np.testing.assert_allclose(sorted(r[3] for r in shown["plants"]), np.sort(last["height"]), atol=1e-3)


def test_without_the_assets_the_picture_alone(plant, monkeypatch):
    monkeypatch.setattr(_view, "_WEB_DIRS", ("/nonexistent",))
    _view._sources_json.cache_clear()
    try:
        assert set(plant._repr_mimebundle_()) == {"image/png"}
    finally:
        _view._sources_json.cache_clear()


def test_sliders_rebuild_with_their_values():
    pytest.importorskip("ipywidgets")
    m = sylva.load(ex("abop", "fig1_24e_plant.syl")).model
    panel = m.interact(3, size=32)
    s = panel.sliders
    assert "angle" in s and "seed" not in s and "derive" not in s  # steps given: no derive slider
    assert s["angle"].min <= m.setting("angle") <= s["angle"].max
    assert s["width"].min >= m.params["width"].min
    s["angle"].value = 40
    assert panel.overrides["angle"] == 40
    want = m.build(3, **panel.overrides).skeleton.positions
    np.testing.assert_array_equal(panel.plant.skeleton.positions, want)
    with pytest.raises(ValueError):
        m.interact(view="vr")
