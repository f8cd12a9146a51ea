"""The notebook view (docs/python.md): a plant, a mesh, a skeleton or an ecosystem snapshot as
an interactive 3D view in the three.js scene of `sylva view` (web/scene.js, web/notebook.js),
every asset inlined — three.js, its glTF loader and orbit controls, the .glb as base64 — so
that it draws offline and in an exported HTML file; with a PNG for frontends without HTML."""
from __future__ import annotations

import base64
import functools
import json
import os
import tempfile
import uuid

import numpy as np

_HERE = os.path.dirname(os.path.abspath(__file__))
# the checkout's web/ when the package runs in place (its latest edits), else the package's
# copy (python/setup.py puts it there)
_WEB_DIRS = (os.path.join(os.path.dirname(os.path.dirname(_HERE)), "web"), os.path.join(_HERE, "_web"))
_THREE = "node_modules/three/"
SOURCES = {  # module name in the loader: path under a web folder
    "three": _THREE + "build/three.module.min.js",
    "bgu": _THREE + "examples/jsm/utils/BufferGeometryUtils.js",
    "orbit": _THREE + "examples/jsm/controls/OrbitControls.js",
    "gltf": _THREE + "examples/jsm/loaders/GLTFLoader.js",
    "scene": "scene.js",
    "notebook": "notebook.js",
}
# Each module imported from a blob: URL, its import specifiers rewritten to the blob URLs of the
# modules before it (a blob has no base to resolve a relative path or an import map against).
_LOADER = """
(async () => {
  const el = document.getElementById(%(id)s);
  try {
    const src = JSON.parse(document.getElementById(%(id)s + '-js').textContent);
    const data = JSON.parse(document.getElementById(%(id)s + '-data').textContent);
    const key = '__sylva_' + src.key;
    if (!window[key]) {
      const url = (code) => URL.createObjectURL(new Blob([code], { type: 'text/javascript' }));
      const sub = (code, map) => code.replace(/(\\bfrom\\s*|\\bimport\\s*)(['"])([^'"]+)\\2/g,
        (m, a, q, spec) => (spec in map ? a + q + map[spec] + q : m));
      const three = url(src.three);
      const bgu = url(sub(src.bgu, { three }));
      const orbit = url(sub(src.orbit, { three }));
      const gltf = url(sub(src.gltf, { three, '../utils/BufferGeometryUtils.js': bgu }));
      const scene = url(sub(src.scene, { three, 'three/addons/controls/OrbitControls.js': orbit }));
      const nb = url(sub(src.notebook, { three, 'three/addons/loaders/GLTFLoader.js': gltf, './scene.js': scene }));
      window[key] = import(nb);
    }
    await (await window[key]).show(el, data);
    el.querySelector('img').style.display = 'none';
    el.querySelector('canvas').style.display = 'block';
  } catch (e) {
    el.querySelector('.sylva-msg').textContent = 'sylva: the 3D view failed (' + e + '); the picture is shown';
  }
})();
"""


def _web_dir() -> str:
    for d in _WEB_DIRS:
        if all(os.path.exists(os.path.join(d, p)) for p in SOURCES.values()):
            return d
    raise FileNotFoundError("the notebook view needs web/scene.js, web/notebook.js and three.js "
                            "(web/node_modules, `make deps`); looked in " + ", ".join(_WEB_DIRS))


@functools.lru_cache(maxsize=1)
def _sources_json() -> str:
    d = _web_dir()
    src = {}
    for name, rel in SOURCES.items():
        with open(os.path.join(d, rel), encoding="utf-8") as f:
            src[name] = f.read()
    with open(os.path.join(d, _THREE, "package.json"), encoding="utf-8") as f:
        three_version = json.load(f)["version"]
    from . import __version__
    src["key"] = f"{__version__}_{three_version}_{len(src['notebook']) + len(src['scene'])}".replace(".", "_")
    return _script_json(src)


def _script_json(obj) -> str:
    """JSON that may stand inside a <script> element: no '<' is left to close it."""
    return json.dumps(obj, separators=(",", ":")).replace("<", "\\u003c")


def html(data: dict, png: bytes, caption: str, height: int = 420) -> str:
    """The view's HTML: a canvas, the PNG shown until the view draws, the sources and data."""
    vid = "sylva-" + uuid.uuid4().hex
    img = base64.b64encode(png).decode("ascii")
    cap = caption.replace("&", "&amp;").replace("<", "&lt;")
    return (f'<div class="sylva-view" id="{vid}" style="position:relative;width:100%;max-width:760px">'
            f'<canvas style="display:none;width:100%;height:{height}px;border-radius:4px;cursor:grab"></canvas>'
            f'<img alt="{cap}" src="data:image/png;base64,{img}" style="max-height:{height}px">'
            f'<div class="sylva-msg" style="font:12px sans-serif;color:#555">{cap} — drag to turn, '
            f'scroll to zoom, right-drag to pan</div></div>\n'
            f'<script type="application/json" id="{vid}-js">{_sources_json()}</script>\n'
            f'<script type="application/json" id="{vid}-data">{_script_json(data)}</script>\n'
            f'<script>{_LOADER % {"id": json.dumps(vid)}}</script>')


def bundle(data: dict, png: bytes, caption: str) -> dict:
    """A mime bundle: the 3D view for HTML frontends, the picture for the others."""
    try:
        return {"text/html": html(data, png, caption), "image/png": png}
    except FileNotFoundError:
        return {"image/png": png}


def glb_data(plant_core) -> dict:
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "view.glb")
        plant_core.write(path)
        with open(path, "rb") as f:
            return {"glb": base64.b64encode(f.read()).decode("ascii")}


# ---- pictures without a renderer: a skeleton's lines, a snapshot's map ----

BACKGROUND = (220, 230, 239, 255)  # scene.js's sky
ORDER_COLOURS = np.array([[0x5a, 0x3a, 0x1a], [0xc0, 0x39, 0x2b], [0xe6, 0x7e, 0x22], [0x27, 0xae, 0x60],
                          [0x29, 0x80, 0xb9], [0x8e, 0x44, 0xad], [0x16, 0xa0, 0x85], [0x7f, 0x8c, 0x8d]], np.uint8)
SPECIES_COLOURS = (0x2e7d32, 0xc62828, 0x1565c0, 0xf9a825, 0x6a1b9a, 0x00838f, 0xef6c00, 0x4e342e)


def _fit(xy: np.ndarray, size: int, flip: bool) -> np.ndarray:
    lo, hi = xy.min(0), xy.max(0)
    scale = size * 0.9 / max(float((hi - lo).max()), 1e-9)
    px = (xy - (lo + hi) / 2) * scale + size / 2
    if flip:
        px[:, 1] = size - 1 - px[:, 1]
    return px


def lines_png(a: np.ndarray, b: np.ndarray, order: np.ndarray, size: int = 384) -> np.ndarray:
    """Segments a[i]-b[i] seen from the front (x right, y up), coloured by branching order."""
    img = np.empty((size, size, 4), np.uint8)
    img[:] = BACKGROUND
    if not len(a):
        return img
    px = _fit(np.concatenate([a[:, :2], b[:, :2]]).astype(np.float64), size, True)
    pa, pb = px[:len(a)], px[len(a):]
    n = np.ceil(np.abs(pb - pa).max(1)).astype(np.int64) + 1
    seg = np.repeat(np.arange(len(a)), n)
    t = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(np.maximum(n - 1, 1), n)
    p = np.rint(pa[seg] + (pb[seg] - pa[seg]) * t[:, None]).astype(np.int64).clip(0, size - 1)
    img[p[:, 1], p[:, 0], :3] = ORDER_COLOURS[np.minimum(order[seg], len(ORDER_COLOURS) - 1)]
    return img


def map_png(altitude: np.ndarray, xz: np.ndarray, species: np.ndarray, size: int = 384) -> np.ndarray:
    """A snapshot from above: the altitude in greys, each plant a dot of its species' colour."""
    nz, nx = altitude.shape
    a = altitude.astype(np.float64)
    g = (a - a.min()) / max(float(np.ptp(a)), 1e-9)
    rows = (np.arange(size) * nz // size).clip(0, nz - 1)
    cols = (np.arange(size) * nx // size).clip(0, nx - 1)
    grey = (120 + 100 * g[np.ix_(rows, cols)]).astype(np.uint8)
    img = np.empty((size, size, 4), np.uint8)
    img[..., :3] = grey[..., None]
    img[..., 3] = 255
    if len(xz):
        colours = np.array([[(c >> 16) & 255, (c >> 8) & 255, c & 255] for c in SPECIES_COLOURS], np.uint8)
        c = (xz * (size / np.array([nx, nz]))).astype(np.int64).clip(1, size - 2)
        r = (-1, 0, 1) if len(xz) < 5000 else (0,)  # a dense stand: one pixel a plant
        for dy in r:
            for dx in r:
                img[c[:, 1] + dy, c[:, 0] + dx, :3] = colours[species % len(colours)]
    return img
